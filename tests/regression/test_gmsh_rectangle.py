"""Regression: a Gmsh mesh of the paper's rectangle gives the built-in mesher's end state.

inputs/gmsh_rectangle_<m>.nml reads inputs/paper_rectangle.geo (13 x 3 quads by extrusion, refined
twice by Gmsh) with boundaries named as physical curves; inputs/baillet_sassi_2002_<m>.nml runs
at --set mesh:level=2 on the built-in (52 x 12) mesh. The two meshes have the same nodes (matched
by coordinates, numbered differently), the first goes through the general block-CSR stiffness,
the second through the structured stencil. Same discrete problem, so the same end state to
round-off: displacement, contact nodes in order, abscissa, pressure, status, step count.
The same geometry meshed by the gmsh command line into MSH 4.1 and MSH 2.2 files, read with
mesh:file and refined by contact2d (straight edges: the same nodes), gives the .geo run's end state.
"""
import os
import shutil
import subprocess
import sys

import numpy as np

import c2dtest

LEVEL = 2


def body(t):
    mult = t.args.multiplier.lower()
    runs = {}
    for kind, deck, extra in (("gmsh", "gmsh_rectangle_%s.nml" % mult, []),
                              ("builtin", "baillet_sassi_2002_%s.nml" % mult, ["--set", "mesh:level=%d" % LEVEL])):
        run = t.run(t.deck(deck), *extra, name=kind)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with run.open() as f:
            runs[kind] = dict(x=f["mesh/coordinates"][()], u=f["final/displacement"][()],
                              nodes=f["contact/nodes"][()] - 1, s=f["contact/abscissa"][()],
                              p=f["final/contact/pressure"][()], status=f["final/contact/status"][()],
                              normal=f["contact/normal"][()], steps=int(f.attrs["steps"]),
                              conv=int(f.attrs["converged"]), h5=run.h5)
    g, b = runs["gmsh"], runs["builtin"]
    t.check_equal("gmsh", "node count", len(b["x"]), len(g["x"]))
    # match nodes by coordinates (rounded to 1e-9 mm, far below the element size 0.025 mm)
    key = {tuple(k): i for i, k in enumerate(np.round(b["x"] / 1e-9).astype(np.int64))}
    perm = np.array([key.get(tuple(k), -1) for k in np.round(g["x"] / 1e-9).astype(np.int64)])
    t.check_equal("gmsh", "every Gmsh node is a built-in node", True, bool(np.all(perm >= 0)))
    t.require(bool(np.all(perm >= 0)), "the meshes do not have the same nodes")
    t.check_close("gmsh", "coordinates", b["x"][perm], g["x"], atol=1e-12,
                  reason="Gmsh places refined nodes by its curve parametrisation: round-off of 1.3 mm")
    t.check_equal("gmsh", "converged (both)", (1, 1), (g["conv"], b["conv"]))
    t.check_equal("gmsh", "steps", b["steps"], g["steps"])
    t.check_equal("gmsh", "contact nodes in order (mapped)", b["nodes"].tolist(), perm[g["nodes"]].tolist())
    t.check_close("gmsh", "abscissa", b["s"], g["s"], atol=1e-12, reason="coordinates to round-off")
    t.check_close("gmsh", "normals", b["normal"], g["normal"], atol=0.0, reason="the same plane")
    umax = float(np.max(np.abs(b["u"])))
    t.check_close("gmsh", "displacement (relative to max |u|)", b["u"][perm], g["u"], atol=1e-12 * umax,
                  reason="same discrete problem; only summation order and 1e-13 mm coordinate differences")
    pmax = float(np.max(np.abs(b["p"])))
    t.check_close("gmsh", "contact pressure (relative to max |p|)", b["p"], g["p"], atol=1e-12 * pmax,
                  reason="as the displacement")
    t.check_equal("gmsh", "status", b["status"].tolist(), g["status"].tolist())

    check_getfem_sides(t, runs, perm, mult)

    # MSH files of every version Gmsh writes are read through the same library
    gmsh = shutil.which("gmsh")
    t.require(gmsh is not None, "the gmsh command (Debian package gmsh) is needed to write the .msh files")
    for fmt in ("msh41", "msh22"):
        msh = os.path.join(t.subdir(fmt), "paper_rectangle_%s.msh" % fmt)
        subprocess.run([gmsh, "-2", os.path.join(t.inputs, "paper_rectangle.geo"), "-format", fmt, "-o", msh],
                       check=True, stdout=subprocess.DEVNULL)
        run = t.run(t.deck("gmsh_rectangle_%s.nml" % mult), "--set", "mesh:file='%s'" % msh, cwd=os.path.dirname(msh))
        t.expect_exit(run, 0)
        with run.open() as f:
            xm, um = f["mesh/coordinates"][()], f["final/displacement"][()]
            pm = f["final/contact/pressure"][()]
        # the file numbers its nodes its own way: match them to the .geo run's by coordinates
        keyg = {tuple(k): i for i, k in enumerate(np.round(g["x"] / 1e-9).astype(np.int64))}
        pm_ = np.array([keyg.get(tuple(k), -1) for k in np.round(xm / 1e-9).astype(np.int64)])
        t.check_equal(run, "%s: the same nodes as the .geo run" % fmt, True,
                      bool(len(xm) == len(g["x"]) and np.all(pm_ >= 0)))
        t.require(bool(np.all(pm_ >= 0)), "the meshes differ")
        t.check_close(run, "%s: coordinates = the .geo run's" % fmt, g["x"][pm_], xm, atol=1e-12, reason="round-off")
        t.check_close(run, "%s: displacement = the .geo run's" % fmt, g["u"][pm_], um, atol=1e-12 * umax,
                      reason="the same mesh and problem")
        t.check_close(run, "%s: pressure = the .geo run's" % fmt, g["p"], pm, atol=1e-12 * pmax, reason="as above")
        if fmt == "msh22":
            # outputs number the nodes 1..n in increasing tag of the file (docs/geometry.md), though
            # the solver renumbers them inside: the file's own quads and nodes, read here
            # (level 0: the file's own quads, unrefined; one step is enough)
            nodes, quads = read_msh22(msh)
            tags = sorted({n for q in quads for n in q})
            rank = {tag: i + 1 for i, tag in enumerate(tags)}
            run = t.run(t.deck("gmsh_rectangle_%s.nml" % mult), "--set", "mesh:file='%s'" % msh,
                        "--set", "mesh:level=0", "--set", "solver:max_steps=1", cwd=os.path.dirname(msh),
                        output="level0.h5")
            t.expect_exit(run, 0)
            with run.open() as f:
                xm, conn = f["mesh/coordinates"][()], f["mesh/connectivity"][()]
            t.check_close(run, "msh22: coordinates in increasing tag", np.array([nodes[k] for k in tags]), xm,
                          atol=0.0, reason="the same numbers, copied")
            t.check_equal(run, "msh22: connectivity = the file's quads (as node sets, in file order)",
                          [sorted(rank[n] for n in q) for q in quads], [sorted(c) for c in conn.tolist()])


