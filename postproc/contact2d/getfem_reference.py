#!/usr/bin/python3
"""Independent static reference for contact2d: the same discrete problem solved by GetFEM.

    postproc/getfem_reference.py IN.h5 -o REF.h5 [--force] [--multiplier P1|P0]
        [--friction frictionless|tresca] [--tol 1e-12]

IN.h5 is any contact2d output file (SPEC section 8): its mesh, effective deck and contact
boundary define the problem. The script solves, in one shot, the static problem of SPEC sections
2-3 with the FINAL values of every load curve:

    Q1 plane strain, 2x2 Gauss, Hooke law (E, nu of the deck); prescribed dofs at their final
    values (GetFEM constraint brick, Lagrange multipliers); uniform tractions on their segments
    (GetFEM source-term brick); contact with the rigid straight obstacle on Gamma_c:
      P1  nodal:     Lambda_i >= 0, d_i <= 0, Lambda_i d_i = 0, d_i = u_i.n - g_i
                     (GetFEM nodal contact-with-rigid-obstacle brick; --p1-brick basic: the
                     basic contact brick with B_N = N);
      P0  dual cell: mu_i >= 0, (D d)_i <= 0, mu_i (D d)_i = 0, F_n = D^T mu
                     (GetFEM basic contact brick with B_N = D N and gap D g);
      Tresca (both): |F_t,i| <= s_i w_i, stick if <, slip if = (nodal quadrature of the friction
                     integral), written in GetFEM's weak-form language with a nodal (Q1 trace)
                     multiplier field and the trapezoidal rule on Gamma_c: an augmented-Lagrangian
                     projection onto [-s, s], solved by the same semismooth Newton.

and writes the solution in contact2d's layout (root attribute program = 'getfem_reference'), so the
compare tools read it. REF.h5 is never IN.h5, an existing REF.h5 is replaced only with --force,
and a missing folder is refused before solving (one line, exit 2); the file is written to a
temporary file beside REF.h5 and moved into place (os.replace). docs/getfem_reference.md says what is solved, how, and how well.

Needs python3-getfem (Debian, 5.4), numpy, h5py; reads the input with contact2d.h5.
"""
import argparse
import os
import sys
import time

import h5py
import numpy as np

from .h5 import Run, parse_effective_deck
from .outfile import OutputRefused, check_target, replacing

PROGRAM = "getfem_reference"
VERSION = "1.0"
SLIP_TOL = 1.0e-8          # SPEC 3: |F_t| >= (1 - 1e-8) s_i w_i counts as slip
SIDES = ("bottom", "right", "top", "left")


class Refused(Exception):
    """The input cannot be represented by this reference (one-line message)."""


# ----------------------------------------------------------------------------------------------
# The problem, from the contact2d file
# ----------------------------------------------------------------------------------------------

def _as_list(v):
    return list(v) if isinstance(v, (list, tuple)) else [v]


def select_nodes(x, edge, group, tol):
    """Nodes of one side of the bounding box inside the group's closed range (with tolerance),
    ordered counter-clockwise along the boundary (as contact2d's mesh_select_nodes)."""
    lo, hi = x.min(axis=0), x.max(axis=0)
    if edge == "bottom":
        mask, key = np.abs(x[:, 1] - lo[1]) <= tol, x[:, 0]
    elif edge == "right":
        mask, key = np.abs(x[:, 0] - hi[0]) <= tol, x[:, 1]
    elif edge == "top":
        mask, key = np.abs(x[:, 1] - hi[1]) <= tol, -x[:, 0]
    elif edge == "left":
        mask, key = np.abs(x[:, 0] - lo[0]) <= tol, -x[:, 1]
    else:
        raise Refused("edge = '%s' is not one of %s" % (edge, ", ".join(SIDES)))
    for c, (kmin, kmax) in enumerate((("xmin", "xmax"), ("ymin", "ymax"))):
        if kmin in group:
            mask &= x[:, c] >= float(group[kmin]) - tol
        if kmax in group:
            mask &= x[:, c] <= float(group[kmax]) + tol
    nodes = np.nonzero(mask)[0]
    return nodes[np.argsort(key[nodes], kind="stable")]


def select_segments(conn, nodes):
    """Element edges with both nodes in the selection, as (nseg, 2) node pairs."""
    sel = np.zeros(conn.max() + 1, bool)
    sel[nodes] = True
    segs = []
    for a in range(4):
        b = (a + 1) % 4
        both = sel[conn[:, a]] & sel[conn[:, b]]
        segs.append(np.stack([conn[both, a], conn[both, b]], axis=1))
    return np.concatenate(segs, axis=0)


def load_shape(group, solver):
    """(times, values / final) of a load curve, or None for a zero curve."""
    values = [float(v) for v in _as_list(group["values"])]
    times = [float(t) for t in _as_list(group.get("times", solver.get("t_ramp", 1.0)))]
    if all(v == 0 for v in values):
        return None
    if values[-1] == 0:
        return ("nonproportional",)
    return (tuple(times), tuple(v / values[-1] for v in values))


def side_of(group, sides=None):
    """The bounding-box side a &dirichlet / &traction group selects: its `edge` (built-in mesh), or,
    for a Gmsh mesh's `boundary = 'name'`, the side the caller says that boundary is (`sides`,
    name -> side; the file holds no boundary names, so the caller vouches for it)."""
    if g_edge(group):
        return g_edge(group)
    name = str(group.get("boundary", ""))
    if sides and name in sides:
        return sides[name]
    raise Refused("boundary = '%s': a Gmsh boundary name; say which bounding-box side it is with "
                  "--side %s=SIDE (SIDE one of %s)" % (name, name, ", ".join(SIDES)))


