#!/usr/bin/python3
"""GetFEM quasi-static Coulomb reference for a contact2d run (P1 multipliers).

    postproc/getfem_coulomb.py IN.h5 -o REF.h5 [--force] [--increments 20] [--tol 1e-12] [--side NAME=SIDE ...]
                               [--from-snapshot TIME]

IN.h5 is a contact2d output file of a deck with `contact:friction = 'coulomb'` and P1 multipliers.
Its mesh, effective deck and contact boundary define the problem (read by getfem_reference.py's
read_problem, so the same body, Dirichlet and traction data, obstacle, Gamma_c, n, t, g_i).
Gamma_c may be curved (a Gmsh mesh, e.g. mindlin_cylinder) when the obstacle is a plane: every
node then has the plane's normal and tangent (docs/geometry.md; /contact/normal is checked). A Gmsh
deck's `boundary = 'name'` groups are mapped to bounding-box sides with --side name=side (the file
holds no boundary names); every dof with a reaction in the run must then be prescribed here.
Coulomb friction is path dependent, so the reference follows the deck's load path
quasi-statically: the time axis of the load curves is cut at every stage end of every curve, each
interval into --increments equal steps; at each step the static problem is solved with the loads
of that time and Coulomb friction on the slip increment since the previous step
(docs/friction.md section 5):

    normal  (P1, per node):  F_n,i >= 0, d_i <= 0, F_n,i d_i = 0
    Coulomb (per node):      |F_t,i| <= mu F_n,i; stick (du_t,i = 0) if <; slip if =, du_t,i of
                             the sign of F_t,i;  du_t,i = (u_i - u_i^prev).t

GetFEM: the basic contact brick (add_basic_contact_brick) with B_N = N (row i: n^T on node i,
what the nodal rigid-obstacle brick builds; the two agree to 1e-14, docs/getfem_reference.md),
B_T = T (row i: t^T on node i), friction coefficient mu (0 where the tangential dof is
prescribed), the initial gaps, alpha = 1, Alart-Curnier (version 1), and the brick's "dynamic"
friction data gamma = -1, wt = u^prev, which makes the tangential law act on B_T (u - u^prev).
Forces: the brick's multipliers are <= 0 in compression; F_n = -lambda_n, F_t = -lambda_t (the
force on the body -F_n n - F_t t = B_N^T lambda_n + B_T^T lambda_t). Newton stops when the
incremental KKT conditions above hold to --tol (relative), checked here, not by GetFEM's residual.

Writes REF.h5 in contact2d's layout (as getfem_reference.py) with root attributes
program = 'getfem_coulomb', increments, steps (solves), newton_iterations (total). As
getfem_reference.py (contact2d.outfile): REF.h5 is never IN.h5, an existing REF.h5 is replaced
only with --force, a missing folder is refused before solving (one line, exit 2), and the file is
written beside REF.h5 and moved into place when complete.
P0 is not represented: GetFEM's brick pairs each tangential row with the normal row of the same
index (|lambda_t,i| <= mu |lambda_n,i|), so with B_N = D N it would bound dual-cell tangential
multipliers by mu_n,i, not the nodal forces F_t,i by mu (D^T mu_n)_i as contact2d does.
"""
import argparse
import sys
import time

import h5py
import numpy as np

from . import getfem_reference as gr
from .h5 import Run
from .outfile import OutputRefused, check_target, replacing

PROGRAM = "getfem_coulomb"
SLIP_TOL = gr.SLIP_TOL


def ramp(tau):
    """SPEC section 5: r(tau) = tau - sin(2 pi tau)/(2 pi) on [0, 1], held after."""
    tau = min(max(tau, 0.0), 1.0)
    return tau - np.sin(2 * np.pi * tau) / (2 * np.pi)


def curve_value(values, times, t):
    """A multi-stage load curve at time t (each stage ramps from the previous value to its own)."""
    out, prev_v, prev_t = 0.0, 0.0, 0.0
    for v, tk in zip(values, times):
        if t > prev_t:
            out = prev_v + (v - prev_v) * ramp((t - prev_t) / (tk - prev_t))
        prev_v, prev_t = v, tk
    return out