def check_getfem_sides(t, runs, perm, mult):
    """The GetFEM reference of the Gmsh run: its named boundaries need --side (refused without, one
    line naming the option); with it, the same static problem as the built-in run's, so the same
    GetFEM solution node for node (both Newton solutions to KKT 1e-12: 1e-9 of max |u| is ample)."""
    try:
        import getfem  # noqa: F401
    except ImportError:
        print("SKIP getfem_reference --side: python3-getfem is missing")
        return
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "postproc",
                          "getfem_reference.py")
    refs = {}
    for kind, extra in (("nosides", []), ("gmsh", ["--side", "top=top", "--side", "right=right"]),
                        ("builtin", [])):
        h5 = runs["builtin" if kind == "builtin" else "gmsh"]["h5"]
        ref = os.path.join(t.workdir, "getfem_%s_%s.h5" % (kind, mult))
        cmd = [sys.executable, script, h5, "-o", ref, "--force"] + extra
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        print("-- run  " + " ".join(cmd) + "\n" + proc.stdout + proc.stderr)
        if kind == "nosides":
            t.check_equal("getfem --side", "a Gmsh deck without --side: exit 2", 2, proc.returncode)
            t.check("getfem --side", "the refusal names --side", "--side top=SIDE" in proc.stderr,
                    "--side top=SIDE", proc.stderr.strip())
            continue
        t.require(proc.returncode == 0, "getfem_reference.py failed: " + proc.stderr[-1500:])
        with c2dtest.h5py.File(ref, "r") as f:
            refs[kind] = f["final/displacement"][()]
    umax = float(np.max(np.abs(refs["builtin"])))
    t.check_close("getfem --side", "GetFEM on the Gmsh run = GetFEM on the built-in run (node for node)",
                  refs["builtin"][perm], refs["gmsh"], atol=1e-9 * umax,
                  reason="the same discrete problem; Newton to a KKT violation of 1e-12")


def read_msh22(path):
    """Nodes {tag: (x, y)} and 4-node quadrilaterals (type 3, in file order) of an MSH 2.2 file."""
    nodes, quads, section = {}, [], None
    with open(path) as fh:
        for line in fh:
            w = line.split()
            if not w:
                continue
            if w[0].startswith("$"):
                section = None if w[0].startswith("$End") else w[0]
                count = True
                continue
            if section in ("$Nodes", "$Elements") and count:
                count = False   # the count line
                continue
            if section == "$Nodes":
                nodes[int(w[0])] = (float(w[1]), float(w[2]))
            elif section == "$Elements" and int(w[1]) == 3:
                ntag = int(w[2])
                quads.append([int(v) for v in w[3 + ntag:3 + ntag + 4]])
    return nodes, quads


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0],
                 [(("--multiplier",), dict(required=True, choices=["P1", "P0"]))]).main(body)
