#!/usr/bin/env python3
"""Geometry verification study: Hertz and Lame across Gmsh refinement levels.

    /usr/bin/python3 postproc/hertz_study.py [--levels 0-2] [--lame-levels 0-4] [--out study/geometry]
                                             [--reuse] [--update-docs] [--force]

Runs inputs/hertz_indenter_<m>.nml and inputs/hertz_cylinder_<m>.nml (m = p1, p0) at the Hertz
levels, inputs/lame_cavity_<m>.nml at the Lame levels, measures them with contact2d.hertz and
contact2d.lame, and writes into --out
  hertz_pressure.png     p(x) of the runs (P1 and P0) against Hertz, per scene
  hertz_convergence.png  relative L2 error of p on Gamma_c against the contact edge size h at
                         x = 0 (Hertz) and energy-norm error against h (Lame)
  geometry_study.md      the table of every run (printed too)
With --update-docs they go instead to the tracked docs/figures/hertz_pressure.png,
docs/figures/hertz_convergence.png and docs/geometry_study.md (docs/geometry.md, "Study").
The table and figures already in --out are refused before any run (one line, exit 2) unless
--force (--update-docs asks for the tracked ones); each is written beside its name and moved into
place (contact2d.outfile).
Outputs of the runs go to --out (kept: --reuse skips a run whose output is a finished run of the
same deck and level, see contact2d.runner).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

from contact2d import hertz, lame
from contact2d.runner import ROOT, find_exe, levels_or_exit, out_dir, run
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

PROG = "hertz_study.py"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--levels", default="0-2",
                    help="Hertz mesh levels, e.g. 0-2, 0,1 or 2 (default 0-2)")
    ap.add_argument("--lame-levels", default="0-4",
                    help="Lame mesh levels, same forms (default 0-4)")
    ap.add_argument("--out", default=str(ROOT / "study" / "geometry"),
                    help="folder of the runs, and of the table and figures without --update-docs "
                         "(default study/geometry)")
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--reuse", action="store_true",
                    help="keep a run whose output in --out is a finished run of the same deck and level")
    ap.add_argument("--update-docs", action="store_true",
                    help="write the table and figures over the tracked docs/geometry_study.md and "
                         "docs/figures/hertz_*.png instead of into --out")
    ap.add_argument("--force", action="store_true",
                    help="replace the table and figures already in --out (refused otherwise, before any run)")
    args = ap.parse_args()
    hertz_levels = levels_or_exit(args.levels, "--levels", PROG)
    lame_levels = levels_or_exit(args.lame_levels, "--lame-levels", PROG)
    out = out_dir(args.out, PROG)
    exe = find_exe(args.exe)
    if args.update_docs:
        figs, table = ROOT / "docs" / "figures", ROOT / "docs" / "geometry_study.md"
    else:
        figs, table = out, out / "geometry_study.md"
    force = args.force or args.update_docs
    refuse_existing(PROG, [table, figs / "hertz_pressure.png", figs / "hertz_convergence.png"], force)
    rows, hz, lm = [], {}, {}
    for scene in ("indenter", "cylinder"):
        for m in ("p1", "p0"):
            for k in hertz_levels:
                h5 = out / f"hertz_{scene}_{m}_k{k}.h5"
                res = run(exe, ROOT / "inputs" / f"hertz_{scene}_{m}.nml", h5, {"mesh:level": k},
                          reuse=args.reuse)
                if res.returncode != 0:
                    sys.exit(f"run failed: {h5}: {res.stderr}")
                r = hertz.measure(h5)
                hz[(scene, m, k)] = r
                ok_a = abs(r["a_fe"] - r["a"]) <= r["h_edge"]
                rows.append(f"| hertz_{scene}_{m} | {k} | {r['nel']} | {r['h_min']:.4f} | {r['P']:.1f} | "
                            f"{r['a']:.4f} | {r['a_fe']:.4f} ({'yes' if ok_a else 'NO'}) | {r['p0']:.1f} | "
                            f"{100 * (r['p0_fe'] / r['p0'] - 1):+.2f} % | {100 * r['p_min'] / r['p0']:+.1f} % | "
                            f"{r['nonzero_separated']} | {r['l2_rel']:.3e} | {res.seconds:.1f} |")
                print(rows[-1], flush=True)
    lrows = []
    for m in ("p1", "p0"):
        prev = None
        for k in lame_levels:
            h5 = out / f"lame_cavity_{m}_k{k}.h5"
            res = run(exe, ROOT / "inputs" / f"lame_cavity_{m}.nml", h5, {"mesh:level": k}, reuse=args.reuse)
            if res.returncode != 0:
                sys.exit(f"run failed: {h5}: {res.stderr}")
            r = lame.measure(h5)
            lm[(m, k)] = r
            rate = "" if prev is None else "%.3f" % (np.log(prev[0] / r["energy_rel"]) / np.log(prev[1] / r["h"]))
            prev = (r["energy_rel"], r["h"])
            lrows.append(f"| lame_cavity_{m} | {k} | {r['nel']} | {r['h']:.4f} | {r['pc']:.4f} | "
                         f"{100 * r['p_err_max']:.3f} % | {r['energy_rel']:.4e} | {rate} | {res.seconds:.1f} |")
            print(lrows[-1], flush=True)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharey="row")
    for i, scene in enumerate(("indenter", "cylinder")):
        for j, m in enumerate(("p1", "p0")):
            ax = axes[i, j]
            ks = [k for (s, mm, k) in hz if s == scene and mm == m]
            for k in ks:
                r = hz[(scene, m, k)]
                if m == "p0":
                    ax.step(r["xs"], r["p"], where="mid", label=f"level {k}")
                else:
                    ax.plot(r["xs"], r["p"], ".-", ms=3, label=f"level {k}")
            r = hz[(scene, m, ks[-1])]
            xx = np.linspace(0, 1.6 * r["a"], 400)
            ax.plot(xx, r["p0"] * np.sqrt(np.clip(1 - (xx / r["a"]) ** 2, 0, None)), "k--", label="Hertz (finest P)")
            ax.set_xlim(0, 1.6 * r["a"])
            ax.set_title(f"hertz_{scene}: {m.upper()}")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("contact pressure [MPa]")
            ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, figs / "hertz_pressure.png", force, dpi=110)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for scene in ("indenter", "cylinder"):
        for m in ("p1", "p0"):
            ks = sorted(k for (s, mm, k) in hz if s == scene and mm == m)
            h = [hz[(scene, m, k)]["h_min"] for k in ks]
            e = [hz[(scene, m, k)]["l2_rel"] for k in ks]
            axes[0].loglog(h, e, "o-", label=f"{scene} {m.upper()}")
    axes[0].set_xlabel("contact edge size at x = 0 [mm]")
    axes[0].set_ylabel("||p_h - p||_L2(Gamma_c) / ||p||")
    axes[0].set_title("Hertz: pressure error")
    axes[0].legend(fontsize=8)
    for m in ("p1", "p0"):
        ks = sorted(k for (mm, k) in lm if mm == m)
        axes[1].loglog([lm[(m, k)]["h"] for k in ks], [lm[(m, k)]["energy_rel"] for k in ks], "o-",
                       label=f"Lame {m.upper()}")
    k1 = sorted(k for (mm, k) in lm if mm == "p1")
    hh = np.array([lm[("p1", k)]["h"] for k in k1])
    axes[1].loglog(hh, lm[("p1", k1[0])]["energy_rel"] * hh / hh[0], "k:", label="slope 1")
    axes[1].set_xlabel("largest element edge h [mm]")
    axes[1].set_ylabel("relative energy-norm error")
    axes[1].set_title("Lame: energy-norm error")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, figs / "hertz_convergence.png", force, dpi=110)

    hertz_list = ",".join(str(k) for k in hertz_levels)
    lame_list = ",".join(str(k) for k in lame_levels)
    text = ["# Geometry verification study (generated by postproc/hertz_study.py)", "",
            f"Made by `/usr/bin/python3 postproc/hertz_study.py --levels {hertz_list} --lame-levels {lame_list} "
            "--update-docs`; wall = the run's process time on the clock (0.0 for a run kept by --reuse), which "
            "depends on the machine and its load (docs/performance.md).", "",
            "Hertz: P from the run (twice the half model's normal force), a and p0 from 2D Hertz;",
            "a_run = abscissa of the farthest node in contact ('yes' when within one boundary element of a);",
            "p(0) error = pressure at the centre against p0; min p = the most tensile value of the recovered "
            "pressure against p0; sep != 0 = separated nodes where |p| > 1e-8 p0; L2 = ||p_h - p||_L2(Gamma_c) / ||p||. "
            "h = smallest contact edge.", "",
            "| deck | level | elements | h [mm] | P [N/mm] | a [mm] | a_run [mm] | p0 [MPa] | p(0) error | min p | "
            "sep != 0 | L2 rel | wall [s] |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"] + rows + [
            "", "Lame: p_c exact, max |p/p_c - 1| over Gamma_c, relative energy-norm error and its rate "
            "(h = largest element edge).", "",
            "| deck | level | elements | h [mm] | p_c [MPa] | max pressure error | energy error | rate | wall [s] |",
            "|---|---|---|---|---|---|---|---|---|"] + lrows + [""]
    with replacing(table, force) as tmp:
        Path(tmp).write_text("\n".join(text))
    print(f"wrote {table}, {figs / 'hertz_pressure.png'}, {figs / 'hertz_convergence.png'}")


if __name__ == "__main__":
    with refusal_exits(PROG):
        main()
