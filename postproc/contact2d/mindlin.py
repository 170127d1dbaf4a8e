#!/usr/bin/python3
"""Cattaneo-Mindlin measures of a contact2d run of inputs/mindlin_cylinder_*.nml.

    postproc/mindlin.py RUN.h5 [RUN2.h5 ...] [--figure docs/figures/mindlin_shear.png [--pressed PRESSED.h5]]
    from contact2d.mindlin import measure;  m = measure("mindlin_cylinder_p1.h5")

The whole half-disk (no symmetry plane), pressed by P, then its flat side moved along x.
With the run's own P = sum F_n,i and Q = sum F_t,i (per unit thickness; t = +x on y = 0):
    a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a)            (Hertz, contact2d.cattaneo_mindlin)
    c = a sqrt(1 - Q / (mu P))                              (Cattaneo-Mindlin stick half-width)
    q(x) = mu p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2))   (shear; mu p(x) in the slip zones)
Measured:
  - the stick zone from the traction ratio (c_ratio, e_ratio): the nodes in contact with
    |F_t,i| < 0.99 mu F_n,i (STICK_RATIO) form one run of consecutive nodes; its ends are where
    the ratio, linear between nodes, crosses 0.99: c = half its length, e = its centre (the
    Cattaneo-Mindlin zone is centred, e = 0). The same from the status labels (c_fe, e_fe):
    status 1 (stick) means below the limit by 1e-8 only, and nodes at 0.999 of it count as stick,
    so that width is not a converged quantity; the ratio's is (docs/friction.md 9.2);
  - nodal tractions F_i / w_i (w_i: /contact/weight; P0: F_n = D^T mu_n, the nodal forces) against
    p(x_i) and q(x_i): largest and root-mean-square differences over the nodes with |x| < a,
    relative to mu p0 (shear) and p0 (pressure).
The formulas neglect the normal-tangential coupling (Dundurs beta = 0.29 here, not 0), which
also puts a shear on the contact during the pressing stage (the run's last /fields snapshot, the
pressed state before shearing, is measured the same way): they are compared with, not asserted (docs/friction.md 9).
Only numpy, h5py (and matplotlib for --figure).
"""
import argparse
import sys

import numpy as np

from . import cattaneo_mindlin as cm
from .h5 import Run


def stick_zone(xc, status):
    """(left end, right end, number of stick nodes, one run?) of the stick nodes along x."""
    idx = np.nonzero(status == 1)[0]
    if idx.size == 0:
        return np.nan, np.nan, 0, False
    one_run = bool(np.all(np.diff(idx) == 1))
    i0, i1 = idx.min(), idx.max()
    left = 0.5 * (xc[i0] + xc[i0 - 1]) if i0 > 0 else xc[i0]
    right = 0.5 * (xc[i1] + xc[i1 + 1]) if i1 + 1 < xc.size else xc[i1]
    return min(left, right), max(left, right), int(idx.size), one_run


#: a node sticks by the traction ratio when |F_t,i| < STICK_RATIO mu F_n,i (stick_zone_ratio)
STICK_RATIO = 0.99


def traction_ratio(fn, ft, mu):
    """|F_t,i| / (mu F_n,i) at the nodes with F_n,i > 0, NaN elsewhere."""
    ok = fn > 0
    out = np.full(fn.shape, np.nan)
    out[ok] = np.abs(ft[ok]) / (mu * fn[ok])
    return out


def stick_zone_ratio(xc, fn, ft, mu, threshold=STICK_RATIO):
    """(left end, right end, number of nodes, one run?) of the stick zone from the traction ratio:
    the nodes in contact with |F_t,i|/(mu F_n,i) < threshold, its ends where the ratio, linear
    between two nodes, crosses the threshold (midway when the neighbour carries no force).

    The status labels call a node slip only at the limit to 1e-8 (SPEC 3), so a node at 0.999 of
    it is 'stick' though it slides in all but name; where the edge of the labelled zone falls
    then depends on how close to the limit the relaxation stopped. The ratio crosses the threshold
    at a point that converges with the mesh."""
    r = traction_ratio(fn, ft, mu)
    idx = np.nonzero(np.isfinite(r) & (r < threshold))[0]
    if idx.size == 0:
        return np.nan, np.nan, 0, False
    one_run = bool(np.all(np.diff(idx) == 1))

    def end(i, j):
        if j < 0 or j >= xc.size:
            return xc[i]
        if not np.isfinite(r[j]) or r[j] <= r[i]:
            return 0.5 * (xc[i] + xc[j])
        return xc[i] + (threshold - r[i]) / (r[j] - r[i]) * (xc[j] - xc[i])

    i0, i1 = idx.min(), idx.max()
    left, right = end(i0, i0 - 1), end(i1, i1 + 1)
    return min(left, right), max(left, right), int(idx.size), one_run


