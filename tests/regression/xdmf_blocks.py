"""ParaView helpers of check_xdmf_paraview*.py (pvpython only): the sidecar's grids as blocks.

The sidecar holds several grids (final, contact_final, and with snapshots the temporal
collections snapshots and contact_snapshots; docs/output.md), so ParaView's XDMF reader gives a
multiblock data set with one block per grid, named after it.
"""


def block(data, name):
    """The block named `name` of a fetched reader output (the data set itself if it is not
    composite and `name` is 'final'), or None."""
    if not data.IsA("vtkMultiBlockDataSet"):
        return data if name == "final" else None
    for i in range(data.GetNumberOfBlocks()):
        meta = data.GetMetaData(i) if data.HasMetaData(i) else None
        if meta is not None and meta.Get(data.NAME()) == name:
            return data.GetBlock(i)
    return None
