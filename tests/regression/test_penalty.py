#!/usr/bin/env python3
"""Penalty contact against the Lagrange multipliers on patch_compression.

- Multipliers (P1 per node, P0 per dual cell) do not penetrate: max penetration <= 1e-12 delta.
- The penalty penetrates uniformly by d = p/k_p, p = E delta / (H (1 - nu^2) + E/k_p) (a spring of
  stiffness k_p per unit length in series with the block): checked to 1e-8.
- Its stable step shrinks with k_p: dt_critical = 2/sqrt(omega_max^2 + max_i k_p w_i/m_i); with
  solver:mass_scaling = dt_t it is at least 2/sqrt((2/dt_t)^2 + max_i k_p w_i/m_i) (scaled masses)
  and below the scaled system's true limit.
- k_p = 1e8 at the elastic dt: refused without solver:allow_unstable (one line, nothing written),
  blows up with it (exit 2, readable file), stable and right at the penalty-adjusted dt.
- 1.1 x the power-iteration limit (penalty springs included) blows up: the guard catches it.
"""
import numpy as np

import c2dtest

E, NU, RHO, H, DELTA = 7.0e4, 0.3, 2.7e-9, 0.5, 1.0e-3


def penetration(f, multiplier):
    u = f["final/displacement"][()]
    nodes = f["contact/nodes"][()] - 1
    d = -u[nodes, 1]                                   # d = u.n - g with n = (0, -1), g = 0
    if multiplier == "P0":
        s = f["contact/abscissa"][()]
        return float(max(np.max(c2dtest.dual_coupling(s) @ d / c2dtest.nodal_weights(s)), 0.0))
    return float(max(d.max(), 0.0))


