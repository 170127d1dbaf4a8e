#!/usr/bin/env python3
"""The paper's numerical section (Baillet & Sassi 2002, section 3; SPEC sections 7, 9): one command.

    /usr/bin/python3 postproc/paper_study.py [--levels 0-6] [--out study/paper] [--threads 2] [--force]

1. Runs inputs/baillet_sassi_2002_p1.nml and _p0.nml at mesh levels k (13 2^k x 3 2^k elements,
   h = 0.1/2^k mm), tightened to tol_residual = 1e-10 so that relaxation error stays far below
   discretisation error. A converged explicit run of the same deck, level and --tol already in
   --out is reused (pass --rerun to redo it); any other file there is rerun, one line says why.
2. Errors (contact2d.compare, SPEC 9): relative energy-norm, H1-seminorm and contact-pressure
   L2 errors of every level against the finest (the reference), and the successive differences
   ||u_(k+1) - u_k|| / ||u_ref||. Least-squares rates in log h over all levels and over the three
   finest, both ways. Writes convergence.csv, rates.csv and convergence.png (the paper's Fig. 2,
   with the theoretical 3/4 slope).
3. fig1_vertical_displacement.png (Fig. 1: u_y on the deformed reference mesh) and
   fig3_contact_stress.png (Fig. 3: normal and tangential contact stress along the abscissa for
   several h, P1 against P0, stick / slip / separated zones marked).
4. p1_sign.csv: where and how much the recovered P1 pressure is tensile, against P0.
The tables and figures already in --out are refused before any run (one line, exit 2) unless
--force; each is written beside its name and moved into place (contact2d.outfile).
"""
import argparse
import csv
import sys
import time

import numpy as np

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, levels_or_exit, out_dir, reuse_problem, run
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure
from contact2d.compare import compare

MULTIPLIERS = ("P1", "P0")


def h_of(level):
    return 0.1 / 2**level