def parse_sides(items):
    """--side NAME=SIDE values as {name: side}."""
    sides = {}
    for item in items:
        name, _, side = item.partition("=")
        if side not in SIDES:
            raise Refused("--side %s: '%s' is not one of %s" % (item, side, ", ".join(SIDES)))
        sides[name] = side
    return sides


def check_prescribed(path, prob):
    """Every dof with a non-zero reaction in the run (/final/reaction is 0 off the prescribed dofs)
    is prescribed here: a --side that selects too few nodes is refused."""
    with Run(path) as run:
        reaction = run.final("reaction")
    missed = (reaction != 0) & prob["free"]
    if missed.any():
        nd, cp = np.argwhere(missed)[0]
        raise Refused("node %d dof %s has a reaction in the run but is free here (check --side)"
                      % (nd + 1, "xy"[cp]))


def g_edge(group):
    return str(group.get("edge", ""))


def read_problem(path, multiplier=None, friction=None, sides=None, curved_plane=False):
    """Everything the static problem needs, from a contact2d output file.

    sides: {boundary name: bounding-box side} for the &dirichlet / &traction groups of a Gmsh mesh
    (side_of). curved_plane: accept a curved Gamma_c against a plane obstacle (every node then has
    the plane's normal, as contact2d's docs/geometry.md says; /contact/normal is checked)."""
    with Run(path) as run:
        f = run.file                       # the groups are copied whole into the reference file
        attrs = dict(run.attrs)
        if run.attr("effective_deck") is None:
            raise Refused("%s has no 'effective_deck' attribute: not a contact2d output file" % path)
        text = str(run.attr("effective_deck"))
        x = f["mesh/coordinates"][()].astype(float)
        conn = f["mesh/connectivity"][()].astype(np.int64) - 1
        has_contact = "contact" in f and "nodes" in f["contact"]
        contact_file = {}
        if has_contact:
            for name in ("nodes", "abscissa", "weight", "gap", "threshold"):
                if name in f["contact"]:
                    contact_file[name] = f["contact/" + name][()]
        copy = {"mesh": {k: f["mesh/" + k][()] for k in f["mesh"]},
                "contact": {k: f["contact/" + k][()] for k in f["contact"]} if "contact" in f else {},
                "contact_attrs": dict(f["contact"].attrs) if "contact" in f else {}}
    deck = parse_effective_deck(text)
    if conn.ndim != 2 or conn.shape[1] != 4:
        raise Refused("the mesh is not made of 4-node quadrilaterals (connectivity shape %s)" % (conn.shape,))
    nnode = x.shape[0]
    tol = 1.0e-9 * max(np.ptp(x[:, 0]), np.ptp(x[:, 1]))
    mat = deck.get("material", {})
    try:
        young, poisson = float(mat["young"]), float(mat["poisson"])
    except KeyError:
        raise Refused("the deck has no &material young/poisson")
    solver = deck.get("solver", {})

    # Dirichlet data: final values (SPEC 2; only the end state matters for a static problem)
    presc = {}
    shapes = []
    for k, g in enumerate(deck["dirichlet"], 1):
        nodes = select_nodes(x, side_of(g, sides), g, tol)
        if nodes.size == 0:
            raise Refused("&dirichlet #%d selects no node" % k)
        comp = {"x": 0, "y": 1}.get(str(g.get("component", "")).lower())
        if comp is None:
            raise Refused("&dirichlet #%d: component '%s' is not 'x' or 'y'" % (k, g.get("component")))
        value = float(_as_list(g["values"])[-1])
        for nd in nodes:
            old = presc.get((int(nd), comp))
            if old is not None and old != value:
                raise Refused("&dirichlet #%d: node %d component %s has two final values (%g, %g)"
                              % (k, nd + 1, g["component"], old, value))
            presc[(int(nd), comp)] = value
        shapes.append(load_shape(g, solver))

    # tractions: consistent nodal loads value * h/2 on the selected segments (SPEC 2)
    tractions = []
    for k, g in enumerate(deck["traction"], 1):
        nodes = select_nodes(x, side_of(g, sides), g, tol)
        segs = select_segments(conn, nodes)
        if segs.shape[0] == 0:
            raise Refused("&traction #%d selects no element edge" % k)
        comp = {"x": 0, "y": 1}.get(str(g.get("component", "")).lower())
        if comp is None:
            raise Refused("&traction #%d: component '%s' is not 'x' or 'y'" % (k, g.get("component")))
        tractions.append((segs, comp, float(_as_list(g["values"])[-1])))
        shapes.append(load_shape(g, solver))
    nonzero = [s for s in shapes if s is not None]
    proportional = all(s == nonzero[0] and len(s) == 2 for s in nonzero) if nonzero else True

    free = np.ones((nnode, 2), bool)
    for (nd, comp) in presc:
        free[nd, comp] = False

    prob = dict(path=path, attrs=attrs, deck=deck, text=text, x=x, conn=conn, nnode=nnode,
                young=young, poisson=poisson, presc=presc, tractions=tractions, free=free,
                proportional=proportional, copy=copy, contact=None, sides=sides)
    if not has_contact:
        if "contact" in deck:
            raise Refused("the deck has a &contact group but the file has no /contact/nodes")
        return prob

    c = deck["contact"]
    method = str(c.get("method", "lagrange")).lower()
    if method != "lagrange":
        raise Refused("contact:method = '%s' (a regularised problem) is not represented; only 'lagrange' "
                      "multipliers are" % method)
    mult = (multiplier or str(c.get("multiplier", attrs.get("multiplier", "P1")))).upper()
    if mult not in ("P1", "P0"):
        raise Refused("multiplier '%s' is not 'P1' or 'P0'" % mult)
    fric = (friction or str(c.get("friction", "frictionless"))).lower()
    if fric not in ("frictionless", "tresca"):
        raise Refused("friction '%s' is not 'frictionless' or 'tresca'" % fric)
    scope = str(c.get("tresca_scope", "all")).lower()
    if fric == "tresca" and scope != "all":
        raise Refused("contact:tresca_scope = '%s' makes the threshold depend on the contact state (no unique "
                      "static solution, SPEC 3); only 'all' is represented" % scope)

    nodes = contact_file["nodes"].astype(np.int64) - 1
    nc = nodes.size
    if nc < 2:
        raise Refused("Gamma_c has fewer than two nodes")
    nu_obs = np.array(_as_list(c.get("obstacle_normal", [0.0, 1.0])), float)
    nu_obs /= np.linalg.norm(nu_obs)
    point = np.array(_as_list(c.get("obstacle_point", [0.0, 0.0])), float)
    n = -nu_obs
    t = np.array([-n[1], n[0]])
    xc = x[nodes]
    h = np.linalg.norm(np.diff(xc, axis=0), axis=1)
    # Gamma_c must be one straight chain of element edges
    segs = {tuple(sorted(p)) for p in select_segments(conn, nodes).tolist()}
    for i in range(nc - 1):
        if tuple(sorted((int(nodes[i]), int(nodes[i + 1])))) not in segs:
            raise Refused("contact nodes %d and %d are not joined by an element edge" % (nodes[i] + 1, nodes[i + 1] + 1))
    if curved_plane:
        if str(c.get("obstacle", "plane")).lower() != "plane":
            raise Refused("obstacle '%s': only the plane is represented" % c.get("obstacle"))
        fn_ = copy["contact"].get("normal")
        if fn_ is None or np.abs(np.asarray(fn_, float).reshape(-1, 2) - n[None, :]).max() > 1e-12:
            raise Refused("/contact/normal is not the plane's normal at every contact node")
    elif np.abs((xc - xc[0]) @ np.array([-(xc[-1] - xc[0])[1], (xc[-1] - xc[0])[0]])).max() > tol * np.linalg.norm(xc[-1] - xc[0]):
        raise Refused("Gamma_c is not straight")
    w = np.zeros(nc)
    w[:-1] += h / 2
    w[1:] += h / 2
    gap = np.maximum((xc - point) @ nu_obs, 0.0)
    if np.any((xc - point) @ nu_obs < -1e-12 * max(np.ptp(x[:, 0]), np.ptp(x[:, 1]))):
        raise Refused("a contact node starts inside the obstacle")
    if np.any(~free[nodes][:, np.abs(n) > 1e-12]):
        raise Refused("a contact node has a prescribed normal displacement (contact2d drops such nodes)")
    # Tresca threshold s_i: uniform, or piecewise linear in the abscissa (held beyond the ends)
    absc = contact_file.get("abscissa")
    if fric == "tresca":
        if "threshold_abscissa" in c:
            s = np.interp(absc, np.array(c["threshold_abscissa"], float), np.array(c["threshold_values"], float))
        else:
            s = np.full(nc, float(c.get("threshold", 0.0)))
        if np.any(s < 0):
            raise Refused("negative Tresca threshold")
        sf = contact_file.get("threshold")
        if str(c.get("friction", "")).lower() == "tresca" and sf is not None and \
                not np.allclose(sf, s, rtol=1e-12, atol=1e-12 * max(np.abs(s).max(), 1e-300)):
            raise Refused("the deck's Tresca threshold and the file's /contact/threshold differ")
    else:
        s = np.zeros(nc)
    # contact2d: no friction force on a node whose tangential dof is prescribed (Dirichlet reaction)
    slides = np.all(free[nodes] | (np.abs(t) <= 1e-12)[None, :], axis=1)
    s_eff = np.where(slides, s, 0.0)
    # P0 coupling D (tridiagonal, SPEC 3)
    D = np.zeros((nc, nc))
    for i in range(nc - 1):
        D[i, i] += 3 * h[i] / 8
        D[i + 1, i + 1] += 3 * h[i] / 8
        D[i, i + 1] = D[i + 1, i] = h[i] / 8
    prob["contact"] = dict(nodes=nodes, nc=nc, n=n, t=t, nu=nu_obs, point=point, h=h, w=w, gap=gap, s=s,
                           s_eff=s_eff, slides=slides, D=D, multiplier=mult, friction=fric,
                           abscissa=absc, file=contact_file)
    return prob


