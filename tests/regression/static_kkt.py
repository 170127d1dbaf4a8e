"""Independent KKT residuals of a static contact2d file (docs/static.md), from its HDF5 contents only.

Used by test_static.py and test_static_friction.py. Nothing is read back from the engine's own
KKT attributes here: the residuals are recomputed with numpy from
  - the mesh (/mesh/coordinates, /mesh/connectivity: any Q1 mesh, structured or Gmsh),
  - the material and the friction law from the effective deck (E, nu; Tresca s w from
    /contact/threshold and /contact/weight, Coulomb mu F_n,i, tresca_scope),
  - Gamma_c (/contact/nodes, gap, normal, abscissa) and the final state (/final/displacement,
    /final/contact/normal_force, tangential_force, pressure, /final/reaction).
K u is formed here element by element (plane-strain Q1, 2 x 2 Gauss, vectorised over elements) with
the element's own geometry, so a graded Gmsh mesh needs nothing more than the rectangle.
Conventions (SPEC section 3, docs/friction.md): /contact/normal is the body's outward normal n_i,
t_i = (-n_2, n_1); the force on the body is -F_n n - F_t t; d_i = u_i . n_i - gap_i; P0 judges
the normal conditions per dual cell with D (tridiagonal, from the abscissae) and mu = pressure.
Friction is judged on the tangential displacement of the last increment, psi = (u - u_prev) . t
(u_prev = 0 for one increment from rest).
"""
import numpy as np

import c2dtest

from contact2d import fem_q1

NAMES = ("normal_feasibility", "complementarity", "friction_feasibility", "equilibrium")


def k_times(coords, conn, u, young, poisson):
    """K u for plane-strain Q1 elements, each with its own geometry (2 x 2 Gauss)."""
    xe = coords[conn]                                   # (E, 4, 2)
    D = fem_q1.plane_strain_D(young, poisson)
    ue = u[conn].reshape(conn.shape[0], 8)
    fe = np.zeros_like(ue)
    for xi, w in zip(fem_q1.GAUSS_POINTS, fem_q1.GAUSS_WEIGHTS):
        dref = fem_q1.shape_gradients_ref(xi[None, :])[0]          # (4, 2)
        J = np.einsum("eai,aj->eij", xe, dref)                      # dx_i / dxi_j
        det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        Jinv = np.stack([np.stack([J[:, 1, 1], -J[:, 0, 1]], -1),
                         np.stack([-J[:, 1, 0], J[:, 0, 0]], -1)], 1) / det[:, None, None]
        dN = np.einsum("aj,eji->eai", dref, Jinv)                   # dN_a / dx_i
        B = np.zeros((conn.shape[0], 3, 8))
        B[:, 0, 0::2] = dN[:, :, 0]
        B[:, 1, 1::2] = dN[:, :, 1]
        B[:, 2, 0::2] = dN[:, :, 1]
        B[:, 2, 1::2] = dN[:, :, 0]
        strain = np.einsum("eij,ej->ei", B, ue)
        fe += w * det[:, None] * np.einsum("eji,jk,ek->ei", B, D, strain)
    f = np.zeros_like(u)
    np.add.at(f, conn, fe.reshape(conn.shape[0], 4, 2))
    return f


