"""contact2d's Python package: read, run, compare and plot contact2d runs (docs/postproc.md).

    from contact2d import open_run
    with open_run("out.h5") as run:
        run.history("time"), run.contact("pressure"), run.units("final/contact/pressure")

Modules:
    h5                the output file reader (Run, open_run, parse_effective_deck; docs/output.md)
    runner            run contact2d from Python (find_exe, run, reuse of finished runs)
    outfile           never-overwrite, atomic writing of the tools' own products
    compare           SPEC section 9 errors between two runs on nested meshes
    fem_q1            Q1 plane-strain element algebra (stiffness, strain energy, prolongation)
    plot              one run's contact fields and histories as PNG figures
    hertz, lame       Hertz contact and Lame's thick cylinder: closed forms and run measures
    cattaneo_mindlin  Cattaneo-Mindlin partial slip closed forms; mindlin measures a run
    impact            the exact 1D wave solution of the impact bar and its run measures
    getfem_reference, getfem_coulomb   the GetFEM static and quasi-static Coulomb references
    calculix          CalculiX (ccx) on the Hertz half-disk: input from a run, solve, read back
    chart             the speed-accuracy table's columns and measures

Scripts in postproc/ import it (Python searches a script's own folder first); elsewhere set
PYTHONPATH=<repository>/postproc. `python3 -m contact2d <command>` lists the commands.
"""
__all__ = ["Run", "RunFileError", "open_run", "parse_effective_deck"]


def __getattr__(name):
    """The reader's names, imported on first use (PEP 562), so that modules needing only the
    standard library (outfile, runner) import without h5py."""
    if name in __all__:
        from . import h5
        return getattr(h5, name)
    raise AttributeError("module 'contact2d' has no attribute %r" % name)