# ----------------------------------------------------------------------------------------------
# GetFEM model and solve
# ----------------------------------------------------------------------------------------------

def _spmat(gf, nrow, ncol, rows):
    """GetFEM sparse matrix from a list of (row, cols, vals)."""
    B = gf.Spmat("empty", nrow, ncol)
    for r, cols, vals in rows:
        B.add([int(r)], [int(cc) for cc in cols], np.array([vals], float))
    return B


def _contact_state(md, prob, info, dof):
    """Contact quantities of the current GetFEM iterate, in our node order and sign conventions."""
    c = prob["contact"]
    U = md.variable("u")
    uc = U[dof[c["nodes"]]]
    lam = np.empty(c["nc"])
    lam[info["lambda_order"]] = md.variable("lambda_n")
    st = {"lambda_n": lam, "d": uc @ c["n"] - c["gap"], "ut": uc @ c["t"]}
    if "tdof" in info:
        st["lambda_t"] = md.variable("lambda_t")[info["tdof"]]
    st["active"] = int((-lam > 0).sum())
    return st


def kkt_violation(prob, st):
    """Largest violation of the discrete contact conditions (SPEC 3), relative: forces to the largest
    normal force, gaps and slips to the largest contact-node displacement."""
    c = prob["contact"]
    if c["multiplier"] == "P1":
        v = -st["lambda_n"]                       # Lambda_n (nodal force)
        dd = st["d"]
        fn = v
    else:
        v = -st["lambda_n"]                       # mu_n (per dual cell)
        dd = c["D"] @ st["d"] / c["w"]            # mean gap of the dual cell
        fn = c["D"] @ v                           # nodal normal forces
    fs = max(np.abs(v).max(), 1e-300)
    us = max(np.abs(st["d"]).max(), np.abs(st["ut"]).max(), np.abs(c["gap"]).max(), 1e-300)
    viol = [max(-v.min(), 0.0) / fs, max(dd.max(), 0.0) / us,
            np.max(np.minimum(np.abs(v) / fs, np.abs(dd) / us))]          # complementarity
    if "lambda_t" in st:
        ft = c["w"] * st["lambda_t"]
        lim = c["s_eff"] * c["w"]
        fts = max(lim.max(), np.abs(fn).max(), 1e-300)
        viol.append(max((np.abs(ft) - lim).max(), 0.0) / fts)              # |F_t| <= s w
        rub = lim > 0                                                      # no condition where s = 0
        slip = rub & (np.abs(ft) >= lim - 1e-8 * fts)
        stick = rub & ~slip
        viol.append(np.abs(st["ut"][stick]).max() / us if stick.any() else 0.0)  # no slip when stuck
        if slip.any():
            viol.append(max((-np.sign(ft[slip]) * st["ut"][slip]).max(), 0.0) / us)  # slip along F_t
    return float(max(viol))


