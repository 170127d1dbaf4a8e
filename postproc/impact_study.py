#!/usr/bin/env python3
"""Impact on the rigid plane against the exact 1D wave solution (docs/impact.md).

    /usr/bin/python3 postproc/impact_study.py [--out study/impact] [--levels 2 3 4 5]
                                              [--figures DIR] [--rerun] [--exe PATH] [--force]

Runs inputs/impact_bar_p1.nml, _p0.nml and _penalty.nml (k_p = 1e6 and 1e7 MPa/mm) at
dt/dt_critical = 0.5, 0.9, 1.0 (solver:dt_factor; dt = dt_critical is accepted, only a dt above
it is refused) and mesh levels 2-5, each with a history sample at every step. For every run it
prints and writes to <out>/impact_study.csv: the contact start against t0 = g0/v0 (in steps), the
duration against 2L/c, the mean pressure over the contact and the plateau (middle 80 %) against
rho c v0 with the rms and largest oscillation about it, the rebound velocity against v0, the
energy returned to the rebounding body (kinetic + strain at the end: the physical energies of the
last whole step, and the staggered ones of the balance; and the rigid-body part (v_reb/v0)^2), the normal contact work (kinetic energy removed by the forward increment) with the
estimate h/(2L) (the bottom row of nodes, mass rho lx h/2, stopped dead once), the largest
penetration and the energy balance error. Figures: <figures>/impact_force.png (force histories
against the exact plateau) and <figures>/impact_energy.png (energy lost and rebound error against
h); --figures defaults to --out (the tracked ones: --figures docs/figures --force). Runs are
reused when their .h5 exists (--rerun redoes them). The table and figures already there are
refused before any run (one line, exit 2) unless --force; each is written beside its name and moved into place (contact2d.outfile).
"""
import argparse
import csv
import sys
from pathlib import Path

import numpy as np

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, out_dir, run
from contact2d.impact import exact, measure
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

METHODS = [  # label, deck, extra settings
    ("P1", "impact_bar_p1.nml", {}),
    ("P0", "impact_bar_p0.nml", {}),
    ("penalty 1e6", "impact_bar_penalty.nml", {"contact:penalty_stiffness": 1.0e6}),
    ("penalty 1e7", "impact_bar_penalty.nml", {"contact:penalty_stiffness": 1.0e7}),
]
DT_RATIOS = (0.5, 0.9, 1.0)


def plt_module():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def one(args, label, deck, sets, level, ratio):
    name = "%s_l%d_dt%.2f" % (label.replace(" ", "_"), level, ratio)
    h5 = args.out / (name + ".h5")
    res = run(args.exe, ROOT / "inputs" / deck, h5,
              {"mesh:level": level, "solver:dt_factor": ratio, "output:history_interval": 1,
               "output:xdmf": False, **sets}, threads=1, reuse=not args.rerun)
    if res.returncode != 0:
        print("%s: contact2d exit %d: %s" % (name, res.returncode, res.stderr.strip().splitlines()[-1:]))
        return None
    with Run(h5) as r:
        ex = exact(r)
        me = measure(r, ex)
        ny = r.ny
    row = dict(method=label, level=level, ny=ny, h=ex["length"] / ny, dt_ratio=ratio, dt=me["dt"],
               steps=me["steps"])
    if not me["contact"]:
        print("%s: no contact" % name)
        return None
    row.update(
        start_steps=(me["start"] - ex["t0"]) / me["dt"],
        duration_err=me["duration"] / ex["duration"] - 1,
        duration_steps=(me["duration"] - ex["duration"]) / me["dt"],
        pressure_mean_err=me["pressure_mean"] / ex["pressure"] - 1,
        pressure_plateau_err=me["pressure_plateau"] / ex["pressure"] - 1,
        osc_rms=me["pressure_osc_rms"],
        osc_max=me["pressure_osc_max"],
        gaps_inside=me["gaps_inside"],
        ended=int(me["ended"]),
        rebound=me["rebound_velocity"] / ex["v0"],
        energy_returned=me["energy_returned"],
        energy_returned_staggered=me["energy_returned_staggered"],
        rigid_energy_returned=me["rigid_energy_returned"],
        normal_work=me["normal_work"],
        estimate_h_2L=ex["length"] / ny / (2 * ex["length"]),
        penetration=me["penetration_max"],
        balance=me["balance_error_max"],
    )
    row["_t"] = (me["force_time"] - ex["t0"]) / ex["duration"]
    row["_p"] = me["force"] / ex["force"]
    return row


