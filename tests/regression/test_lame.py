"""Regression: Lame ring in a rigid circular cavity (issue 10), P1 or P0, levels 1-3.

inputs/lame_cavity_<m>.nml: a quarter ring (ra = 1, rb = 2 mm) inside the rigid cavity r = rb
(obstacle = 'circle', body inside), frictionless, pressure p_i = 100 MPa on its inner boundary
(a 'normal' traction on a curved boundary). The whole outer boundary stays in contact and the
contact pressure is p_c = p_i 2 (1 - nu) / (1 + (1 - 2 nu) rb^2 / ra^2) (Lame with u_r(rb) = 0,
derived in the deck header; postproc/lame.py). Checked: every contact node in contact, the
pressure everywhere within 0.5 % of p_c at level 3, the relative energy-norm error (exact field
against the run's, 2 x 2 Gauss) converging at a rate >= 0.9 between levels (Q1 optimum: 1),
the circle's normals n_i = x_i / |x_i| and gaps rb - |x_i|.
"""
import os
import sys

import numpy as np

import c2dtest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postproc"))
import lame  # noqa: E402

LEVELS = (1, 2, 3)


def body(t):
    mult = t.args.multiplier.lower()
    prev = None
    for level in LEVELS:
        run = t.run(t.deck("lame_cavity_%s.nml" % mult), "--set", "mesh:level=%d" % level, name="level%d" % level)
        t.expect_exit(run, 0)
        t.expect_output(run)
        m = lame.measure(run.h5)
        t.check_equal(run, "converged", 1, m["converged"])
        t.check_equal(run, "every contact node in contact", True, m["all_in_contact"])
        t.info(run, "max |p / p_c - 1|", "%.3e" % m["p_err_max"])
        t.info(run, "energy-norm error (relative), h", "%.4e %.4e" % (m["energy_rel"], m["h"]))
        if level == 3:
            t.check_le(run, "max |p / p_c - 1| at level 3", m["p_err_max"], 0.005)
        if prev is not None:
            rate = np.log(prev[0] / m["energy_rel"]) / np.log(prev[1] / m["h"])
            t.check_ge(run, "energy-norm error rate from the previous level", rate, 0.9)
        prev = (m["energy_rel"], m["h"])
        with run.open() as f:
            x = f["mesh/coordinates"][()]
            nodes = f["contact/nodes"][()] - 1
            gap = f["contact/gap"][()]
            normal = f["contact/normal"][()]
        r = np.linalg.norm(x[nodes], axis=1)
        t.check_close(run, "normals x / |x|", x[nodes] / r[:, None], normal, atol=1e-15, reason="round-off")
        t.check_close(run, "gaps rb - |x| (nodes on the circle)", 0.0, gap, atol=1e-14,
                      reason="Gmsh puts refined nodes on the circle to round-off")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0],
                 [(("--multiplier",), dict(required=True, choices=["P1", "P0"]))]).main(body)