def _state(xc, w, fn, ft, status, mu, P, Q, R, E, nu):
    a, p0 = cm.hertz(P, R, E, nu)
    ratio = Q / (mu * P)
    c = cm.stick_half_width(a, Q, mu, P) if 0 <= ratio <= 1 else np.nan
    left, right, nstick, one_run = stick_zone(xc, status)
    c_fe, e_fe = 0.5 * (right - left), 0.5 * (right + left)
    rleft, rright, nstick_r, one_run_r = stick_zone_ratio(xc, fn, ft, mu)
    c_r, e_r = 0.5 * (rright - rleft), 0.5 * (rright + rleft)
    inside_c = fn > 0
    h = float(np.median(np.diff(xc)[inside_c[:-1] & inside_c[1:]])) if np.count_nonzero(inside_c) > 1 else np.nan
    inside = np.abs(xc) < a
    p_fe, q_fe = fn / w, ft / w
    p_ex = cm.pressure(xc, a, p0)
    q_ex = cm.shear(xc, a, c, mu, p0) if np.isfinite(c) else np.full_like(xc, np.nan)
    dq, dp = (q_fe - q_ex)[inside] / (mu * p0), (p_fe - p_ex)[inside] / p0
    slip = status == 2
    return dict(P=P, Q=Q, ratio=ratio, a=a, p0=p0, c=c, c_over_a=c / a, c_fe=c_fe, e_fe=e_fe,
                c_fe_over_a=c_fe / a, e_fe_over_a=e_fe / a, nstick=nstick, stick_one_run=one_run,
                c_ratio_over_a=c_r / a, e_ratio_over_a=e_r / a, nstick_ratio=nstick_r, stick_ratio_one_run=one_run_r,
                h_over_a=h / a, traction_ratio=traction_ratio(fn, ft, mu),
                nslip_trailing=int(np.count_nonzero(slip & (xc < e_fe))),
                nslip_leading=int(np.count_nonzero(slip & (xc > e_fe))),
                shear_max=float(np.abs(dq).max()), shear_rms=float(np.sqrt(np.mean(dq ** 2))),
                pressure_max=float(np.abs(dp).max()), pressure_rms=float(np.sqrt(np.mean(dp ** 2))),
                x=xc, p_fe=p_fe, q_fe=q_fe, p_ex=p_ex, q_ex=q_ex, status=status)


def measure(path):
    """Final state, and the pressed state (key 'stage1': the run's last /fields snapshot, at the
    start of the shearing stage in the shipped decks) when the run has one."""
    with Run(path) as run:
        deck = run.deck
        x = run.coordinates
        nodes = run.contact_nodes
        w = run.contact_setup("weight")
        fn = run.contact("normal_force")
        ft = run.contact("tangential_force")
        status = run.contact("status")
        reaction = run.final("reaction")
        mult = run.attr("multiplier")
        conv = int(run.attr("converged"))
        snaps = run.snapshots()
        snap = None
        if snaps:
            g = snaps[-1]                                # the last: the pressed state before shearing
            snap = (float(g.attrs["time"]), g["contact_normal_force"][()], g["contact_tangential_force"][()])
        hist = {k: run.history(k) for k in ("time", "status_changes")}
    E, nu = float(deck["material"]["young"]), float(deck["material"]["poisson"])
    mu = float(deck["contact"]["friction_coefficient"])
    R = float(np.max(x[:, 1]) - np.min(x[:, 1]))       # the flat side's height above the contact point
    xc = x[nodes, 0]
    out = _state(xc, w, fn, ft, status, mu, float(fn.sum()), float(ft.sum()), R, E, nu)
    out.update(path=path, multiplier=mult, converged=conv, mu=mu, R=R, E=E, nu=nu,
               reaction=reaction.sum(axis=0), status_changes=int(hist["status_changes"].sum()), hist=hist)
    if snap is not None:
        t1, fn1, ft1 = snap
        # at the end of stage 1 no tangential load: Q = 0, c = a; the status from the forces
        lim = mu * fn1
        st1 = np.where(fn1 > 0, np.where(np.abs(ft1) >= (1 - 1e-8) * lim, 2, 1), 0)
        s1 = _state(xc, w, fn1, ft1, st1, mu, float(fn1.sum()), 0.0, R, E, nu)
        s1["time"] = t1
        out["stage1"] = s1
    return out