def table(rows):
    cols = [("method", "%-11s"), ("level", "%5d"), ("dt_ratio", "%5.2f"), ("start_steps", "%+6.2f"),
            ("duration_err", "%+8.4f"), ("pressure_mean_err", "%+8.4f"), ("pressure_plateau_err", "%+8.4f"),
            ("osc_rms", "%7.4f"), ("osc_max", "%7.4f"), ("gaps_inside", "%4d"), ("rebound", "%7.4f"),
            ("energy_returned", "%7.4f"), ("energy_returned_staggered", "%7.4f"), ("rigid_energy_returned", "%7.4f"),
            ("normal_work", "%+8.5f"),
            ("estimate_h_2L", "%8.5f"), ("penetration", "%9.2e"), ("balance", "%8.1e")]
    heads = ["method", "lvl", "dt/c", "start", "dur", "p_mean", "p_plat", "osc_rms", "osc_max", "chat",
             "v_reb", "E_ret", "E_stag", "E_rigid", "W_n/E0", "h/(2L)", "penetr", "balance"]
    print("  ".join(heads))
    for r in rows:
        print("  ".join(fmt % r[c] for c, fmt in cols))
    print("start: (t_first - t0)/dt; dur: duration/(2L/c) - 1; p_mean, p_plat: mean pressure over the contact and "
          "over its middle 80 %, / (rho c v0) - 1; osc_*: |p - rho c v0|/(rho c v0) on the plateau; chat: force-free "
          "steps inside the contact; v_reb: rebound velocity / v0; E_ret: (E_kin + E_strain)/E0 at the end, the "
          "physical energies of the last whole step; E_stag: the same with the staggered energies of the balance; "
          "E_rigid: (v_reb/v0)^2; W_n/E0: normal contact work / initial kinetic energy; penetr [mm]")


def slope(x, y):
    x, y = np.log(np.asarray(x)), np.log(np.asarray(y))
    return float(np.polyfit(x, y, 1)[0])