def solve_getfem(prob, tol=1e-12, p1_brick="nodal", lsolver="auto", max_iter=100, noisy=False, r_normal=1.0,
                 r_tangential=1.0):
    """Build the GetFEM model, solve it; returns a dict of raw results and timings."""
    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    x, conn, E, nu = prob["x"], prob["conn"], prob["young"], prob["poisson"]
    nnode = prob["nnode"]
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))   # plane strain: the 2D Lame constants are the 3D ones
    mu = E / (2 * (1 + nu))
    c = prob["contact"]
    xe = x[conn]
    hmesh = float(np.linalg.norm(xe - np.roll(xe, 1, axis=1), axis=2).min())   # shortest element edge
    hmin = float(c["h"].min()) if c else hmesh

    t0 = time.perf_counter()
    # mesh: our nodes in our order; GT_QK(2,1) numbers a cell's nodes lexicographically
    m = gf.Mesh("empty", 2)
    pids = m.add_point(np.ascontiguousarray(x.T))
    if not np.array_equal(np.asarray(pids), np.arange(nnode)):
        raise RuntimeError("GetFEM renumbered the mesh points")
    gt = gf.GeoTrans("GT_QK(2,1)")
    m.add_convex(gt, np.ascontiguousarray(x[conn[:, [0, 1, 3, 2]]].transpose(2, 1, 0)))
    mfu = gf.MeshFem(m, 2)
    mfu.set_fem(gf.Fem("FEM_QK(2,1)"))
    mim = gf.MeshIm(m, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,3)"))       # 2 x 2 Gauss
    ndof = mfu.nbdof()
    # dof of (node, component): Lagrange dofs sit on the mesh points, components interleaved
    dnodes = mfu.basic_dof_nodes()
    pid = np.asarray(m.pid_from_coords(np.ascontiguousarray(dnodes[:, ::2]), 1e-6 * hmesh), np.int64)
    if np.any(pid < 0) or np.unique(pid).size != nnode:
        raise RuntimeError("could not map GetFEM dofs to mesh nodes")
    dof = np.empty((nnode, 2), np.int64)
    dof[pid, 0] = np.arange(0, ndof, 2)
    dof[pid, 1] = np.arange(1, ndof, 2)
    if not np.allclose(dnodes[:, dof[:, 1]].T, x):
        raise RuntimeError("GetFEM dof components are not interleaved as expected")

    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")

    # prescribed dofs at their final values: B u = L with Lagrange multipliers
    keys = sorted(prob["presc"])
    if keys:
        B = _spmat(gf, len(keys), ndof, [(r, [dof[nd, cp]], [1.0]) for r, (nd, cp) in enumerate(keys)])
        md.add_variable("mult_dirichlet", len(keys))
        md.add_constraint_with_multipliers("u", "mult_dirichlet", B, np.array([prob["presc"][k] for k in keys]))

    # tractions: uniform vector traction on the selected edges (source-term brick)
    region = 10
    for segs, comp, value in prob["tractions"]:
        faces = m.faces_from_pid(np.unique(segs))
        m.set_region(region, faces)
        vec = [0.0, 0.0]
        vec[comp] = value
        md.add_initialized_data("traction_%d" % region, vec)
        md.add_source_term_brick(mim, "u", "traction_%d" % region, region)
        region += 1

    info = dict(ndof=ndof, dof=dof)
    if c is not None:
        nodes, nc, n, tv = c["nodes"], c["nc"], c["n"], c["t"]
        GC = 2
        faces = np.asarray(m.faces_from_pid(nodes))
        if faces.shape[1] != nc - 1:
            raise RuntimeError("Gamma_c: found %d faces for %d nodes" % (faces.shape[1], nc))
        m.set_region(GC, faces)
        # normal contact
        if c["multiplier"] == "P1" and p1_brick == "nodal":
            obstacle = "(x-(%.17g))*(%.17g)+(y-(%.17g))*(%.17g)" % (c["point"][0], c["nu"][0], c["point"][1], c["nu"][1])
            region_dofs = np.asarray(mfu.basic_dof_on_region(GC), np.int64)
            xdofs = np.sort(region_dofs[region_dofs % 2 == 0])
            if xdofs.size != nc:
                raise RuntimeError("Gamma_c region holds %d nodes, expected %d" % (xdofs.size, nc))
            md.add_variable("lambda_n", nc)
            r_n = E * r_normal                       # N/mm: multiplier = nodal force, GetFEM's advice
            md.add_initialized_data("r_n", [r_n])
            md.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "r_n", GC, obstacle, 1)
            # the brick's multipliers follow the region's dofs in increasing order
            inv = {int(d): i for i, d in enumerate(dof[nodes, 0])}
            info["lambda_order"] = np.array([inv[int(d)] for d in xdofs])
            info["normal_kind"] = "nodal brick"
        else:
            Dm = c["D"] if c["multiplier"] == "P0" else np.eye(nc)
            rows = []
            for i in range(nc):
                js = np.nonzero(Dm[i])[0]
                cols, vals = [], []
                for j in js:
                    for cp in range(2):
                        if abs(n[cp]) > 0:
                            cols.append(dof[nodes[j], cp])
                            vals.append(Dm[i, j] * n[cp])
                rows.append((i, cols, vals))
            BN = _spmat(gf, nc, ndof, rows)
            md.add_variable("lambda_n", nc)
            # augmentation parameter in the multiplier's units (P0: MPa per mm^2 of D d)
            r_n = r_normal * (E if c["multiplier"] == "P1" else E / hmin ** 2)
            md.add_initialized_data("r_n", [r_n])
            md.add_initialized_data("gap_n", Dm @ c["gap"])
            md.add_basic_contact_brick("u", "lambda_n", "r_n", BN, "gap_n")
            info["lambda_order"] = np.arange(nc)
            info["normal_kind"] = "basic brick, B_N = %s" % ("D N" if c["multiplier"] == "P0" else "N")
        # Tresca friction with nodal quadrature: trapezoidal rule on Gamma_c, nodal multiplier
        if c["friction"] == "tresca":
            mfs = gf.MeshFem(m, 1)
            mfs.set_fem(gf.Fem("FEM_QK(2,1)"))
            sdofs = np.asarray(mfs.basic_dof_on_region(GC), np.int64)
            mft = gf.MeshFem("partial", mfs, sdofs)
            mim_c = gf.MeshIm(m, gf.Integ("IM_NC_PARALLELEPIPED(2,1)"))  # trapezoid on each face
            svals = np.zeros(mfs.nbdof())
            spid = np.asarray(m.pid_from_coords(np.ascontiguousarray(mfs.basic_dof_nodes()), 1e-6 * hmesh), np.int64)
            node_to_sdof = np.empty(nnode, np.int64)
            node_to_sdof[spid] = np.arange(mfs.nbdof())
            svals[node_to_sdof[nodes]] = c["s_eff"]
            md.add_fem_variable("lambda_t", mft)
            md.add_initialized_fem_data("s_tresca", mfs, svals)
            md.add_initialized_data("t_vec", list(tv))
            # MPa/mm; E/h would balance the two terms, but the semismooth Newton then cycles between
            # stick and slip sets on fine meshes (k = 4..6 of the paper scene); 0.01 E/h does not
            r_t = 0.01 * r_tangential * E / hmin
            md.add_initialized_data("r_t", [r_t])
            md.add_nonlinear_term(
                mim_c,
                "lambda_t*(Test_u.t_vec)"
                " + (lambda_t - min(s_tresca, max(-s_tresca, lambda_t + r_t*(u.t_vec))))*Test_lambda_t/r_t",
                GC)
            # lambda_t dofs of the contact nodes: the partial fem's (reduced) dof k extends to the
            # basic dof in row k of its extension matrix's column k
            colptr, rowind = (np.asarray(a, np.int64) for a in mft.extension_matrix().csc_ind())
            if mft.nbdof() != nc or not np.all(np.diff(colptr) == 1):
                raise RuntimeError("unexpected extension matrix of the Gamma_c multiplier fem")
            where = {int(b): k for k, b in enumerate(rowind)}
            info["tdof"] = np.array([where[int(node_to_sdof[nd])] for nd in nodes])
    t1 = time.perf_counter()

    # Newton: GetFEM's standard (semismooth) Newton, one iteration per call so that convergence is
    # judged here. GetFEM's own residual (l1 norm of the whole residual vector) mixes units and
    # divides the contact equations by the augmentation parameter, so a small value of it does not
    # prove the contact conditions. After each step the linear equations (equilibrium with the
    # multipliers' forces, prescribed values) hold to round-off; the test is that the discrete
    # contact conditions (KKT, SPEC 3) hold to tol at the new iterate. A model without contact is
    # linear: one step.
    args = ["max_iter", 1, "max_res", 0.0]
    if lsolver != "auto":
        args += ["lsolver", lsolver]
    history = []
    conv = False
    nbit = 0
    kkt = 0.0
    state = {}
    best, since_best = np.inf, 0
    for nbit in range(1, max_iter + 1):
        md.solve(*args)
        if c is None:
            conv = True
            history.append((nbit, 0.0, 0))
            break
        state = _contact_state(md, prob, info, dof)
        kkt = kkt_violation(prob, state)
        history.append((nbit, kkt, state["active"]))
        if noisy:
            print("  Newton %3d: contact KKT violation %.3e, %d nodes active" % history[-1], flush=True)
        if kkt <= tol:
            conv = True
            break
        # safeguard against cycling of the active sets: no progress in 8 iterations -> divide the
        # augmentation parameters by 10 (the solution does not depend on them)
        if kkt < 0.999 * best:
            best, since_best = kkt, 0
        else:
            since_best += 1
        if since_best >= 8:
            since_best, best = 0, np.inf
            r_n /= 10
            md.set_variable("r_n", [r_n])
            if c["friction"] == "tresca":
                r_t /= 10
                md.set_variable("r_t", [r_t])
            info["r_reductions"] = info.get("r_reductions", 0) + 1
            print("getfem_reference: note: Newton made no progress in 8 iterations; augmentation parameters "
                  "divided by 10", file=sys.stderr)
    t2 = time.perf_counter()
    # GetFEM's residual at the solution (diagnostic; for a linear model GetFEM's rhs is not a residual)
    res_l1 = float("nan")
    if c is not None:
        md.assembly("build_rhs")
        res_l1 = float(np.abs(md.rhs()).sum())

    U = md.variable("u")
    info.update(u=U[dof], iterations=int(nbit), getfem_converged=bool(conv), getfem_residual=res_l1,
                kkt=kkt, history=history, time_setup=t1 - t0, time_solve=t2 - t1)
    if c is not None:
        info.update(lambda_n=state["lambda_n"], r_n=r_n, r_t=r_t if c["friction"] == "tresca" else 0.0)
        if "lambda_t" in state:
            info["lambda_t"] = state["lambda_t"]
    info.pop("tdof", None)
    return info


