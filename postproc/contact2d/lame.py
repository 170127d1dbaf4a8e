"""Lame measures of a run of inputs/lame_cavity_<m>.nml (quarter ring in a rigid cavity).

    from contact2d.lame import measure
    m = measure("lame_cavity_p1.h5")  # dict: pc, p (pressure field), p_err_max, energy_rel, h, ...

Exact solution (the deck header): u = (A + B / r^2) (x, y), B = -A rb^2,
A = -p_i / (2 (lambda + mu) + 2 mu rb^2 / ra^2), contact pressure p_c = -sigma_rr(rb).
energy_rel = sqrt(a(u - u_h, u - u_h) / a(u, u)) with a(v, v) = int eps(v) : C : eps(v), both
integrated with 2 x 2 Gauss on the run's (polygonal) mesh, the exact gradient evaluated at the
physical Gauss points. h = the largest element edge. ra, rb, p_i, E, nu come from the effective deck
and the mesh (ra = min |x|, rb = max |x|). Only numpy and h5py (and contact2d.fem_q1).
"""
import sys

import numpy as np

from . import fem_q1
from .h5 import Run
from .hertz import _deck_value


def exact(ra, rb, pi, E, nu):
    lam, mu = fem_q1.plane_strain_lame(E, nu)
    A = -pi / (2 * (lam + mu) + 2 * mu * rb ** 2 / ra ** 2)
    B = -A * rb ** 2
    pc = -(2 * (lam + mu) * A - 2 * mu * B / rb ** 2)
    return A, B, pc


def measure(path):
    with Run(path) as run:
        eff = run.attr("effective_deck")
        x = run.coordinates
        conn = run.connectivity - 1
        u = run.displacement
        p = run.contact("pressure")
        status = run.contact("status")
        conv = int(run.attr("converged"))
    E = float(_deck_value(eff, "material", "young"))
    nu = float(_deck_value(eff, "material", "poisson"))
    pi = -float(_deck_value(eff, "traction", "values").split(",")[0])
    r = np.linalg.norm(x, axis=1)
    ra, rb = float(r.min()), float(r.max())
    A, B, pc = exact(ra, rb, pi, E, nu)
    geo = fem_q1.Q1Geometry(x, conn)
    xg = np.einsum("ga,ead->egd", geo.N, x[conn])          # physical Gauss points (nel, 4, 2)
    rg2 = np.sum(xg ** 2, axis=-1)
    # grad u_exact: d u_i / d x_j = (A + B / r^2) delta_ij - 2 B x_i x_j / r^4
    ge = (A + B / rg2)[..., None, None] * np.eye(2) - 2 * B * np.einsum("egi,egj->egij", xg, xg) / rg2[..., None, None] ** 2
    gh = geo.gradients(u)
    lam, mu = fem_q1.plane_strain_lame(E, nu)

    def dens(g):
        exx, eyy, exy = g[..., 0, 0], g[..., 1, 1], 0.5 * (g[..., 0, 1] + g[..., 1, 0])
        return lam * (exx + eyy) ** 2 + 2 * mu * (exx ** 2 + eyy ** 2 + 2 * exy ** 2)

    wd = np.broadcast_to(geo.wdet, dens(ge).shape)
    err = float(np.sum(dens(ge - gh) * wd))
    ref = float(np.sum(dens(ge) * wd))
    xe = x[conn]
    h = float(np.max(np.linalg.norm(xe - np.roll(xe, -1, axis=1), axis=-1)))
    return dict(pc=pc, p=p, p_err_max=float(np.max(np.abs(p / pc - 1))), all_in_contact=bool(np.all(status > 0)),
                energy_rel=np.sqrt(err / ref), h=h, converged=conv, nel=len(conn), ra=ra, rb=rb)


if __name__ == "__main__":
    print("contact2d.lame is a module, not a script (docs/postproc.md): it is used by "
          "postproc/hertz_study.py and tests/regression/test_lame.py", file=sys.stderr)
    sys.exit(2)