def figures(rows, args):
    plt = plt_module()
    # force histories at the coarsest and finest level, every method and step ratio
    shown = sorted({args.levels[0], args.levels[-1]})
    fig, axes = plt.subplots(len(shown), len(METHODS), figsize=(4.2 * len(METHODS), 3.4 * len(shown)),
                             sharey=True, squeeze=False)
    for row_axes, lvl in zip(axes, shown):
        for ax, (label, _, _) in zip(row_axes, METHODS):
            for ratio, style in zip(DT_RATIOS, ("-", "--", ":")):
                r = next((r for r in rows if r["method"] == label and r["level"] == lvl and r["dt_ratio"] == ratio),
                         None)
                if r is None:
                    continue
                ax.plot(r["_t"], r["_p"], style, lw=1.2, label="dt = %.1f dt_crit" % ratio)
            ax.plot([-0.2, 0, 0, 1, 1, 1.5], [0, 0, 1, 1, 0, 0], "k-", lw=0.8, alpha=0.6, label="exact")
            ax.set_xlim(-0.1, 1.4)
            ax.set_title("%s, level %d" % (label, lvl))
            ax.set_xlabel("(t - t0) / (2L/c)")
            ax.grid(alpha=0.3)
        row_axes[0].set_ylabel("contact force / (rho c v0 lx)")
    axes[0][0].legend(fontsize=8, loc="lower center")
    fig.tight_layout()
    path = args.figures / "impact_force.png"
    save_figure(fig, path, args.force, dpi=100)
    print("wrote %s" % path)

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(14, 4))
    for label, marker in (("P1", "o"), ("P0", "x"), ("penalty 1e6", "s"), ("penalty 1e7", "^")):
        for ratio, style in zip(DT_RATIOS, ("-", "--", ":")):
            sel = sorted((r for r in rows if r["method"] == label and r["dt_ratio"] == ratio), key=lambda r: r["h"])
            if not sel:
                continue
            h = [r["h"] for r in sel]
            kw = dict(marker=marker, ls=style, label="%s, dt %.1f" % (label, ratio))
            if label.startswith("P"):
                ax1.loglog(h, [max(r["normal_work"], 1e-12) for r in sel], **kw)
            ax2.loglog(h, [max(abs(r["rebound"] - 1), 1e-6) for r in sel], **kw)
            ax3.semilogx(h, [r["energy_returned"] for r in sel], **kw)
    hs = sorted({r["h"] for r in rows})
    ax1.loglog(hs, [h / 2 for h in hs], "k-", lw=0.8, label="h/(2L): bottom row stopped once")
    ax1.set_title("kinetic energy removed by the forward increment")
    ax1.set_xlabel("h [mm]")
    ax1.set_ylabel("W_normal / E0")
    ax2.set_title("rebound velocity error")
    ax2.set_xlabel("h [mm]")
    ax2.set_ylabel("|v_reb / v0 - 1|")
    ax3.set_title("energy returned to the body")
    ax3.set_xlabel("h [mm]")
    ax3.set_ylabel("(E_kin + E_strain) / E0 at the end (whole-step state)")
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3, which="both")
    ax1.legend(fontsize=7)
    ax2.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    path = args.figures / "impact_energy.png"
    save_figure(fig, path, args.force, dpi=110)
    print("wrote %s" % path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "study" / "impact")
    ap.add_argument("--figures", type=Path, default=None,
                    help="folder of the two figures (default: --out; docs/figures holds the tracked ones)")
    ap.add_argument("--levels", type=int, nargs="+", default=[2, 3, 4, 5])
    ap.add_argument("--exe", default=None)
    ap.add_argument("--rerun", action="store_true")
    ap.add_argument("--force", action="store_true",
                    help="replace impact_study.csv in --out and the figures in --figures (refused otherwise, "
                         "before any run)")
    args = ap.parse_args()
    args.exe = find_exe(args.exe)
    args.out = out_dir(args.out, "impact_study.py")
    args.figures = out_dir(args.figures, "impact_study.py", "--figures") if args.figures else args.out
    refuse_existing("impact_study.py", [args.out / "impact_study.csv", args.figures / "impact_force.png",
                                        args.figures / "impact_energy.png"], args.force)
    rows = []
    for label, deck, sets in METHODS:
        for level in args.levels:
            for ratio in DT_RATIOS:
                r = one(args, label, deck, sets, level, ratio)
                if r is not None:
                    rows.append(r)
    table(rows)
    # trends with the mesh
    print()
    for label in ("P1", "P0"):
        for ratio in DT_RATIOS:
            sel = sorted((r for r in rows if r["method"] == label and r["dt_ratio"] == ratio), key=lambda r: r["h"])
            if len(sel) >= 2:
                print("%-4s dt %.1f: W_normal/E0 ~ h^%.2f, |v_reb/v0 - 1| ~ h^%.2f, W_normal/(h/2L) = %s" % (
                    label, ratio, slope([r["h"] for r in sel], [r["normal_work"] for r in sel]),
                    slope([r["h"] for r in sel], [abs(r["rebound"] - 1) for r in sel]),
                    ", ".join("%.2f" % (r["normal_work"] / r["estimate_h_2L"]) for r in sel)))
    path = args.out / "impact_study.csv"
    keys = [k for k in rows[0] if not k.startswith("_")]
    with replacing(path, args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print("wrote %s" % path)
    figures(rows, args)
    return 0


if __name__ == "__main__":
    with refusal_exits("impact_study.py"):
        sys.exit(main())