# ----------------------------------------------------------------------------------------------
# Post-processing (numpy, independent of GetFEM)
# ----------------------------------------------------------------------------------------------

def element_fields(prob, u):
    """Element-average stress (mean of the 2x2 Gauss points) and the internal forces K u."""
    x, conn, E, nu = prob["x"], prob["conn"], prob["young"], prob["poisson"]
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    xe = x[conn]                       # (nel, 4, 2), counter-clockwise from bottom-left
    ue = u[conn]
    g = 1 / np.sqrt(3)
    xi_n = np.array([-1, 1, 1, -1.0])
    eta_n = np.array([-1, -1, 1, 1.0])
    stress = np.zeros((conn.shape[0], 3))
    fint = np.zeros((conn.shape[0], 4, 2))
    for xi, eta in ((-g, -g), (g, -g), (g, g), (-g, g)):
        dN = np.stack([xi_n * (1 + eta_n * eta) / 4, eta_n * (1 + xi_n * xi) / 4])   # (2, 4) d/dxi, d/deta
        J = np.einsum("ak,eki->eai", dN, xe)                                          # (nel, 2, 2)
        det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        Jinv = np.stack([np.stack([J[:, 1, 1], -J[:, 0, 1]], -1), np.stack([-J[:, 1, 0], J[:, 0, 0]], -1)], 1) / det[:, None, None]
        dNx = np.einsum("eia,ak->eik", Jinv, dN)                                      # (nel, 2, 4) d/dx, d/dy
        grad = np.einsum("eik,ekj->eji", dNx, ue)                                     # du_j/dx_i
        exx, eyy = grad[:, 0, 0], grad[:, 1, 1]
        gxy = grad[:, 0, 1] + grad[:, 1, 0]
        sxx = (lam + 2 * mu) * exx + lam * eyy
        syy = lam * exx + (lam + 2 * mu) * eyy
        sxy = mu * gxy
        stress += np.stack([sxx, syy, sxy], 1) / 4
        fint[:, :, 0] += (dNx[:, 0, :] * sxx[:, None] + dNx[:, 1, :] * sxy[:, None]) * det[:, None]
        fint[:, :, 1] += (dNx[:, 0, :] * sxy[:, None] + dNx[:, 1, :] * syy[:, None]) * det[:, None]
    f = np.zeros((prob["nnode"], 2))
    np.add.at(f, conn, fint)
    return stress, f


