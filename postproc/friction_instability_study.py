#!/usr/bin/env python3
"""Stick-slip fronts along a sliding interface: their speed against the elastic wave speeds.

    /usr/bin/python3 postproc/friction_instability_study.py [--exe build/bin/contact2d]
        [--out study/friction_instability] [--figures DIR] [--levels 0,1,2] [--dt-factors 1,0.5]
        [--reuse] [--force]

Scene: inputs/friction_instability_p1.nml (docs/verification.md section 10): an elastic block
4 x 0.5 mm pressed on a rigid plane that starts to slide along x at 1000 mm/s, Coulomb mu = 0.3,
no damping. Runs the deck at every level of --levels and every solver:dt_factor of --dt-factors
(a history sample at every step), reads history/contact_slip_velocity (docs/output.md) and
detects the fronts where a node goes from stick (slip velocity 0) to slip (contact2d.slip_fronts):
- the detachment front: after the sample where most nodes stick (t_stick), the time at which
  each node has slipped 5e-5 mm relative to the plane (50 ns of sliding at V); its speed fitted (least squares of the onset time on x) over
  each quarter of the interface, and the time it takes to cover the interface;
- the later pulses: every stick-to-slip onset after the front's last onset, linked into fronts (onsets at
  neighbouring nodes within one shear-wave transit of a node spacing, h/c_s, or one sample if
  longer); their count and median |speed|.
Each speed is printed against the shear wave speed c_s = sqrt(G/rho), the plane-strain P-wave
speed and the Rayleigh speed c_R (the root of Rayleigh's equation for the material's nu, computed
here). Prints the table (mesh convergence over the levels, time-step convergence over the
dt factors) and writes it to <out>/friction_instability.csv; draws the space-time map of the slip
velocity (x along the contact, t up from just before the interface sticks; a diverging colour
map, stick = 0 in black; the detachment onsets and lines at c_R, c_s, c_p from the first one) of
every level at the first dt factor into <figures>/friction_instability.png (--figures defaults to --out; the
tracked one: --figures docs/figures --force).

The table and figure already there are refused before any run (one line, exit 2) unless --force;
each is written beside its name and moved into place (contact2d.outfile). --reuse keeps a run only
when it is a finished run of the same deck and settings (contact2d.runner.reuse_problem).
"""
import argparse
import csv
import math
import os
import sys
from pathlib import Path

import numpy as np

from contact2d.h5 import Run
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure
from contact2d.runner import ROOT, find_exe, levels_or_exit, out_dir, run
from contact2d.slip_fronts import fronts, primary_front, slip_map, wave_speeds, window_speeds

PROG = "friction_instability_study.py"
DECK = ROOT / "inputs" / "friction_instability_p1.nml"
QUARTERS = 4
SLID = 5.0e-5      # mm: a node has detached once it has slipped this far (50 ns of sliding at V = 1000 mm/s)


def dt_factors_or_exit(text):
    try:
        out = [float(v) for v in text.split(",")]
    except ValueError:
        out = []
    if not out or any(not (math.isfinite(v) and 0.0 < v <= 1.0) for v in out):
        print("%s: refused: --dt-factors '%s' is not a list of numbers in (0, 1] (e.g. 1,0.5)" % (PROG, text),
              file=sys.stderr)
        sys.exit(2)
    return out