def load_path(prob, sides=None):
    """Dirichlet (node, comp) -> (values, times); traction list with (values, times); breakpoints."""
    deck, x = prob["deck"], prob["x"]
    solver = deck.get("solver", {})
    tol = 1.0e-9 * max(np.ptp(x[:, 0]), np.ptp(x[:, 1]))
    curves, breaks = {}, set()
    for g in deck["dirichlet"]:
        nodes = gr.select_nodes(x, gr.side_of(g, sides), g, tol)
        comp = {"x": 0, "y": 1}[str(g["component"]).lower()]
        vals = [float(v) for v in gr._as_list(g["values"])]
        tms = [float(v) for v in gr._as_list(g.get("times", solver.get("t_ramp", 1.0)))]
        breaks.update(tms)
        for nd in nodes:
            curves[(int(nd), comp)] = (vals, tms)
    tractions = []
    for (segs, comp, _), g in zip(prob["tractions"], deck["traction"]):
        vals = [float(v) for v in gr._as_list(g["values"])]
        tms = [float(v) for v in gr._as_list(g.get("times", solver.get("t_ramp", 1.0)))]
        breaks.update(tms)
        tractions.append((segs, comp, vals, tms))
    return curves, tractions, sorted(breaks)


def solve(prob, mu_f, increments=20, tol=1e-12, max_iter=60, r_factor=1.0, noisy=False, start=None):
    """start: None (from the undeformed state at t = 0) or (t0, u0): follow the path from time t0,
    with u0 (nnode, 2) as the previous state (the friction law's reference)."""
    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    x, conn, E, nu = prob["x"], prob["conn"], prob["young"], prob["poisson"]
    nnode = prob["nnode"]
    c = prob["contact"]
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    xe = x[conn]
    hmesh = float(np.linalg.norm(xe - np.roll(xe, 1, axis=1), axis=2).min())
    t0 = time.perf_counter()
    m = gf.Mesh("empty", 2)
    m.add_point(np.ascontiguousarray(x.T))
    m.add_convex(gf.GeoTrans("GT_QK(2,1)"), np.ascontiguousarray(x[conn[:, [0, 1, 3, 2]]].transpose(2, 1, 0)))
    mfu = gf.MeshFem(m, 2)
    mfu.set_fem(gf.Fem("FEM_QK(2,1)"))
    mim = gf.MeshIm(m, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,3)"))
    ndof = mfu.nbdof()
    dnodes = mfu.basic_dof_nodes()
    pid = np.asarray(m.pid_from_coords(np.ascontiguousarray(dnodes[:, ::2]), 1e-6 * hmesh), np.int64)
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
    curves, tractions, breaks = load_path(prob, prob.get("sides"))
    keys = sorted(curves)
    if keys:
        B = gr._spmat(gf, len(keys), ndof, [(r, [dof[nd, cp]], [1.0]) for r, (nd, cp) in enumerate(keys)])
        md.add_variable("mult_dirichlet", len(keys))
        md.add_initialized_data("dirichlet_values", np.zeros(len(keys)))
        md.add_constraint_with_multipliers("u", "mult_dirichlet", B, "dirichlet_values")
    region = 10
    tnames = []
    for segs, comp, vals, tms in tractions:
        m.set_region(region, m.faces_from_pid(np.unique(segs)))
        md.add_initialized_data("traction_%d" % region, [0.0, 0.0])
        md.add_source_term_brick(mim, "u", "traction_%d" % region, region)
        tnames.append(("traction_%d" % region, comp, vals, tms))
        region += 1
    nodes, nc, n, tv = c["nodes"], c["nc"], c["n"], c["t"]
    rows_n = [(i, [dof[nodes[i], cp] for cp in range(2) if abs(n[cp]) > 0],
               [n[cp] for cp in range(2) if abs(n[cp]) > 0]) for i in range(nc)]
    rows_t = [(i, [dof[nodes[i], cp] for cp in range(2) if abs(tv[cp]) > 0],
               [tv[cp] for cp in range(2) if abs(tv[cp]) > 0]) for i in range(nc)]
    BN = gr._spmat(gf, nc, ndof, rows_n)
    BT = gr._spmat(gf, nc, ndof, rows_t)
    coef = np.where(c["slides"], mu_f, 0.0)
    md.add_variable("lambda_n", nc)
    md.add_variable("lambda_t", nc)
    r = E * r_factor
    md.add_initialized_data("r", [r])
    md.add_initialized_data("friction_coeff", coef)
    md.add_initialized_data("gap", c["gap"])
    md.add_initialized_data("alpha", np.ones(nc))
    md.add_initialized_data("gamma", [-1.0])
    md.add_initialized_data("wt", np.zeros(ndof))
    md.add_basic_contact_brick("u", "lambda_n", "lambda_t", "r", BN, BT, "friction_coeff", "gap", "alpha", 1,
                               "gamma", "wt")
    t1 = time.perf_counter()

    # time points: every breakpoint interval cut into `increments` equal steps
    tpts = []
    prev = 0.0 if start is None else start[0]
    for b in breaks:
        if b <= prev:
            continue
        tpts += list(prev + (b - prev) * np.arange(1, increments + 1) / increments)
        prev = b
    u_prev = np.zeros(ndof)
    if start is not None:
        u_prev[dof[:, 0]] = start[1][:, 0]
        u_prev[dof[:, 1]] = start[1][:, 1]
        md.set_variable("u", u_prev)
    total_it, worst_kkt, history, reductions = 0, 0.0, [], 0
    ok = True
    for k, tk in enumerate(tpts):
        if keys:
            md.set_variable("dirichlet_values", np.array([curve_value(*curves[key], tk) for key in keys]))
        for name, comp, vals, tms in tnames:
            vec = [0.0, 0.0]
            vec[comp] = curve_value(vals, tms, tk)
            md.set_variable(name, vec)
        md.set_variable("wt", u_prev)
        conv, kkt = False, np.inf
        best, since_best = np.inf, 0
        for it in range(1, max_iter + 1):
            md.solve("max_iter", 1, "max_res", 0.0, "lsolver", "mumps")
            U = md.variable("u")
            fn = -md.variable("lambda_n")
            ft = -md.variable("lambda_t")
            kkt = kkt_incremental(c, coef, U[dof[nodes]], u_prev[dof[nodes]], fn, ft, float(np.abs(U).max()))
            if noisy:
                print("  t %.4e Newton %2d: KKT %.2e" % (tk, it, kkt), flush=True)
            if kkt <= tol:
                conv = True
                break
            # safeguard against cycling of the stick/slip sets (as getfem_reference.py): no progress
            # in 8 iterations -> divide the augmentation parameter by 10 (the solution does not
            # depend on it)
            if kkt < 0.999 * best:
                best, since_best = kkt, 0
            else:
                since_best += 1
            if since_best >= 8:
                best, since_best = np.inf, 0
                r /= 10
                md.set_variable("r", [r])
                reductions += 1
        total_it += it
        worst_kkt = max(worst_kkt, kkt)
        history.append((tk, it, kkt))
        ok = ok and conv
        u_prev = np.array(md.variable("u"))
    t2 = time.perf_counter()
    U = md.variable("u")
    return dict(u=U[dof], fn=-md.variable("lambda_n"), ft=-md.variable("lambda_t"), coef=coef, converged=ok,
                iterations=total_it, steps=len(tpts), kkt=worst_kkt, history=history, ndof=ndof,
                time_setup=t1 - t0, time_solve=t2 - t1, r=r, reductions=reductions)