def external_forces(prob):
    f = np.zeros((prob["nnode"], 2))
    x = prob["x"]
    for segs, comp, value in prob["tractions"]:
        half = 0.5 * np.linalg.norm(x[segs[:, 1]] - x[segs[:, 0]], axis=1)
        np.add.at(f[:, comp], segs[:, 0], value * half)
        np.add.at(f[:, comp], segs[:, 1], value * half)
    return f


def tridiag_solve(diag, off, rhs):
    A = np.diag(diag) + np.diag(off, 1) + np.diag(off, -1)
    return np.linalg.solve(A, rhs)


def postprocess(prob, info):
    u = info["u"]
    stress, fint = element_fields(prob, u)
    fext = external_forces(prob)
    r = fint - fext                     # force the supports and the obstacle exert on the body
    free = prob["free"]
    out = dict(displacement=u, stress=stress)
    fc = np.zeros_like(r)
    c = prob["contact"]
    diag = {}
    if c is not None:
        nodes, n, t = c["nodes"], c["n"], c["t"]
        lam = info["lambda_n"]
        # GetFEM's contact multipliers are <= 0 (compressive): F_n = -lambda for P1, mu = -lambda for P0
        if c["multiplier"] == "P1":
            Fn = -lam
            mu_n = None
        else:
            mu_n = -lam
            Fn = c["D"].T @ mu_n
        if c["friction"] == "tresca":
            # trapezoidal rule: nodal force = w_i lambda_t,i (exactly 0 where s_i = 0, up to round-off)
            Ft = np.where(c["s_eff"] > 0, c["w"] * info["lambda_t"], 0.0)
        else:
            Ft = np.zeros(c["nc"])
        fc[nodes] = -Fn[:, None] * n[None, :] - Ft[:, None] * t[None, :]
        # contact forces seen by equilibrium (a check on the multipliers' ordering and signs)
        Fn_eq = -(r[nodes] @ n)
        Ft_eq = np.where(c["slides"], -(r[nodes] @ t), 0.0)
        fnorm = max(np.abs(Fn).max(), 1e-300)
        diag["contact_force_mismatch"] = max(np.abs(Fn - Fn_eq).max(), np.abs(Ft - Ft_eq).max()) / fnorm
        d = u[nodes] @ n - c["gap"]
        # status (SPEC 3): P1 judged on Lambda_n,i, P0 on the node's own dual cell mu_n,i
        touch_val = Fn if mu_n is None else mu_n
        touching = touch_val > 1e-12 * max(np.abs(touch_val).max(), 1e-300)
        limit = c["s_eff"] * c["w"]
        status = np.where(~touching, 0, np.where(
            c["friction"] != "tresca", 2,
            np.where((c["s_eff"] > 0) & (np.abs(Ft) >= (1 - SLIP_TOL) * limit), 2, 1)))
        # multiplier fields: P1 lambda = M_c^-1 F (consistent 1D mass); P0 mu_n, mu_t = D^-1 F_t
        h = c["h"]
        if c["multiplier"] == "P1":
            md_ = np.zeros(c["nc"])
            md_[:-1] += h / 3
            md_[1:] += h / 3
            fields = tridiag_solve(md_, h / 6, np.stack([Fn, Ft], 1))
            pressure, shear = fields[:, 0], fields[:, 1]
            pen = max(d.max(), 0.0)
        else:
            pressure = mu_n
            shear = np.linalg.solve(c["D"], Ft)
            pen = max((c["D"] @ d / c["w"]).max(), 0.0)
        diag["penetration_max"] = pen
        diag["negative_multiplier"] = max(-touch_val.min(), 0.0)
        diag["friction_excess"] = max((np.abs(Ft) - limit).max(), 0.0) if c["friction"] == "tresca" else 0.0
        out["contact"] = dict(normal_force=Fn, tangential_force=Ft, pressure=pressure, shear=shear,
                              status=status.astype(np.int32))
    # out-of-balance force on free dofs, contact included (SPEC 5 measure)
    rfree = np.where(free, r - fc, 0.0)
    reaction = np.where(free, 0.0, r)
    denom = max(np.abs(reaction).max(), np.abs(fext).max(), np.abs(fc).max(), 1e-300)
    diag["relative_residual"] = np.abs(rfree).max() / denom
    out["reaction"] = reaction
    out["diag"] = diag
    return out