def one(args, level, factor):
    """Run (or reuse) one level and dt factor; measure its fronts. Returns the row and the map."""
    h5 = args.out / ("friction_instability_l%d_dt%g.h5" % (level, factor))
    sets = {"mesh:level": level, "solver:dt_factor": factor, "output:history_interval": 1, "output:xdmf": False}
    res = run(args.exe, DECK, h5, sets, threads=1, reuse=args.reuse)
    if res.returncode != 0:
        sys.exit("%s: contact2d failed on level %d, dt factor %g: %s" % (PROG, level, factor,
                                                                         res.stderr.strip().splitlines()[-1:]))
    with Run(h5) as r:
        t, x, s = slip_map(r)
        young, nu, rho = r.material
        dt = float(r.attr("dt"))
        v_plane = float(np.max(np.abs(np.asarray(r.deck["contact"]["obstacle_velocity_x"], float))))
        t_move = float(np.asarray(r.deck["contact"]["obstacle_motion_times"], float).ravel()[0])
    c = wave_speeds(young, nu, rho)
    length = float(x[-1] - x[0])
    h = float(np.min(np.diff(x)))
    pf = primary_front(t, x, s, SLID, t_from=t_move)
    edges = np.linspace(x[0], x[-1], QUARTERS + 1)
    quarter = window_speeds(x, pf["onset"], edges)
    sample = float(np.median(np.diff(t)))
    later = fronts(t, x, s, window=max(h / c["c_s"], sample), min_nodes=3,
                   t_from=np.nanmax(pf["onset"]) if np.any(np.isfinite(pf["onset"])) else t[-1])
    sp = np.array([abs(f["speed"]) for f in later])
    row = {"level": level, "dt_factor": factor, "h_mm": h, "dt_s": dt, "ncontact": len(x), "samples": len(t),
           "file_MB": os.path.getsize(h5) / 1e6, "c_s": c["c_s"], "c_R_over_c_s": c["c_R"] / c["c_s"],
           "c_p_over_c_s": c["c_p"] / c["c_s"], "t_stick_us": pf["t_stick"] * 1e6,
           "sweep_us": (np.nanmax(pf["onset"]) - np.nanmin(pf["onset"])) * 1e6 if np.any(np.isfinite(pf["onset"])) else math.nan,
           "sweep_speed_over_c_s": math.nan}
    on = pf["onset"]
    if np.any(np.isfinite(on)) and row["sweep_us"] > 0:
        row["sweep_speed_over_c_s"] = length / (row["sweep_us"] * 1e-6) / c["c_s"]
    for j, q in enumerate(quarter):
        row["front_q%d_over_c_s" % (j + 1)] = q / c["c_s"]
    row["later_fronts"] = len(later)
    row["later_median_speed_over_c_s"] = float(np.median(sp)) / c["c_s"] if len(sp) else math.nan
    row["later_fronts_subsonic_share"] = float(np.mean(sp < c["c_p"])) if len(sp) else math.nan
    return row, (t, x, s, pf, v_plane, c)


def table(rows, c):
    print("wave speeds: c_s = %.4e mm/s, c_R = %.4f c_s (Rayleigh's equation), c_p = %.4f c_s (plane strain)"
          % (c["c_s"], c["c_R"] / c["c_s"], c["c_p"] / c["c_s"]))
    heads = ["lvl", "dt/dtc", "h [mm]", "n_c", "MB", "t_stick", "sweep"] + \
            ["q%d/c_s" % (j + 1) for j in range(QUARTERS)] + ["pulses", "|c|/c_s", "<c_p"]
    print("  ".join("%8s" % h for h in heads))
    for r in rows:
        vals = ["%8d" % r["level"], "%8.2f" % r["dt_factor"], "%8.4f" % r["h_mm"], "%8d" % r["ncontact"],
                "%8.2f" % r["file_MB"], "%8.3f" % r["t_stick_us"], "%8.3f" % r["sweep_us"]]
        vals += ["%8.3f" % r["front_q%d_over_c_s" % (j + 1)] for j in range(QUARTERS)]
        vals += ["%8d" % r["later_fronts"], "%8.3f" % r["later_median_speed_over_c_s"],
                 "%8.2f" % r["later_fronts_subsonic_share"]]
        print("  ".join(vals))
    print("t_stick: the sample [us] where most nodes stick; sweep: "
          "last - first onset of the front [us]; q1..q4: the detachment front's speed fitted over each quarter of the "
          "interface from x = 0 (signed, > 0 towards +x; 'inf' where the quarter's nodes start in one sample); "
          "pulses: stick-to-slip fronts after the detachment front reaching >= 3 nodes; |c|/c_s their median speed; <c_p: "
          "the share slower than c_p")


