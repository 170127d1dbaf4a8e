"""Regression 5: patch_compression (P1 or P0) reproduces the uniform contact pressure exactly.

Block [0, L] x [0, H] = [0, 1] x [0, 0.5] mm on the rigid line y = 0 (P = (0, 0), nu = (0, 1)),
frictionless; the top pressed down by delta = 1e-3 mm, u_x = 0 only at the top-middle node; the
sides free. Exact answer (linear, so Q1 and both multiplier spaces reproduce it exactly):
    p = E delta / (H (1 - nu^2)) at every node (P1) / dual cell (P0), sum of nodal normal forces
    p L, nodal forces p w_i, u_y = -delta y / H, u_x = nu (1 + nu) p / E (x - L/2), no penetration.
Penetration is judged as SPEC section 3 says: d_i = u_i.n - g_i with n = -nu = (0, -1) and
g_i = (x_i - P).nu; P1 per node (d_i <= 0), P0 per dual cell ((D d)_i <= 0, D the tridiagonal
coupling built here from /contact/abscissa).
Runs at mesh:level=1 and level=2.
"""
import numpy as np

import c2dtest

E, NU, L, H, DELTA = 7.0e4, 0.3, 1.0, 0.5, 1.0e-3
P_EXACT = E * DELTA / (H * (1 - NU ** 2))
LEVELS = (1, 2)


def body(t):
    mult = t.args.multiplier
    deck = t.deck("patch_compression_%s.nml" % mult.lower())
    t.info("patch_compression_%s" % mult.lower(), "p = E delta / (H (1 - nu^2))", "%.12g MPa" % P_EXACT)
    for level in LEVELS:
        print()
        run = t.run(deck, "--set", "mesh:level=%d" % level, name="level%d" % level)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with run.open() as f:
            a = f.attrs
            eff = c2dtest.parse_effective_deck(c2dtest.attr_str(a["effective_deck"]))
            t.check_equal(run, "deck (young, poisson, lx, ly)", (E, NU, L, H),
                          (float(eff["material"]["young"]), float(eff["material"]["poisson"]),
                           float(eff["mesh"]["lx"]), float(eff["mesh"]["ly"])))
            t.check_equal(run, "multiplier", mult, c2dtest.attr_str(a["multiplier"]))
            t.check_equal(run, "converged", 1, int(a["converged"]))
            t.info(run, "steps", int(a["steps"]))
            nx = int(a["nx"])
            x = f["mesh/coordinates"][()]
            u = f["final/displacement"][()]
            nodes = f["contact/nodes"][()] - 1
            s = f["contact/abscissa"][()]
            w_file = f["contact/weight"][()]
            gap_file = f["contact/gap"][()]
            fn = f["final/contact/normal_force"][()]
            ft = f["final/contact/tangential_force"][()]
            pressure = f["final/contact/pressure"][()]
            status = f["final/contact/status"][()]

        # Gamma_c: the bottom nodes, ids 1..nx+1 (SPEC section 8 numbering), abscissa = x from O
        t.check_equal(run, "contact nodes = bottom nodes in order", list(range(nx + 1)), nodes.tolist())
        t.check_close(run, "abscissa = x of the contact nodes (O = (0, 0))", x[nodes, 0], s, atol=1e-14,
                      reason="same coordinates, round-off")
        w = c2dtest.nodal_weights(s)
        t.check_close(run, "contact weights w_i = (h_{i-1} + h_i)/2", w, w_file, rtol=1e-14,
                      reason="round-off of sums of abscissa differences")

        # the analytic answer
        reason = "converged to tol_residual 1e-11; the bound is 1e-8 relative"
        t.check_close(run, "%s pressure at every %s" % (mult, "node" if mult == "P1" else "dual cell"),
                      P_EXACT, pressure, rtol=1e-8, reason=reason)
        t.check_close(run, "nodal normal force = p w_i", P_EXACT * w, fn, rtol=1e-8,
                      scale=P_EXACT * float(np.max(w)), reason=reason)
        t.check_close(run, "sum of normal_force = p L", P_EXACT * L, float(np.sum(fn)), rtol=1e-8, reason=reason)
        t.check_close(run, "tangential force (frictionless)", 0.0, ft, atol=1e-12 * P_EXACT * float(np.max(w)),
                      reason="frictionless: zero up to round-off (1e-12 of a nodal normal force)")
        t.check_equal(run, "status (2 = sliding freely, every node in contact)", [2] * len(nodes), status.tolist())
        u_exact = np.column_stack([NU * (1 + NU) * P_EXACT / E * (x[:, 0] - L / 2), -DELTA * x[:, 1] / H])
        t.check_close(run, "displacement vs the linear field of the deck header", u_exact, u, rtol=1e-8,
                      reason=reason)

        # non-penetration
        gap = x[nodes, 1] - 0.0            # g_i = (x_i - P).nu with P = (0, 0), nu = (0, 1)
        d = -u[nodes, 1] - gap             # d_i = u_i.n - g_i, n = (0, -1)
        t.check_close(run, "/contact/gap = (x_i - P).nu", gap, gap_file, atol=1e-14,
                      reason="geometry: the bottom lies on the obstacle, round-off only")
        if mult == "P1":
            t.check_le(run, "P1 penetration max_i d_i / delta (per node)", np.max(d) / DELTA, 1e-12,
                       reason="P1 closes each node exactly: round-off only")
        else:
            D = c2dtest.dual_coupling(s)
            t.check_close(run, "D 1 = w (coupling built from the abscissa)", w, D @ np.ones(len(s)), rtol=1e-14,
                          reason="algebraic identity, round-off")
            cell = np.maximum(D @ d, 0.0) / w
            t.check_le(run, "P0 penetration max_i max((D d)_i, 0)/w_i / delta (per dual cell)",
                       np.max(cell) / DELTA, 1e-12, reason="the LCP is solved to round-off")
            t.info(run, "P0 largest nodal d_i / delta (not constrained per node)", "%.3e" % (np.max(d) / DELTA))


if __name__ == "__main__":
    c2dtest.Test("patch_compression: exact uniform pressure, no penetration",
                 extra_args=[(("--multiplier",), {"choices": ["P1", "P0"], "required": True})]).main(body)
