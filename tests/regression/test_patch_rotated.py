"""Regression: the contact patch test rotated by 30 degrees on an unstructured Gmsh quad mesh.

inputs/patch_rotated_<m>.nml: block [0, 1] x [0, 0.5] mm in axes e1 = (cos 30, sin 30),
e2 = (-sin 30, cos 30), on the inclined rigid plane with normal e2, uniform pressure p = 150 MPa on
its top (a 'normal' traction), frictionless. A linear field, so exact for Q1 on any straight-sided
quad mesh and for both multiplier spaces: pressure p everywhere on Gamma_c (1e-10 relative),
nodal normal forces p w_i, zero tangential force, the displacement field of the deck header,
every contact normal = -e2, gaps zero. Run by the explicit engine and by the static one (--static):
the block is held along its plane by contact alone (the pin fixes the slide, not the normal
translation), so the static engine takes its proximal path (docs/static.md "Bodies held by
contact"); it refused the deck as singular before.
"""
import math

import numpy as np

import c2dtest

E, NU, P = 7.0e4, 0.3, 150.0
C, S = math.cos(math.pi / 6), math.sin(math.pi / 6)
E1, E2 = np.array([C, S]), np.array([-S, C])
L, H = 1.0, 0.5


def body(t):
    for engine in ("explicit", "static"):
        print()
        check(t, engine)


def check(t, engine):
    mult = t.args.multiplier
    extra = ["--static"] if engine == "static" else []
    run = t.run(t.deck("patch_rotated_%s.nml" % mult.lower()), *extra, name=engine)
    t.expect_exit(run, 0)
    t.expect_output(run)
    with run.open() as f:
        t.check_equal(run, "converged", 1, int(f.attrs["converged"]))
        x = f["mesh/coordinates"][()]
        u = f["final/displacement"][()]
        nodes = f["contact/nodes"][()] - 1
        s = f["contact/abscissa"][()]
        gap = f["contact/gap"][()]
        normal = f["contact/normal"][()]
        fn = f["final/contact/normal_force"][()]
        ft = f["final/contact/tangential_force"][()]
        pressure = f["final/contact/pressure"][()]
        status = f["final/contact/status"][()]
    t.check_ge(run, "unstructured: contact nodes", len(nodes), 5)
    t.check_close(run, "abscissa = distance from O along e1", x[nodes] @ E1, s, atol=1e-12,
                  reason="Gmsh places nodes on the line to round-off")
    t.check_close(run, "normals = -e2", np.tile(-E2, (len(nodes), 1)), normal, atol=1e-15, reason="round-off")
    t.check_close(run, "gaps = 0", 0.0, gap, atol=1e-12, reason="nodes on the plane to round-off")
    reason = ("converged to tol_residual 1e-13; the bound is 1e-10" if engine == "explicit" else
              "a direct solve (proximal passes to 1e-14 of the force scale); the bound is 1e-10")
    t.check_close(run, "%s pressure = p" % mult, P, pressure, rtol=1e-10, reason=reason)
    w = c2dtest.nodal_weights(s)
    t.check_close(run, "nodal normal force = p w_i", P * w, fn, atol=1e-10 * P * float(np.max(w)), reason=reason)
    t.check_close(run, "tangential force", 0.0, ft, atol=1e-12 * P * float(np.max(w)), reason="frictionless")
    t.check_equal(run, "status: all in contact, sliding freely", [2] * len(nodes), status.tolist())
    # the exact field in the block axes
    xi, eta = x @ E1, x @ E2
    e11, e22 = NU * (1 + NU) * P / E, -(1 - NU ** 2) * P / E
    top_mid = L / 2 * E1 + H * E2
    # c from u_x = 0 at the top-middle node: (e22 H e2 + c e1)_x = 0
    c = -e22 * H * E2[0] / E1[0]
    ue = np.outer(e11 * (xi - L / 2) + c, E1) + np.outer(e22 * eta, E2)
    t.check_close(run, "displacement = exact linear field", ue, u, atol=1e-10 * float(np.max(np.abs(ue))),
                  reason=reason)
    k = int(np.argmin(np.linalg.norm(x - top_mid, axis=1)))
    t.check_close(run, "u_x at the top-middle node", 0.0, u[k, 0], atol=0.0)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0],
                 [(("--multiplier",), dict(required=True, choices=["P1", "P0"]))]).main(body)