def figure(maps, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(maps), figsize=(4.6 * len(maps) + 1.0, 6.0), sharey=True, squeeze=False)
    mesh = None
    for ax, (level, factor, (t, x, s, pf, v, c)) in zip(axes[0], maps):
        ax.set_facecolor("black")           # stick (slip velocity exactly 0) is masked: shown black
        shown = np.ma.masked_where(s == 0, s / v)
        mesh = ax.pcolormesh(x, t * 1e6, shown, cmap="RdBu_r", vmin=-3, vmax=3, shading="nearest",
                             rasterized=True)
        ok = np.isfinite(pf["onset"])
        ax.plot(x[ok], pf["onset"][ok] * 1e6, ".", color="yellow", ms=2.5, label="detachment onset")
        # reference slopes from the front's first onset: x = x0 + c (t - t0)
        if np.any(ok):
            j = int(np.nanargmin(pf["onset"]))
            t0, x0 = pf["onset"][j], x[j]
            for name, style in (("c_R", "--"), ("c_s", ":"), ("c_p", "-.")):
                tt = np.array([t0, t0 + (x[-1] - x0) / c[name]])
                ax.plot(x0 + c[name] * (tt - t0), tt * 1e6, style, color="lime", lw=1.0, label=name)
        ax.set_xlim(x[0], x[-1])
        ax.set_ylim(pf["t_stick"] * 1e6 - 0.5, t[-1] * 1e6)   # from just before the stuck state on
        ax.set_xlabel("x along the contact [mm]")
        ax.set_title("level %d (h = %.4g mm), dt = %g dt_crit" % (level, np.min(np.diff(x)), factor), fontsize=9)
    axes[0][0].set_ylabel("t [us]")
    axes[0][0].legend(fontsize=7, loc="lower right", framealpha=0.9)
    fig.colorbar(mesh, ax=axes[0].tolist(), label="slip velocity / V (stick = 0: black)", shrink=0.8)
    path = args.figures / "friction_instability.png"
    save_figure(fig, path, args.force, dpi=75)
    print("wrote %s" % path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=None)
    ap.add_argument("--out", default=str(ROOT / "study" / "friction_instability"))
    ap.add_argument("--figures", default=None, help="folder of the figure (default: --out)")
    ap.add_argument("--levels", default="0,1,2", help="mesh levels, e.g. 0-3 or 0,1,2 (default 0,1,2)")
    ap.add_argument("--dt-factors", default="1,0.5", help="solver:dt_factor values (default 1,0.5)")
    ap.add_argument("--reuse", action="store_true",
                    help="keep the runs already in --out that finished with the same deck and settings")
    ap.add_argument("--force", action="store_true",
                    help="replace the CSV in --out and the figure in --figures (refused otherwise, before any run)")
    args = ap.parse_args()
    levels = levels_or_exit(args.levels, "--levels", PROG)
    factors = dt_factors_or_exit(args.dt_factors)
    args.exe = find_exe(args.exe)
    args.out = out_dir(args.out, PROG)
    args.figures = out_dir(args.figures, PROG, "--figures") if args.figures else args.out
    refuse_existing(PROG, [args.out / "friction_instability.csv", args.figures / "friction_instability.png"],
                    args.force)
    rows, maps = [], []
    for level in levels:
        for factor in factors:
            row, m = one(args, level, factor)
            rows.append(row)
            if factor == factors[0]:
                maps.append((level, factor, m))
    table(rows, maps[0][2][5])
    path = args.out / "friction_instability.csv"
    with replacing(path, args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("wrote %s" % path)
    figure(maps, args)
    return 0


if __name__ == "__main__":
    with refusal_exits(PROG):
        sys.exit(main())