def body(t):
    deck = t.deck("patch_compression_penalty.nml")
    # ---- multipliers: zero penetration, elastic step --------------------------------------------
    dt_elastic = None
    for m in ("p1", "p0"):
        run = t.run(t.deck("patch_compression_%s.nml" % m), name="lagrange_" + m)
        t.expect_exit(run, 0)
        with run.open() as f:
            pen = penetration(f, m.upper())
            dt_elastic = float(f.attrs["dt_critical"])
        t.check_le(run, "max penetration / delta (%s)" % m.upper(), pen / DELTA, 1e-12,
                   reason="forward-increment multipliers close the gap exactly")

    # ---- penalty at several k_p: d = p/k_p, penalty-adjusted step ---------------------------------
    for kp in (1e5, 1e6, 1e7):
        run = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, name="penalty_%.0e" % kp)
        t.expect_exit(run, 0)
        with run.open() as f:
            pen = penetration(f, "P1")
            dt_crit = float(f.attrs["dt_critical"])
            converged = int(f.attrs["converged"])
            coords = f["mesh/coordinates"][()]
            conn = f["mesh/connectivity"][()] - 1
            nodes = f["contact/nodes"][()] - 1
            w = c2dtest.nodal_weights(f["contact/abscissa"][()])
            deck_eff = c2dtest.parse_effective_deck(c2dtest.attr_str(f.attrs["effective_deck"]))
        # the true limit from first principles: K plus the springs k_p w_i on the normal (y) dofs
        K, mdof = c2dtest.q1_plane_strain(coords, conn, E, NU, RHO)
        K[2 * nodes + 1, 2 * nodes + 1] += kp * w
        free = np.flatnonzero(c2dtest.free_dofs_from_deck(coords, deck_eff))
        sc = 1 / np.sqrt(mdof[free])
        dt_true = 2 / np.sqrt(np.linalg.eigvalsh(K[np.ix_(free, free)] * sc[:, None] * sc[None, :])[-1])
        p = E * DELTA / (H * (1 - NU**2) + E / kp)
        t.check_equal(run, "converged", 1, converged)
        t.check_close(run, "penetration = p/k_p (k_p = %g)" % kp, p / kp, pen, rtol=1e-8,
                      reason="a uniform spring in series, exact for Q1: only the relaxation residual (tol_residual) "
                      "remains; measured <= 1e-11")
        t.info(run, "true limit with the springs / penalty dt_critical", "%.4f" % (dt_true / dt_crit))
        t.check_ge(run, "true limit (dense eigensolve, springs included) / penalty dt_critical", dt_true / dt_crit,
                   1 - 1e-12, reason="the nodal bound 2/sqrt(omega_el^2 + k_p w/m) must be conservative")
        t.check_le(run, "penalty dt_critical <= elastic dt_critical", dt_crit, dt_elastic * (1 + 1e-15))

    # ---- penalty with mass scaling: the springs lower the scaled system's bound, not the original's --
    kp, dt_t = 1e6, 1e-7
    run = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, "--set", "solver:mass_scaling=%r" % dt_t,
                name="penalty_mass_scaling")
    t.expect_exit(run, 0)
    with run.open() as f:
        pen = penetration(f, "P1")
        dt_crit = float(f.attrs["dt_critical"])
        t.check_equal(run, "converged", 1, int(f.attrs["converged"]))
        t.check(run, "mass added", float(f.attrs["added_mass"]) > 0, "> 0", float(f.attrs["added_mass"]))
        coords = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()] - 1
        nodes = f["contact/nodes"][()] - 1
        mass = f["mesh/mass"][()]                       # the scaled nodal masses
        w = c2dtest.nodal_weights(f["contact/abscissa"][()])
        deck_eff = c2dtest.parse_effective_deck(c2dtest.attr_str(f.attrs["effective_deck"]))
    # every row of the scaled system meets dt_t (Gershgorin), so the springs can only lower the step to
    bound = 2 / np.sqrt((2 / dt_t) ** 2 + np.max(kp * w / mass[nodes]))
    t.check_ge(run, "dt_critical / 2/sqrt((2/dt_t)^2 + max k_p w_i/m_i) (scaled m_i)", dt_crit / bound, 1 - 1e-12,
               reason="mass scaling reaches dt_t before the springs (docs/deck.md)")
    K, _ = c2dtest.q1_plane_strain(coords, conn, E, NU, RHO)
    K[2 * nodes + 1, 2 * nodes + 1] += kp * w
    free = np.flatnonzero(c2dtest.free_dofs_from_deck(coords, deck_eff))
    sc = 1 / np.sqrt(np.repeat(mass, 2)[free])
    dt_true = 2 / np.sqrt(np.linalg.eigvalsh(K[np.ix_(free, free)] * sc[:, None] * sc[None, :])[-1])
    t.check_ge(run, "true limit of the scaled system with the springs / dt_critical", dt_true / dt_crit, 1 - 1e-12,
               reason="the bound must stay conservative")
    p = E * DELTA / (H * (1 - NU**2) + E / kp)
    t.check_close(run, "penetration = p/k_p with mass scaling (the static end state)", p / kp, pen, rtol=1e-8,
                  reason="added mass does not move an equilibrium: exact for Q1 up to tol_residual; measured 2e-13")

    # ---- k_p beyond the stable limit at the elastic dt -------------------------------------------
    kp = 1e8
    dt = 0.9 * dt_elastic
    refused = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, "--set", "solver:dt=%r" % dt,
                    name="refused")
    t.expect_exit(refused, 1, stop=False)
    t.check_equal(refused, "error lines", 1, len(refused.error_lines()))
    msg = refused.error_lines()[0] if refused.error_lines() else ""
    t.check(refused, "message names the penalty-adjusted limit", "penalty" in msg and "allow_unstable" in msg,
            "mentions penalty and allow_unstable", repr(msg))
    t.check(refused, "nothing written", not __import__("os").path.exists(refused.h5), "no out.h5", refused.h5)
    forced = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, "--set", "solver:dt=%r" % dt,
                   "--set", "solver:allow_unstable=.true.", name="forced")
    t.expect_exit(forced, 2, stop=False)
    t.expect_output(forced)
    with forced.open() as f:
        t.check_equal(forced, "status", "blow-up", c2dtest.attr_str(f.attrs["status"]))
        t.info(forced, "dt / penalty dt_critical", "%.3f" % (dt / float(f.attrs["dt_critical"])))
    reduced = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, name="reduced")
    t.expect_exit(reduced, 0)
    with reduced.open() as f:
        pen = penetration(f, "P1")
        t.check_equal(reduced, "converged at the penalty-adjusted dt", 1, int(f.attrs["converged"]))
        dt_est = float(f.attrs["dt_stable_estimate"])
    p = E * DELTA / (H * (1 - NU**2) + E / kp)
    t.check_close(reduced, "penetration = p/k_p (k_p = 1e8)", p / kp, pen, rtol=1e-8, reason="exact for Q1 up to tol_residual; measured 1e-11")

    # ---- 1.1 x the true limit (power iteration with the penalty springs): the guard stops it ------
    bad = t.run(deck, "--set", "contact:penalty_stiffness=%r" % kp, "--set", "solver:dt=%r" % (1.1 * dt_est),
                "--set", "solver:allow_unstable=.true.", "--set", "solver:damping='none'", name="unstable")
    t.expect_exit(bad, 2, stop=False)
    t.check(bad, "error line mentions the blow-up", any("blew up" in e for e in bad.error_lines()),
            "'blew up'", repr(bad.error_lines()))
    t.expect_output(bad)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