def residuals(h5, u_prev=None, fext=None):
    """The four relative KKT residuals of the file's final state, as a dict, plus details.

    fext: the nodal external forces (nnode, 2) where the scene has tractions (the file does not
    store them; the caller forms them from its deck), else none."""
    deck = c2dtest.parse_effective_deck(c2dtest.attr_str(h5.attrs["effective_deck"]))
    young, poisson = float(deck["material"]["young"]), float(deck["material"]["poisson"])
    contact = deck["contact"]
    coords = h5["mesh/coordinates"][()]
    conn = h5["mesh/connectivity"][()] - 1
    u = h5["final/displacement"][()]
    if u_prev is None:
        u_prev = np.zeros_like(u)
    nodes = h5["contact/nodes"][()] - 1
    gap = h5["contact/gap"][()]
    normal = h5["contact/normal"][()]
    tangent = np.stack([-normal[:, 1], normal[:, 0]], axis=1)
    w = h5["contact/weight"][()]
    absc = h5["contact/abscissa"][()]
    fn = h5["final/contact/normal_force"][()]
    ft = h5["final/contact/tangential_force"][()]
    pressure = h5["final/contact/pressure"][()]
    p0 = c2dtest.attr_str(h5.attrs["multiplier"]) == "P0"
    umax = np.abs(u).max()
    d = np.sum(u[nodes] * normal, axis=1) - gap
    if p0:
        e = c2dtest.dual_coupling(absc) @ d / w     # mean gap per dual cell
        lam = pressure                              # mu per cell
    else:
        e = d
        lam = fn
    lmax = max(np.abs(lam).max(), np.finfo(float).tiny)
    res = {"normal_feasibility": max(e.max(), 0.0) / umax,
           "negative_multiplier": max(-lam.min(), 0.0) / lmax,
           "complementarity_product": np.abs(lam * e).max() / (lmax * umax)}
    res["complementarity"] = max(res["negative_multiplier"], res["complementarity_product"])
    # equilibrium on the free dofs: K u - F_c - f_ext = 0
    f = k_times(coords, conn, u, young, poisson)
    fc = np.zeros_like(u)
    fc[nodes] = -fn[:, None] * normal - ft[:, None] * tangent
    if fext is None:
        fext = np.zeros_like(u)
    r = f - fc - fext
    free = h5["final/reaction"][()] == 0
    scale = max(np.abs(r[~free]).max() if (~free).any() else 0.0, np.abs(fc).max(), np.abs(fext).max())
    res["equilibrium"] = np.abs(r[free]).max() / scale
    # the friction limit of each node for the final forces
    law = str(contact.get("friction", "frictionless")).lower()
    if law == "coulomb":
        limit = float(contact["friction_coefficient"]) * np.maximum(fn, 0.0)
    elif law == "tresca":
        limit = h5["contact/threshold"][()] * w
        if str(contact.get("tresca_scope", "all")).lower() == "contact":
            limit = np.where((pressure if p0 else fn) > 0, limit, 0.0)
    else:
        limit = np.zeros_like(fn)
    psi = np.sum((u - u_prev)[nodes] * tangent, axis=1)
    if limit.max() > 0:
        lm = limit.max()
        res["friction_bound"] = max((np.abs(ft) - limit).max(), 0.0) / lm
        res["friction_slip"] = np.abs(limit * np.abs(psi) - ft * psi).max() / (lm * umax)
        res["friction_feasibility"] = max(res["friction_bound"], res["friction_slip"])
    else:
        # no limit anywhere: any F_t is wrong, against the force scale (as kkt_values)
        res["friction_feasibility"] = np.abs(ft).max() / scale
    res["limit"], res["psi"], res["fn"], res["ft"] = limit, psi, fn, ft
    return res


def check(t, run, h5, tol, u_prev=None, attributes=True, fext=None):
    """check_le every residual of residuals() against tol; also the file's own kkt_* attributes."""
    res = residuals(h5, u_prev, fext)
    t.check_le(run, "normal feasibility max(d, 0) / max|u| (P0: per dual cell)", res["normal_feasibility"], tol)
    t.check_le(run, "negative multiplier / max", res["negative_multiplier"], tol)
    t.check_le(run, "complementarity max|lambda d| / (max lambda max|u|)", res["complementarity_product"], tol)
    if "friction_bound" in res:
        t.check_le(run, "friction: max(|F_t| - limit, 0) / max limit", res["friction_bound"], tol)
        t.check_le(run, "friction: max|limit |psi| - F_t psi| / (max limit max|u|)", res["friction_slip"], tol)
    else:
        t.check_le(run, "no friction limit: max |F_t|", res["friction_feasibility"], 0.0)
    t.check_le(run, "equilibrium max|K u - F_c - f_ext| on free dofs / max(reaction, F_c, f_ext)", res["equilibrium"], tol)
    if attributes:
        for name in NAMES:
            t.check_le(run, "attribute kkt_" + name, float(h5.attrs["kkt_" + name]), tol)
    return res
