"""Open a Gmsh scene's XDMF sidecar in ParaView (pvpython) and check what a user would see.

    pvpython check_xdmf_paraview_scene.py <contact2d> <deck> <workdir>

Runs the deck, reads <out>.xmf with ParaView's XDMF reader and checks: the numbers of points and
quadrilaterals the program reported on its 'mesh from <file>: N Q1 elements, M nodes' line, a
3-component displacement with a non-zero range, the element stress array, and that Warp By
Vector moves the bounds (all on the sidecar's `final` block, xdmf_blocks.py). (the structured-mesh check is check_xdmf_paraview.py.)
Not run where ParaView is not installed.
"""
import os
import re
import subprocess
import sys

from paraview.simple import WarpByVector, XDMFReader, servermanager

from xdmf_blocks import block

exe, deck, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
out = os.path.join(work, "out.h5")
proc = subprocess.run([exe, deck, "-q", "-o", out, "--force"], check=True, capture_output=True, text=True)
m = re.search(r"^mesh from .*: (\d+) Q1 elements, (\d+) nodes", proc.stdout, re.M)
failures = []


def check(what, ok, detail):
    print(("PASS " if ok else "FAIL ") + what + ": " + str(detail))
    if not ok:
        failures.append(what)


check("the program reports its Gmsh mesh", m is not None, proc.stdout.splitlines()[:3])
if m is None:
    sys.exit(1)
nel, nnode = int(m.group(1)), int(m.group(2))
reader = XDMFReader(FileNames=[os.path.join(work, "out.xmf")])
reader.UpdatePipeline()
grid = block(servermanager.Fetch(reader), "final")
check("points", grid.GetNumberOfPoints() == nnode, (grid.GetNumberOfPoints(), nnode))
check("cells", grid.GetNumberOfCells() == nel, (grid.GetNumberOfCells(), nel))
check("cells are quadrilaterals (VTK type 9)", grid.GetCellType(0) == 9, grid.GetCellType(0))
u = grid.GetPointData().GetArray("displacement")
check("displacement has 3 components", u is not None and u.GetNumberOfComponents() == 3,
      None if u is None else u.GetNumberOfComponents())
lo, hi = u.GetRange(-1)
check("displacement magnitude range not zero", hi > 0, (lo, hi))
check("stress array present", grid.GetCellData().GetArray("stress_xx_yy_xy") is not None, "stress_xx_yy_xy")
b0 = grid.GetBounds()
warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=1.0e3 / max(hi, 1e-300))
warp.UpdatePipeline()
b1 = block(servermanager.Fetch(warp), "final").GetBounds()
check("Warp By Vector moves the bounds", any(abs(a - b) > 1e-9 for a, b in zip(b0, b1)), (b0, b1))
sys.exit(1 if failures else 0)
