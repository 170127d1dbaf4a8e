"""Regression 1: quasi-static uniaxial compression on rollers ends on the exact linear field.

inputs/uniaxial_compression.nml: block [0, L] x [0, H] = [0, 1] x [0, 0.5] mm, E = 7e4 MPa,
nu = 0.3, plane strain; u_y = 0 on the bottom, u_x = 0 on the left, u_y = -delta on the top,
right side free. The exact solution is linear, so Q1 reproduces it exactly:
    eps_yy = -delta / H,  eps_xx = -nu / (1 - nu) eps_yy   (sigma_xx = 0 in plane strain)
    u_x = eps_xx x,  u_y = eps_yy y
    sigma_yy = -E delta / (H (1 - nu^2)),  sigma_xx = sigma_xy = 0.
"""
import numpy as np

import c2dtest

E, NU, L, H, DELTA = 7.0e4, 0.3, 1.0, 0.5, 1.0e-3


def body(t):
    run = t.run(t.deck("uniaxial_compression.nml"), name="uniaxial")
    t.expect_exit(run, 0)
    t.expect_output(run)
    with run.open() as f:
        deck = c2dtest.parse_effective_deck(c2dtest.attr_str(f.attrs["effective_deck"]))
        # the analytic constants below are the deck's (its header states them)
        t.check_equal(run, "deck material (young, poisson)", (E, NU),
                      (float(deck["material"]["young"]), float(deck["material"]["poisson"])))
        t.check_equal(run, "deck block (lx, ly)", (L, H), (float(deck["mesh"]["lx"]), float(deck["mesh"]["ly"])))
        x = f["mesh/coordinates"][()]
        u = f["final/displacement"][()]
        stress = f["final/stress"][()]
        t.check_equal(run, "converged", 1, int(f.attrs["converged"]))
        t.check_equal(run, "status", "converged", c2dtest.attr_str(f.attrs["status"]))
        t.info(run, "steps", int(f.attrs["steps"]))

    eps_yy = -DELTA / H
    eps_xx = -NU / (1 - NU) * eps_yy
    u_exact = np.column_stack([eps_xx * x[:, 0], eps_yy * x[:, 1]])
    t.info(run, "eps_xx, eps_yy (exact)", "%.10g, %.10g" % (eps_xx, eps_yy))
    # 1e-8: the run stops at tol_residual = 1e-10 (relative out-of-balance force), so the
    # displacement error is ~1e-10 times a condition factor well below 100 on an 8 x 4 mesh.
    reason = "converged to tol_residual 1e-10; the bound is 1e-8 relative"
    t.check_close(run, "final displacement vs exact linear field (max-norm)", u_exact, u,
                  rtol=1e-8, scale=float(np.max(np.abs(u_exact))), reason=reason)
    t.check_close(run, "u_x vs eps_xx x", u_exact[:, 0], u[:, 0], rtol=1e-8,
                  scale=float(np.max(np.abs(u_exact))), reason=reason)
    t.check_close(run, "u_y vs eps_yy y", u_exact[:, 1], u[:, 1], rtol=1e-8,
                  scale=float(np.max(np.abs(u_exact))), reason=reason)

    sigma_yy = -E * DELTA / (H * (1 - NU ** 2))
    t.info(run, "sigma_yy (exact)", "%.12g MPa" % sigma_yy)
    reason = "stress is linear in u, so it inherits the 1e-8 relative displacement accuracy"
    t.check_close(run, "element sigma_yy = -E delta / (H (1 - nu^2))", sigma_yy, stress[:, 1],
                  rtol=1e-8, scale=abs(sigma_yy), reason=reason)
    t.check_close(run, "element sigma_xx = 0", 0.0, stress[:, 0], rtol=1e-8, scale=abs(sigma_yy),
                  reason=reason + " (relative to |sigma_yy|)")
    t.check_close(run, "element sigma_xy = 0", 0.0, stress[:, 2], rtol=1e-8, scale=abs(sigma_yy),
                  reason=reason + " (relative to |sigma_yy|)")


if __name__ == "__main__":
    c2dtest.Test("uniaxial compression ends on the exact linear field").main(body)
