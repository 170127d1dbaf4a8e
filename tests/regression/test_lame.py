"""Regression: Lame ring in a rigid circular cavity, P1 or P0, levels 1-3.

inputs/lame_cavity_<m>.nml: a quarter ring (ra = 1, rb = 2 mm) inside the rigid cavity r = rb
(obstacle = 'circle', body inside), frictionless, pressure p_i = 100 MPa on its inner boundary
(a 'normal' traction on a curved boundary). The whole outer boundary stays in contact and the
contact pressure is p_c = p_i 2 (1 - nu) / (1 + (1 - 2 nu) rb^2 / ra^2) (Lame with u_r(rb) = 0,
derived in the deck header; contact2d.lame). Checked: every contact node in contact, the
pressure everywhere within 0.06 % of p_c at level 3, the relative energy-norm error (exact field
against the run's, 2 x 2 Gauss) converging at a rate >= 0.98 between levels (Q1 optimum: 1),
the circle's normals n_i = x_i / |x_i| and gaps rb - |x_i|.
"""

import numpy as np

import c2dtest

from contact2d import lame

LEVELS = (1, 2, 3)

# The pressure error is Q1's discretisation error with the chordal (polygonal) outer boundary
# (stopping at tol_residual = 1e-10 changes it by 1.3e-9, against a run to 1e-13). Measured at
# h = 0.26, 0.13, 0.065 (levels 1-3): mean p/p_c - 1 = -4.30e-3, -1.08e-3, -2.69e-4 (order 2.0: the O(h^2) of the
# chords and of the Q1 stress at the boundary), max |p/p_c - 1| = 5.2e-3, 1.5e-3, 4.7e-4 (P1),
# 4.9e-3, 1.4e-3, 4.3e-4 (P0), order 1.75, worst at the node (rb, 0) on the cut y = 0, where Gamma_u
# meets Gamma_c. The bound is the level-2 maximum divided by 2^1.5 (the a-priori h^(3/2) rate of the
# contact multiplier): 1.545e-3 / 2.83 = 5.5e-4, rounded up to 6e-4 (was 5e-3, no reason).
P_ERR_LEVEL3 = 6e-4
P_REASON = "Q1 + chords, order >= 1.5 from level 2's 1.5e-3; measured 4.7e-4 (P1), 4.3e-4 (P0)"
# Q1 energy-norm error = C h (1 + O(h)) for the smooth Lame field: measured rates 0.9965 (levels
# 1-2) and 0.9992 (2-3), for P1 and P0 alike; 0.98 leaves 6 times the larger deficit (was 0.9).
RATE_MIN = 0.98
RATE_REASON = "Q1 optimum 1; measured 0.9965 and 0.9992"


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
            t.check_le(run, "max |p / p_c - 1| at level 3", m["p_err_max"], P_ERR_LEVEL3, reason=P_REASON)
        if prev is not None:
            rate = np.log(prev[0] / m["energy_rel"]) / np.log(prev[1] / m["h"])
            t.check_ge(run, "energy-norm error rate from the previous level", rate, RATE_MIN, reason=RATE_REASON)
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