# ----------------------------------------------------------------------------------------------
# Output in contact2d's layout
# ----------------------------------------------------------------------------------------------

def write_output(path, prob, info, out, args):
    c = prob["contact"]
    a = prob["attrs"]
    with h5py.File(path, "w") as f:
        f.attrs["program"] = PROGRAM
        f.attrs["program_version"] = VERSION
        f.attrs["format_version"] = a.get("format_version", "1.0")
        f.attrs["source_file"] = os.path.abspath(prob["path"])
        f.attrs["multiplier"] = c["multiplier"] if c else a.get("multiplier", "none")
        f.attrs["friction"] = c["friction"] if c else "none"
        f.attrs["converged"] = np.int32(1 if info["converged"] else 0)
        f.attrs["status"] = "converged" if info["converged"] else "not converged"
        f.attrs["steps"] = np.int32(0)
        f.attrs["dt"] = 0.0
        f.attrs["dt_critical"] = 0.0
        f.attrs["final_time"] = 0.0
        f.attrs["element_count"] = np.int32(prob["conn"].shape[0])
        f.attrs["node_count"] = np.int32(prob["nnode"])
        for k in ("nx", "ny", "units"):
            if k in a:
                f.attrs[k] = a[k]
        f.attrs["effective_deck"] = prob["text"]
        if "deck" in a:
            f.attrs["deck"] = a["deck"]
        f.attrs["wall_seconds"] = info["time_setup"] + info["time_solve"]
        f.attrs["time_setup_seconds"] = info["time_setup"]
        f.attrs["time_solve_seconds"] = info["time_solve"]
        f.attrs["newton_iterations"] = np.int32(info["iterations"])
        f.attrs["newton_residual"] = out["diag"]["relative_residual"]
        f.attrs["getfem_residual_l1"] = info["getfem_residual"]
        f.attrs["newton_kkt_violation"] = info["kkt"]
        f.attrs["relative_residual"] = out["diag"]["relative_residual"]
        f.attrs["tol"] = args.tol
        f.attrs["lsolver"] = args.lsolver
        f.attrs["getfem_dofs"] = np.int32(info["ndof"])
        if c:
            f.attrs["normal_contact"] = info["normal_kind"]
            f.attrs["augmentation_normal"] = info["r_n"]
            f.attrs["augmentation_tangential"] = info["r_t"]
            f.attrs["contact_force_mismatch"] = out["diag"]["contact_force_mismatch"]
            f.attrs["penetration_max"] = out["diag"]["penetration_max"]
        f.attrs["proportional_loading"] = np.int32(prob["proportional"])
        for k, v in prob["copy"]["mesh"].items():
            f.create_dataset("mesh/" + k, data=v)
        for k, v in prob["copy"]["contact"].items():
            f.create_dataset("contact/" + k, data=v)
        if "contact" in f:
            for k, v in prob["copy"]["contact_attrs"].items():
                f["contact"].attrs[k] = v
            if c:
                f["contact"].attrs["friction"] = c["friction"]
                f["contact"].attrs["multiplier"] = c["multiplier"]
                if "threshold" in f["contact"]:
                    del f["contact/threshold"]
                f.create_dataset("contact/threshold", data=c["s"])
        f.create_dataset("final/displacement", data=out["displacement"])
        f.create_dataset("final/stress", data=out["stress"])
        f.create_dataset("final/reaction", data=out["reaction"])
        if "contact" in out:
            for k, v in out["contact"].items():
                f.create_dataset("final/contact/" + k, data=v)


