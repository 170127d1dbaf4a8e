#!/usr/bin/env python3
"""A Tresca threshold profile s(abscissa) and a contact origin O off the first node (docs/deck.md).

tresca_sliding (block [0, 1] x [0, 0.5] on y = 0, Gamma_c = bottom) with contact:origin = (-0.25, 0),
so the abscissa of bottom node x_i is x_i + 0.25 (the chain runs along +x from O), and a piecewise
linear threshold through (0.4, 50), (0.9, 150), (1.1, 100) MPa, held beyond the ends. Facts:
- /contact/abscissa = x_i - O_x at every contact node (geometry);
- /contact/threshold = s(abscissa_i), interpolated here with numpy (np.interp holds the end values);
- after the stage-2 stroke the block slides: every node carries its own limit, |F_t,i| = s_i w_i
  with s_i from the profile above (not read back) and w_i from the abscissae; the total is
  sum_i s_i w_i (nodal quadrature of the friction integral, SPEC section 3).
Static engine, 20 increments (as test_static.py's sliding check), P1 and P0.
"""
import os

import numpy as np

import c2dtest

ORIGIN_X = -0.25
XS, VS = [0.4, 0.9, 1.1], [50.0, 150.0, 100.0]


def body(t):
    for mult in ("p1", "p0"):
        # the shipped deck gives a uniform threshold, which excludes a profile: drop that line
        with open(t.deck("tresca_sliding_%s.nml" % mult)) as fh:
            text = fh.read()
        t.require("   threshold = 100.0\n" in text, "the deck has the uniform threshold line")
        folder = t.subdir("deck_" + mult)
        deck = os.path.join(folder, "profile_%s.nml" % mult)
        with open(deck, "w") as fh:
            fh.write(text.replace("   threshold = 100.0\n", ""))
        run = t.run(deck, "--static",
                    "--set", "solver:static_increments=20",
                    "--set", "contact:origin=%r,0.0" % ORIGIN_X,
                    "--set", "contact:threshold_abscissa=" + ",".join(map(repr, XS)),
                    "--set", "contact:threshold_values=" + ",".join(map(repr, VS)),
                    name="profile_" + mult)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with run.open() as f:
            x = f["mesh/coordinates"][()]
            nodes = f["contact/nodes"][()] - 1
            s_abs = f["contact/abscissa"][()]
            thr = f["contact/threshold"][()]
            ft = f["final/contact/tangential_force"][()]
        t.check_close(run, "abscissa = x_i - O_x along the bottom", x[nodes, 0] - ORIGIN_X, s_abs, atol=1e-14,
                      reason="coordinates of multiples of 1/8 mm: round-off only")
        s_exact = np.interp(x[nodes, 0] - ORIGIN_X, XS, VS)
        t.check(run, "the profile's clamped ends and interior are all exercised",
                bool(np.any(s_exact == VS[0]) and np.any(s_exact == VS[-1]) and np.any((s_exact != VS[0])
                     & (s_exact != VS[-1]))), "True", "")
        t.check_close(run, "/contact/threshold = s(abscissa) (piecewise linear, held at the ends)", s_exact, thr,
                      rtol=1e-14, reason="one linear interpolation: round-off")
        w = c2dtest.nodal_weights(x[nodes, 0])
        t.check_close(run, "slid: |F_t,i| = s(x_i) w_i at every contact node", s_exact * w, np.abs(ft), rtol=1e-10,
                      reason="each node at its Tresca limit (as test_tresca_sliding.py, 1e-10)")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