def report(m):
    lines = ["%s (%s, mu = %g, %s)" % (m["path"], m["multiplier"], m["mu"],
                                      "converged" if m["converged"] else "NOT converged"),
             "  P = %.6g N/mm, Q = %.6g N/mm, Q/(mu P) = %.4f; reaction of the flat side (%.6g, %.6g)"
             % (m["P"], m["Q"], m["ratio"], m["reaction"][0], m["reaction"][1]),
             "  Hertz a = %.4f mm, p0 = %.1f MPa; Cattaneo-Mindlin c/a = %.3f" % (m["a"], m["p0"], m["c_over_a"]),
             "  stick zone from the traction ratio |F_t|/(mu F_n) < %g: %d nodes, c/a = %.3f (difference %+.3f), "
             "centre e/a = %+.3f; contact edge h/a = %.3f" % (STICK_RATIO, m["nstick_ratio"], m["c_ratio_over_a"],
                                                            m["c_ratio_over_a"] - m["c_over_a"], m["e_ratio_over_a"],
                                                            m["h_over_a"]),
             "  stick zone from the status labels: %d nodes, c_fe/a = %.3f (difference %+.3f), centre e/a = %+.3f; "
             "slip nodes trailing %d, leading %d" % (m["nstick"], m["c_fe_over_a"], m["c_fe_over_a"] - m["c_over_a"],
                                                     m["e_fe_over_a"], m["nslip_trailing"], m["nslip_leading"]),
             "  shear F_t/w - q(x) over |x| < a: max %.3f, rms %.3f (of mu p0); pressure F_n/w - p(x): max %.3f, "
             "rms %.3f (of p0)" % (m["shear_max"], m["shear_rms"], m["pressure_max"], m["pressure_rms"]),
             "  status changes in the run: %d" % m["status_changes"]]
    if "stage1" in m:
        s = m["stage1"]
        lines.append("  pressed state (t = %.4g s, no tangential load): P = %.6g, Q = %.4g N/mm; inner stick zone "
                     "(ratio < %g): c/a = %.3f, centre %+.3f (labels: %.3f); shear max %.3f, rms %.3f (of mu p0) "
                     "against q = 0" % (s["time"], s["P"], s["Q"], STICK_RATIO, s["c_ratio_over_a"], s["e_ratio_over_a"],
                                        s["c_fe_over_a"], s["shear_max"], s["shear_rms"]))
    return "\n".join(lines)


def figure(ms, path, pressed=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 1, figsize=(7.5, 4.6))
    m0 = ms[0]
    a, p0, mu = m0["a"], m0["p0"], m0["mu"]
    xs = np.linspace(-1.15 * a, 1.15 * a, 801)
    ax.plot(xs / a, mu * cm.pressure(xs, a, p0) / (mu * p0), "k:", lw=1, label=r"$\mu p(x)$ (Hertz)")
    ax.plot(xs / a, cm.shear(xs, a, m0["c"], mu, p0) / (mu * p0), "k-", lw=1,
            label=r"Cattaneo-Mindlin $q(x)$, $c/a$ = %.2f" % m0["c_over_a"])
    marks = {"P1": "o", "P0": "s"}
    for m in ms:
        mk = marks.get(m["multiplier"], "^")
        ax.plot(m["x"] / a, m["q_fe"] / (mu * p0), mk + "-", ms=4, lw=0.8, mfc="none",
                label=r"%s: $F_{t,i}/w_i$, stick zone ($|F_t|/\mu F_n$ < %g) $c/a$ = %.2f, centre %+.2f"
                % (m["multiplier"], STICK_RATIO, m["c_ratio_over_a"], m["e_ratio_over_a"]))
    if pressed is not None:
        ax.plot(pressed["x"] / a, pressed["q_fe"] / (mu * p0), "x--", ms=4, lw=0.6, color="0.5",
                label="%s pressed only (no shear stroke), converged: Q = %.2g N/mm"
                % (pressed["multiplier"], pressed["Q"]))
    ax.axhline(0, color="0.8", lw=0.5)
    ax.set_xlim(-1.15, 1.15)
    ax.set_xlabel("x / a")
    ax.set_ylabel(r"shear / $\mu p_0$")
    ax.set_title("mindlin_cylinder: Q/(mu P) = %.3f, mu = %g, a = %.3f mm" % (m0["ratio"], mu, a), fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print("figure: " + path)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--figure")
    p.add_argument("--pressed", help="a run of the same deck without the shear stroke (its final state is drawn)")
    args = p.parse_args(argv)
    ms = [measure(r) for r in args.runs]
    for m in ms:
        print(report(m))
    if args.figure:
        pressed = measure(args.pressed) if args.pressed else None
        if pressed is not None:
            print(report(pressed))
        figure(ms, args.figure, pressed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