def lsq_slope(points):
    """Least-squares slope of log e against log h over the (h, e) pairs; nan with fewer than 2."""
    h = np.array([p[0] for p in points], float)
    e = np.array([p[1] for p in points], float)
    ok = e > 0
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(h[ok]), np.log(e[ok]), 1)[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--levels", default="0-6", help="mesh levels, e.g. 0-6 or 0,1,2 (finest = reference)")
    ap.add_argument("--out", default="study/paper", help="output directory (runs and figures)")
    ap.add_argument("--threads", type=int, default=None, help="OMP_NUM_THREADS for the runs")
    ap.add_argument("--tol", type=float, default=1e-10, help="solver:tol_residual of the runs")
    ap.add_argument("--rerun", action="store_true", help="redo runs even if their .h5 exists")
    ap.add_argument("--force", action="store_true",
                    help="replace the tables and figures already in --out (refused otherwise, before any run)")
    args = ap.parse_args()

    exe = find_exe(args.exe)
    levels = levels_or_exit(args.levels, "--levels", "paper_study.py")
    out = out_dir(args.out, "paper_study.py")
    ref_level = max(levels)
    products = ["convergence.csv", "fig1_vertical_displacement.png", "fig3_contact_stress.png", "p1_sign.csv"]
    refuse_existing("paper_study.py", [out / name for name in products + (["rates.csv", "convergence.png"]
                                                                           if len(levels) > 1 else [])], args.force)

    # 1. runs
    files = {}
    for m in MULTIPLIERS:
        deck = ROOT / "inputs" / f"baillet_sassi_2002_{m.lower()}.nml"
        for k in levels:
            h5 = out / f"{m.lower()}_k{k}.h5"
            sets = {"mesh:level": k, "solver:tol_residual": args.tol, "output:xdmf": k == ref_level}
            ok = h5.is_file() and not args.rerun
            if ok:
                why = reuse_problem(h5, deck, sets, statuses=("converged",))
                ok = why is None
                if not ok:
                    print(f"rerunning {h5}: {why}")
            if not ok:
                t0 = time.perf_counter()
                res = run(exe, deck, h5, sets, threads=args.threads)
                if res.returncode != 0:
                    sys.exit(f"run {m} k={k} failed: {res.stderr.strip()}")
                print(f"ran {m} k={k}: {time.perf_counter() - t0:.1f} s")
            else:
                print(f"reusing {h5}")
            files[m, k] = h5

    # 2. errors against the finest level and successive differences
    rows = []
    for m in MULTIPLIERS:
        ref = files[m, ref_level]
        for k in levels:
            row = {"multiplier": m, "level": k, "h": h_of(k)}
            with Run(files[m, k]) as r:
                row["elements"] = int(r.attrs["element_count"])
                row["steps"] = int(r.attrs["steps"])
                row["wall_seconds"] = float(r.attrs["wall_seconds"])
            if k < ref_level:
                e = compare(files[m, k], ref)["errors"]
                row.update(energy=e["energy"], h1=e["h1"], pressure_l2=e["pressure_l2"])
            if k + 1 in levels:
                e = compare(files[m, k], files[m, k + 1])["errors"]
                row.update(diff_energy=e["energy"], diff_h1=e["h1"], diff_pressure_l2=e["pressure_l2"])
            rows.append(row)
    keys = ["multiplier", "level", "h", "elements", "steps", "wall_seconds", "energy", "h1", "pressure_l2",
            "diff_energy", "diff_h1", "diff_pressure_l2"]
    with replacing(out / "convergence.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in keys})
    print(f"\nwrote {out / 'convergence.csv'} (reference: level {ref_level})")
    print(f"{'':3s}{'k':>3s} {'h':>9s} {'energy':>10s} {'H1':>10s} {'p L2':>10s} | {'diff en.':>10s} {'diff H1':>10s} {'diff p':>10s}")
    for r in rows:
        def f(key):
            return f"{r[key]:10.3e}" if key in r else " " * 10
        print(f"{r['multiplier']:3s}{r['level']:3d} {r['h']:9.2e} {f('energy')} {f('h1')} {f('pressure_l2')} | "
              f"{f('diff_energy')} {f('diff_h1')} {f('diff_pressure_l2')}")

    if len(levels) < 2:
        print(f"\none level ({levels[0]}): no errors, rates or convergence.png (they need two levels or more)")
        plot_fig1(files["P1", ref_level], out / "fig1_vertical_displacement.png", args.force)
        plot_fig3(files, levels, out / "fig3_contact_stress.png", args.force)
        p1_sign(files, levels, out / "p1_sign.csv", args.force)
        return

    rates = []
    for m in MULTIPLIERS:
        rr = [r for r in rows if r["multiplier"] == m]
        for measure in ("energy", "h1", "pressure_l2"):
            vs_ref = [(r["h"], r[measure]) for r in rr if measure in r]
            diff = [(r["h"], r["diff_" + measure]) for r in rr if "diff_" + measure in r]
            rates.append(dict(multiplier=m, measure=measure, way="against finest", levels="all",
                              rate=lsq_slope(vs_ref)))
            rates.append(dict(multiplier=m, measure=measure, way="against finest", levels="three finest",
                              rate=lsq_slope(vs_ref[-3:])))
            rates.append(dict(multiplier=m, measure=measure, way="successive differences", levels="all",
                              rate=lsq_slope(diff)))
            rates.append(dict(multiplier=m, measure=measure, way="successive differences", levels="three finest",
                              rate=lsq_slope(diff[-3:])))
    with replacing(out / "rates.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rates[0]))
        w.writeheader()
        w.writerows(rates)
    print(f"\nleast-squares rates in log h (wrote {out / 'rates.csv'}):")
    for r in rates:
        print(f"  {r['multiplier']} {r['measure']:12s} {r['way']:23s} {r['levels']:12s} {r['rate']:6.3f}")

    plot_convergence(rows, rates, out / "convergence.png", ref_level, args.force)
    plot_fig1(files["P1", ref_level], out / "fig1_vertical_displacement.png", args.force)
    plot_fig3(files, levels, out / "fig3_contact_stress.png", args.force)
    p1_sign(files, levels, out / "p1_sign.csv", args.force)


def plot_convergence(rows, rates, path, ref_level, force):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for ax, (measure, title) in zip(axes, (("energy", "displacement, energy norm"),
                                          ("pressure_l2", "contact pressure, L2(Gamma_c)"))):
        for m, color, mk, ms in zip(MULTIPLIERS, ("tab:blue", "tab:orange"), ("o", "^"), (9, 5)):
            rr = [r for r in rows if r["multiplier"] == m]
            h = np.array([r["h"] for r in rr if measure in r])
            e = np.array([r[measure] for r in rr if measure in r])
            hd = np.array([r["h"] for r in rr if "diff_" + measure in r])
            ed = np.array([r["diff_" + measure] for r in rr if "diff_" + measure in r])
            s_ref = next(x["rate"] for x in rates if x["multiplier"] == m and x["measure"] == measure
                         and x["way"] == "against finest" and x["levels"] == "all")
            s_diff = next(x["rate"] for x in rates if x["multiplier"] == m and x["measure"] == measure
                          and x["way"] == "successive differences" and x["levels"] == "three finest")
            ax.loglog(h, e, mk + "-", color=color, ms=ms, mfc="none" if m == "P1" else color,
                      label=f"{m} vs level {ref_level} (slope {s_ref:.2f})")
            ax.loglog(hd, ed, "s--", color=color, mfc="none", ms=ms,
                      label=f"{m} successive diff. (slope {s_diff:.2f}, 3 finest)")
        hh = np.array([min(h), max(h)])
        e0 = max(e) * 1.3
        ax.loglog(hh, e0 * (hh / hh[1]) ** 0.75, "k:", label="slope 3/4 (paper, H^2 solution)")
        ax.loglog(hh, e0 * 0.5 * (hh / hh[1]) ** 0.5, "k-.", lw=0.8, label="slope 1/2 (corner singularities)")
        ax.set_xlabel("h [mm]")
        ax.set_ylabel("relative error")
        ax.set_title(title)
        ax.legend(fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("Convergence of the P1 and P0 multiplier methods (cf. Baillet & Sassi 2002, Fig. 2)")
    fig.tight_layout()
    save_figure(fig, path, force, dpi=130)
    print(f"wrote {path}")


def plot_fig1(h5, path, force):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    with Run(h5) as r:
        x, conn, u = r.coordinates, r.connectivity - 1, r.displacement
    scale = 0.05 / np.abs(u).max()        # displacements magnified to 5 % of the size
    xd = x + scale * u
    uy_el = u[conn, 1].mean(axis=1)
    fig, ax = plt.subplots(figsize=(10, 3.4))
    pc = PolyCollection(xd[conn], array=uy_el, cmap="viridis", edgecolors="face", linewidths=0.2)
    ax.add_collection(pc)
    ax.autoscale()
    ax.set_aspect("equal")
    fig.colorbar(pc, ax=ax, label="u_y [mm]", shrink=0.8)
    ax.set_title(f"Vertical displacement u_y on the deformed reference mesh (cf. Fig. 1)\n"
                 f"{len(conn)} elements, displacements magnified {scale:.0f} times", fontsize=10)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    fig.tight_layout()
    save_figure(fig, path, force, dpi=130)
    print(f"wrote {path}")


def contact_curves(h5):
    """Abscissa and the multiplier fields as plottable curves (P0: steps over dual cells)."""
    with Run(h5) as r:
        s, p, q, st = r.abscissa, r.contact("pressure"), r.contact("shear"), r.contact("status")
        mult = r.attrs["multiplier"]
    if mult == "P0":
        z = np.concatenate([[s[0]], 0.5 * (s[1:] + s[:-1]), [s[-1]]])
        xs = np.repeat(z, 2)[1:-1]
        return xs, np.repeat(p, 2), np.repeat(q, 2), s, st
    return s, p, q, s, st


def plot_fig3(files, levels, path, force):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # three levels two apart (coarse to fine) so that the differences are visible
    shown = [k for k in levels if (levels[-1] - k) % 2 == 0][-3:]
    fig, axes = plt.subplots(2, 2, figsize=(12, 7.5), sharex=True)
    for col, m in enumerate(MULTIPLIERS):
        for k, ls in zip(shown, ("-", "--", ":")):
            xs, p, q, s, st = contact_curves(files[m, k])
            axes[0, col].plot(xs, p, ls, label=f"h = {h_of(k):.4f} mm")
            axes[1, col].plot(xs, q, ls, label=f"h = {h_of(k):.4f} mm")
        # zones of the finest shown level: stick / slip / separated
        _, _, _, s, st = contact_curves(files[m, shown[-1]])
        for ax in axes[:, col]:
            for code, color, name in ((1, "tab:green", "stick"), (2, "tab:red", "slip"), (0, "0.7", "separated")):
                mask = st == code
                ax.scatter(s[mask], np.full(mask.sum(), 0.0), marker="|", s=60, color=color, label=name,
                           transform=ax.get_xaxis_transform(), clip_on=False)
            ax.axhline(0, color="k", lw=0.5)
            ax.grid(alpha=0.3)
        # zoom on the edge of the contact zone, where the P1 recovered pressure turns tensile
        inset = axes[0, col].inset_axes([0.45, 0.35, 0.3, 0.4])
        for k, ls in zip(shown, ("-", "--", ":")):
            xs, p, _, _, _ = contact_curves(files[m, k])
            inset.plot(xs, p, ls)
        inset.axhline(0, color="k", lw=0.5)
        inset.set_xlim(0.6, 0.85)
        inset.set_ylim(-40, 160)
        inset.tick_params(labelsize=6)
        inset.set_title("edge of the contact zone", fontsize=7)
        axes[0, col].set_title(f"{m}: normal contact stress (pressure)")
        axes[1, col].set_title(f"{m}: tangential contact stress")
        axes[1, col].set_xlabel("curvilinear abscissa [mm]")
    axes[0, 0].set_ylabel("lambda_1 = -sigma_n [MPa]")
    axes[1, 0].set_ylabel("lambda_2 = -sigma_t [MPa]")
    for ax in axes.flat:
        ax.legend(fontsize=7, ncol=2)
    fig.suptitle("Contact stresses for several h, P1 against P0; ticks on the axis: stick / slip / separated "
                 f"(level {shown[-1]}) (cf. Fig. 3)")
    fig.tight_layout()
    save_figure(fig, path, force, dpi=130)
    print(f"wrote {path}")


def p1_sign(files, levels, path, force):
    """Where and how much the recovered P1 pressure is tensile, against P0 (which cannot be)."""
    rows = []
    for k in levels:
        for m in MULTIPLIERS:
            with Run(files[m, k]) as r:
                s, p, st = r.abscissa, r.contact("pressure"), r.contact("status")
            edge = s[st > 0].max() if np.any(st > 0) else float("nan")
            neg = p < 0
            rows.append(dict(multiplier=m, level=k, h=h_of(k), contact_edge=edge, max_pressure=p.max(),
                             min_pressure=p.min(), min_at=s[np.argmin(p)], tensile_nodes=int(neg.sum()),
                             tensile_in_contact=int((neg & (st > 0)).sum()),
                             min_over_max=p.min() / p.max()))
    with replacing(path, force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"\nsign of the recovered pressure (wrote {path}):")
    for r in rows:
        print(f"  {r['multiplier']} k={r['level']}: contact edge {r['contact_edge']:.4f} mm, min {r['min_pressure']:9.3f} MPa "
              f"at s = {r['min_at']:.4f} ({100 * r['min_over_max']:6.2f} % of the max), "
              f"{r['tensile_nodes']} tensile values ({r['tensile_in_contact']} at nodes in contact)")


if __name__ == "__main__":
    with refusal_exits("paper_study.py"):
        main()