def main(argv=None):
    p = argparse.ArgumentParser(description="GetFEM static reference for a contact2d output file (same mesh, deck, "
                                "contact boundary); writes the solution in contact2d's HDF5 layout.")
    p.add_argument("input", help="contact2d output file (.h5)")
    p.add_argument("-o", "--output", required=True,
                   help="reference file to write (.h5; never the input, an existing file only with --force)")
    p.add_argument("--force", action="store_true", help="replace an existing output file")
    p.add_argument("--multiplier", choices=["P1", "P0"], help="default: the deck's")
    p.add_argument("--friction", choices=["frictionless", "tresca"], help="default: the deck's")
    p.add_argument("--tol", type=float, default=1e-12,
                   help="Newton stops when the discrete contact conditions hold to this relative tolerance (default 1e-12)")
    p.add_argument("--p1-brick", choices=["nodal", "basic"], default="nodal",
                   help="P1 normal contact: GetFEM's nodal rigid-obstacle brick (default) or the basic brick, B_N = N")
    p.add_argument("--lsolver", default="mumps", help="GetFEM linear solver: mumps (default), superlu, auto")
    p.add_argument("--max-iter", type=int, default=100, help="Newton iteration limit (default 100)")
    p.add_argument("--r-normal", type=float, default=1.0,
                   help="factor on the normal augmentation parameter (default 1: E for P1, E/h^2 for P0)")
    p.add_argument("--r-tangential", type=float, default=1.0,
                   help="factor on the Tresca augmentation parameter (default 1: 0.01 E/h)")
    p.add_argument("--noisy", action="store_true", help="print every Newton iteration as it happens")
    p.add_argument("--side", action="append", default=[], metavar="NAME=SIDE",
                   help="a Gmsh mesh's &dirichlet / &traction boundary NAME is the bounding-box side SIDE "
                        "(bottom, right, top, left); checked against the run's reactions")
    args = p.parse_args(argv)
    try:
        check_target(args.output, inputs=(args.input,), force=args.force)
    except OutputRefused as e:
        print("getfem_reference: refused: %s" % e, file=sys.stderr)
        return 2
    try:
        prob = read_problem(args.input, args.multiplier, args.friction, sides=parse_sides(args.side))
        if args.side:
            check_prescribed(args.input, prob)   # the sides the user named select the run's supports
    except Refused as e:
        print("getfem_reference: refused: %s: %s" % (args.input, e), file=sys.stderr)
        return 2
    except (OSError, KeyError) as e:
        print("getfem_reference: cannot read %s: %s" % (args.input, e), file=sys.stderr)
        return 2
    c = prob["contact"]
    if c is not None and c["friction"] == "tresca" and not prob["proportional"]:
        print("getfem_reference: warning: the loading is not proportional; with friction the one-shot static "
              "problem is not the quasi-static path's end state", file=sys.stderr)
    info = solve_getfem(prob, tol=args.tol, p1_brick=args.p1_brick, lsolver=args.lsolver,
                        max_iter=args.max_iter, noisy=args.noisy, r_normal=args.r_normal,
                        r_tangential=args.r_tangential)
    out = postprocess(prob, info)
    dg = out["diag"]
    # converged: GetFEM's Newton met its target and the solution balances (SPEC 5 measure)
    # and the multipliers' forces are the ones equilibrium sees (guards the dof/multiplier mapping)
    info["converged"] = (info["getfem_converged"] and dg["relative_residual"] < max(1e3 * args.tol, 1e-9)
                         and dg.get("contact_force_mismatch", 0.0) < 1e-8)
    try:
        with replacing(args.output, force=args.force) as tmp:
            write_output(tmp, prob, info, out, args)
    except (OutputRefused, OSError) as e:
        print("getfem_reference: %s not written: %s" % (args.output, e), file=sys.stderr)
        return 2
    nel = prob["conn"].shape[0]
    what = "no contact" if c is None else "%s, %s, %s" % (c["multiplier"], c["friction"], info["normal_kind"])
    print("getfem_reference: %s -> %s" % (args.input, args.output))
    print("  problem        %d Q1 elements, %d nodes, %d GetFEM dofs; %s" % (nel, prob["nnode"], info["ndof"], what))
    print("  wall time      %.4f s (set-up %.4f, solve %.4f)" % (info["time_setup"] + info["time_solve"],
                                                                info["time_setup"], info["time_solve"]))
    if c is None:
        print("  solve          linear (no contact), %s: relative residual (SPEC 5) %.2e"
              % ("converged" if info["converged"] else "NOT converged", dg["relative_residual"]))
    else:
        print("  Newton         %d iteration(s), %s: contact KKT violation %.1e (tol %.0e); relative residual (SPEC 5) "
              "%.2e; GetFEM residual (l1) %.2e"
              % (info["iterations"], "converged" if info["converged"] else "NOT converged", info["kkt"], args.tol,
                 dg["relative_residual"], info["getfem_residual"]))
        print("  history        " + ", ".join("%d: %.0e/%d" % h for h in info["history"])
              + "   (iteration: KKT violation/active nodes)")
    if c is not None:
        oc = out["contact"]
        st = oc["status"]
        print("  contact        total F_n %.10g N, total F_t %.10g N; %d separated, %d stick, %d slip; "
              "max penetration %.2e mm; multiplier/equilibrium mismatch %.1e"
              % (oc["normal_force"].sum(), oc["tangential_force"].sum(), (st == 0).sum(), (st == 1).sum(),
                 (st == 2).sum(), dg["penetration_max"], dg["contact_force_mismatch"]))
    return 0 if info["converged"] else 1


if __name__ == "__main__":
    sys.exit(main())
