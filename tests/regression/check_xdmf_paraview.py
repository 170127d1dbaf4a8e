"""Open a run's XDMF sidecar in ParaView (pvpython) and check what a user would see.

    pvpython check_xdmf_paraview.py <contact2d> <deck> <workdir>

Runs the deck (patch_compression_p1: 8 x 4 elements, 45 nodes) with two snapshot times, reads
<out>.xmf with ParaView's XDMF reader and checks, on the `final` block: the mesh (45 points, 32
quadrilaterals, 0-based connectivity of element 1 = nodes 1, 2, 11, 10 of the file), the
3-component displacement whose y range is [-delta, 0], the element stress
sigma_yy = -E delta / (H (1 - nu^2)), and that Warp By Vector works; on the `contact_final`
block: 9 points, 8 line cells, pressure = E delta / (H (1 - nu^2)) at every node; and that the
reader's time steps are the two snapshot times written in the sidecar.
"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from paraview.simple import WarpByVector, XDMFReader, servermanager

from xdmf_blocks import block

exe, deck, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
out = os.path.join(work, "out.h5")
subprocess.run([exe, deck, "-q", "-o", out, "--force", "--set", "output:snapshot_times=1e-6,2e-6"], check=True,
               stdout=subprocess.DEVNULL)
reader = XDMFReader(FileNames=[os.path.join(work, "out.xmf")])
reader.UpdatePipeline()
data = servermanager.Fetch(reader)
grid = block(data, "final")
failures = []


def check(what, ok, detail):
    print(("PASS " if ok else "FAIL ") + what + ": " + str(detail))
    if not ok:
        failures.append(what)


check("points", grid.GetNumberOfPoints() == 45, grid.GetNumberOfPoints())
check("cells", grid.GetNumberOfCells() == 32, grid.GetNumberOfCells())
cell = grid.GetCell(0)
ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
check("element 1 nodes (0-based)", ids == [0, 1, 10, 9], ids)
u = grid.GetPointData().GetArray("displacement")
check("displacement has 3 components", u is not None and u.GetNumberOfComponents() == 3,
      None if u is None else u.GetNumberOfComponents())
lo, hi = u.GetRange(1)
check("u_y range [-1e-3, 0]", abs(lo + 1e-3) < 1e-12 and abs(hi) < 1e-12, (lo, hi))
sig = grid.GetCellData().GetArray("stress_xx_yy_xy")
p = 7.0e4 * 1.0e-3 / (0.5 * (1 - 0.3**2))
lo, hi = sig.GetRange(1)
check("sigma_yy = -p in every element", abs(lo + p) < 1e-8 * p and abs(hi + p) < 1e-8 * p, (lo, hi, -p))
line = block(data, "contact_final")
check("contact_final: 9 points, 8 segments", line is not None and (line.GetNumberOfPoints(), line.GetNumberOfCells())
      == (9, 8), None if line is None else (line.GetNumberOfPoints(), line.GetNumberOfCells()))
pc = None if line is None else line.GetPointData().GetArray("pressure")
check("contact_final: pressure = p at every node", pc is not None and all(
    abs(v - p) < 1e-8 * p for v in pc.GetRange(0)), None if pc is None else (pc.GetRange(0), p))
times = [float(e.get("Value")) for e in ET.parse(os.path.join(work, "out.xmf")).getroot().iter("Time")]
steps = list(reader.TimestepValues)
check("reader time steps = the sidecar's snapshot times", len(times) == 4 and steps == sorted(set(times)),
      (steps, times))
warp = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=100.0)
warp.UpdatePipeline(steps[-1] if steps else 0.0)
b = block(servermanager.Fetch(warp), "final").GetBounds()
check("Warp By Vector: top at y = 0.5 - 100 delta", abs(b[3] - 0.4) < 1e-9, b[2:4])
sys.exit(1 if failures else 0)