def kkt_incremental(c, coef, uc, uc_prev, fn, ft, umax):
    """Largest violation of the incremental P1 Coulomb conditions: forces relative to the largest
    normal force, lengths to the largest displacement of the body (umax; the contact nodes alone
    can all sit still, closed and stuck, and then give no length scale)."""
    d = uc @ c["n"] - c["gap"]
    du = (uc - uc_prev) @ c["t"]
    fs = max(np.abs(fn).max(), 1e-300)
    us = max(umax, np.abs(c["gap"]).max(), 1e-300)
    viol = [max(-fn.min(), 0.0) / fs, max(d.max(), 0.0) / us, np.max(np.minimum(np.abs(fn) / fs, np.abs(d) / us))]
    lim = coef * np.maximum(fn, 0.0)
    viol.append(max((np.abs(ft) - lim).max(), 0.0) / fs)
    viol.append(np.abs(ft[coef == 0]).max() / fs if np.any(coef == 0) else 0.0)
    rub = lim > 1e-12 * fs
    slip = rub & (np.abs(ft) >= lim * (1 - 1e-8))
    stick = rub & ~slip
    viol.append(np.abs(du[stick]).max() / us if stick.any() else 0.0)
    if slip.any():
        viol.append(max((-np.sign(ft[slip]) * du[slip]).max(), 0.0) / us)
    return float(max(viol))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("input")
    p.add_argument("-o", "--output", required=True,
                   help="reference file to write (.h5; never the input, an existing file only with --force)")
    p.add_argument("--force", action="store_true", help="replace an existing output file")
    p.add_argument("--increments", type=int, default=20, help="steps per load-curve interval (default 20)")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--max-iter", type=int, default=60)
    p.add_argument("--noisy", action="store_true")
    p.add_argument("--from-snapshot", type=float, metavar="TIME",
                   help="start from the run's /fields snapshot at TIME (the first at or after it): its time "
                        "and displacement are the previous state of the first increment (a relaxed hold "
                        "before it makes it an equilibrium)")
    p.add_argument("--side", action="append", default=[], metavar="NAME=SIDE",
                   help="a Gmsh mesh's &dirichlet / &traction boundary NAME is the bounding-box side SIDE "
                        "(bottom, right, top, left); checked against the run's reactions")
    args = p.parse_args(argv)
    try:
        check_target(args.output, inputs=(args.input,), force=args.force)
    except OutputRefused as e:
        print("getfem_coulomb: refused: %s" % e, file=sys.stderr)
        return 2
    try:
        prob = gr.read_problem(args.input, friction="frictionless", sides=gr.parse_sides(args.side),
                               curved_plane=True)
        gr.check_prescribed(args.input, prob)
        c = prob["contact"]
        if c is None:
            raise gr.Refused("the run has no contact")
        cd = prob["deck"]["contact"]
        if str(cd.get("friction", "")).lower() != "coulomb":
            raise gr.Refused("contact:friction is '%s', not 'coulomb'" % cd.get("friction"))
        if c["multiplier"] != "P1":
            raise gr.Refused("multiplier %s: only P1 is represented (see the module docstring)" % c["multiplier"])
        mu_f = float(cd["friction_coefficient"])
    except gr.Refused as e:
        print("getfem_coulomb: refused: %s: %s" % (args.input, e), file=sys.stderr)
        return 2
    start = None
    if args.from_snapshot is not None:
        with Run(args.input) as run:
            snaps = [(float(g.attrs["time"]), g) for g in run.snapshots()
                     if float(g.attrs["time"]) >= args.from_snapshot * (1 - 1e-9)]
            if not snaps:
                print("getfem_coulomb: refused: %s: no /fields snapshot at or after t = %g"
                      % (args.input, args.from_snapshot), file=sys.stderr)
                return 2
            start = (snaps[0][0], snaps[0][1]["displacement"][()])
        print("getfem_coulomb: starting from the snapshot at t = %.9g s" % start[0])
    info = solve(prob, mu_f, args.increments, args.tol, args.max_iter, noisy=args.noisy, start=start)
    c = prob["contact"]
    fn, ft, coef = info["fn"], info["ft"], info["coef"]
    info_ref = dict(u=info["u"], lambda_n=-fn, converged=info["converged"], iterations=info["iterations"],
                    getfem_residual=float("nan"), kkt=info["kkt"], time_setup=info["time_setup"],
                    time_solve=info["time_solve"], ndof=info["ndof"], normal_kind="basic brick, B_N = N, Coulomb",
                    r_n=info["r"], r_t=info["r"])
    # contact2d's status rule (SPEC 3) with the Coulomb limit mu F_n,i
    out = gr.postprocess(prob, dict(info_ref, lambda_t=np.zeros(c["nc"])))
    touching = fn > 1e-12 * max(np.abs(fn).max(), 1e-300)
    lim = coef * fn
    status = np.where(~touching, 0, np.where((lim > 0) & (np.abs(ft) >= (1 - SLIP_TOL) * lim), 2, 1))
    h = c["h"]
    md_ = np.zeros(c["nc"])
    md_[:-1] += h / 3
    md_[1:] += h / 3
    fields = gr.tridiag_solve(md_, h / 6, np.stack([fn, ft], 1))
    out["contact"].update(normal_force=fn, tangential_force=ft, pressure=fields[:, 0], shear=fields[:, 1],
                          status=status.astype(np.int32))
    # residual with the friction forces included
    stress, fint = gr.element_fields(prob, info["u"])
    fext = gr.external_forces(prob)
    fc = np.zeros_like(fint)
    fc[c["nodes"]] = -fn[:, None] * c["n"][None, :] - ft[:, None] * c["t"][None, :]
    rr = fint - fext
    rfree = np.where(prob["free"], rr - fc, 0.0)
    denom = max(np.abs(np.where(prob["free"], 0.0, rr)).max(), np.abs(fext).max(), np.abs(fc).max(), 1e-300)
    out["diag"]["relative_residual"] = float(np.abs(rfree).max() / denom)
    info_ref["converged"] = info["converged"] and out["diag"]["relative_residual"] < max(1e3 * args.tol, 1e-9)

    class A:
        pass
    a = A()
    a.tol, a.lsolver = args.tol, "mumps"
    try:
        with replacing(args.output, force=args.force) as tmp:
            gr.write_output(tmp, prob, info_ref, out, a)
            with h5py.File(tmp, "r+") as f:
                f.attrs["program"] = PROGRAM
                f.attrs["friction"] = "coulomb"
                f.attrs["friction_coefficient"] = mu_f
                f.attrs["increments"] = np.int32(args.increments)
                f.attrs["steps"] = np.int32(info["steps"])
                f["contact"].attrs["friction"] = "coulomb"
    except (OutputRefused, OSError) as e:
        print("getfem_coulomb: %s not written: %s" % (args.output, e), file=sys.stderr)
        return 2
    print("getfem_coulomb: %s -> %s" % (args.input, args.output))
    print("  problem        %d Q1 elements, %d GetFEM dofs; P1 Coulomb mu = %g, basic brick B_N = N, B_T = T"
          % (prob["conn"].shape[0], info["ndof"], mu_f))
    print("  path           %d load steps (%d per interval), %d Newton iterations, worst KKT %.1e (tol %.0e), "
          "%s; augmentation divided by 10 %d time(s)" % (info["steps"], args.increments, info["iterations"], info["kkt"],
                  args.tol, "converged" if info_ref["converged"] else "NOT converged", info["reductions"]))
    print("  wall time      %.3f s (set-up %.3f, solve %.3f); relative residual (SPEC 5) %.2e"
          % (info["time_setup"] + info["time_solve"], info["time_setup"], info["time_solve"],
             out["diag"]["relative_residual"]))
    print("  contact        total F_n %.10g N, total F_t %.10g N; %d separated, %d stick, %d slip"
          % (fn.sum(), ft.sum(), (status == 0).sum(), (status == 1).sum(), (status == 2).sum()))
    return 0 if info_ref["converged"] else 1


if __name__ == "__main__":
    sys.exit(main())
