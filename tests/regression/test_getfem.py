#!/usr/bin/env python3
"""contact2d's quasi-static end state against an independent static solver.

postproc/getfem_reference.py solves the same discrete problem (SPEC 2-3) on the same mesh with
GetFEM (python3-getfem): P1 with the nodal rigid-obstacle brick, P0 with the basic contact brick
and B_N = D N, Tresca in GetFEM's weak-form language. Cases at mesh level 2: the paper scene
frictionless and with Tresca (proportional, monotone loading: the one-shot static problem is the
quasi-static end state), and patch_compression, for P1 and P0.

Tolerances. contact2d relaxes to a relative residual of 1e-11 (set here); the displacement error
this leaves is the residual times the conditioning of K, measured as 200-5000 x tol_residual on
levels 2-4 (docs/getfem_reference.md), i.e. <= 2e-8 here. GetFEM's Newton stops at a contact KKT
violation of 1e-12. Bound: 1e-6 relative in displacement, pressure and shear (50x margin over
what is measured, far below any modelling difference, which shows at 1e-4 or more), and the
contact status node for node.
"""
import os
import subprocess
import sys

import numpy as np

import c2dtest

POSTPROC = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                                         "postproc"))
FRICTIONLESS = ["--set", "contact:friction='frictionless'", "--set", "contact:threshold=0"]
CASES = [
    ("paper_p1_frictionless", "baillet_sassi_2002_p1.nml", FRICTIONLESS),
    ("paper_p0_frictionless", "baillet_sassi_2002_p0.nml", FRICTIONLESS),
    ("paper_p1_tresca", "baillet_sassi_2002_p1.nml", []),
    ("paper_p0_tresca", "baillet_sassi_2002_p0.nml", []),
    ("patch_p1", "patch_compression_p1.nml", []),
    ("patch_p0", "patch_compression_p0.nml", []),
]


def body(t):
    for name, deck, extra in CASES:
        run = t.run(t.deck(deck), "--set", "mesh:level=2", "--set", "solver:tol_residual=1e-11", *extra, name=name)
        t.expect_exit(run, 0)
        ref = os.path.join(run.cwd, "getfem.h5")
        cmd = [sys.executable, os.path.join(POSTPROC, "getfem_reference.py"), run.h5, "-o", ref]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        print("-- run  " + " ".join(cmd) + "\n" + proc.stdout)
        t.require(proc.returncode == 0, "getfem_reference.py failed: " + proc.stderr[-1500:])
        with run.open() as a, c2dtest.h5py.File(ref, "r") as b:
            ua, ub = a["final/displacement"][()], b["final/displacement"][()]
            t.check_le(run, "max |u - u_GetFEM| / max |u_GetFEM|", np.abs(ua - ub).max() / np.abs(ub).max(), 1e-6,
                       reason="relaxation tolerance 1e-11 x conditioning, see the module docstring")
            for field in ("pressure", "shear", "normal_force", "tangential_force"):
                fa, fb = a["final/contact/" + field][()], b["final/contact/" + field][()]
                scale = max(np.abs(fb).max(), 1e-300)
                if np.abs(fb).max() == 0:
                    t.check_le(run, field + " (zero in GetFEM)", np.abs(fa).max(), 1e-9, reason="frictionless")
                else:
                    t.check_le(run, "max |%s - GetFEM| / max |GetFEM|" % field, np.abs(fa - fb).max() / scale, 1e-6,
                               reason="as for the displacement")
            t.check_equal(run, "contact status node for node", b["final/contact/status"][()].tolist(),
                          a["final/contact/status"][()].tolist())


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
