#!/usr/bin/env python3
"""Coulomb friction: end state against ramp duration and loading path, and large mu.

    /usr/bin/python3 postproc/coulomb_path_study.py [--exe build/bin/contact2d] [--out study/coulomb]
                     [--level 1] [--factors 1,2,4,8,16,32] [--reuse] [--force]

Scene: inputs/coulomb_sliding_p1.nml (and _p0), mesh level 1 by default, tol_residual 1e-11. The
top is pressed by 1e-3 mm and moved by a stroke s_x: 5e-3 mm (the deck: the block ends fully
sliding) or 4e-4 mm (partial slip: stick and slip nodes at the end). Two loading paths:
  staged        press over [0, 2e-6 f] s, then shear over [2e-6 f, 6e-6 f] s (the deck's, times f);
  simultaneous  press and shear together over [0, 6e-6 f] s, proportionally (both curves in the
                same two stages, to half the values at 3e-6 f s, then to the full ones).
f scales the ramp duration. Each P1 end state is compared (energy norm, contact2d.compare) with
GetFEM's quasi-static Coulomb solution of the same path (postproc/getfem_coulomb.py, 20 load
increments per interval); P0 (no GetFEM reference) with the P0 run of the slowest ramp of the same
path. The path effect is the difference between the two paths' quasi-static (GetFEM) answers.
Large mu: mu = 1 and 2 on the same scene (deck ramp and 8x slower): whether the run converges,
status changes summed over the run (chatter), and the end state against GetFEM.

Prints every figure; writes coulomb_path.csv, coulomb_large_mu.csv and coulomb_path.png in --out.
Those already there are refused before any run (one line, exit 2) unless --force; each is written
beside its name and moved into place (contact2d.outfile). --reuse keeps a run only when it is a
finished run of the same deck and settings (contact2d.runner.reuse_problem), and a GetFEM reference only when
it is a complete, converged getfem_coulomb.py file of the same run's problem (effective deck) with
the same increments (contact2d.runner.reference_problem); any other is redone, one line says why.
"""
import argparse
import csv
import subprocess
import sys
from pathlib import Path

import numpy as np

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, keep_reference, out_dir, run
from contact2d.compare import compare
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

HERE = Path(__file__).resolve().parent
STROKES = {"sliding": 5.0e-3, "partial": 4.0e-4}
INCREMENTS = 20     # getfem_coulomb.py --increments: load steps per interval of the reference


def path_sets(path, stroke, f, level, mu=None):
    """--set values of one run (contact2d.runner.run)."""
    t1, t2 = 2.0e-6 * f, 6.0e-6 * f
    sets = {"mesh:level": level, "solver:tol_residual": 1e-11, "output:xdmf": False, "solver:t_end": 10 * t2}
    if path == "staged":
        sets.update({"dirichlet#1:times": [t1], "dirichlet#2:values": [0.0, stroke], "dirichlet#2:times": [t1, t2]})
    else:
        # proportional: both curves in two equal stages (a namelist override cannot shorten the
        # deck's two-entry u_x curve to one entry), so u_x/u_y is the same at every time
        sets.update({"dirichlet#1:values": [-5e-4, -1e-3], "dirichlet#1:times": [t2 / 2, t2],
                     "dirichlet#2:values": [stroke / 2, stroke], "dirichlet#2:times": [t2 / 2, t2]})
    if mu is not None:
        sets["contact:friction_coefficient"] = mu
    return sets


def contact2d(exe, mult, sets, h5, reuse):
    """One run on one thread; with reuse, an existing h5 is kept only when contact2d.runner.reuse_problem
    finds it is this run, finished."""
    res = run(exe, ROOT / "inputs" / f"coulomb_sliding_{mult.lower()}.nml", h5, sets, threads=1, reuse=reuse)
    if res.returncode != 0:
        sys.exit(f"contact2d failed ({h5}): {res.stderr.strip()}")
    return res.returncode


def getfem(h5, ref, reuse):
    """The GetFEM Coulomb reference of the run h5; with reuse, an existing ref is kept only when it is
    a complete, converged one of h5's problem with this study's increments (contact2d.runner.keep_reference)."""
    if keep_reference(ref, h5, reuse, program="getfem_coulomb", friction="coulomb", increments=INCREMENTS):
        return 0
    proc = subprocess.run([sys.executable, str(HERE / "getfem_coulomb.py"), str(h5), "-o", str(ref), "--force",
                           "--increments", str(INCREMENTS)], capture_output=True, text=True)
    return proc.returncode


def summary(h5):
    with Run(h5) as f:
        st = f.contact("status")
        conv = int(f.attr("converged"))
        chg = int(np.sum(f.history("status_changes"))) if f.has("history/status_changes") else -1
        steps = int(f.attr("steps"))
        ft, fn = float(np.sum(f.contact("tangential_force"))), float(np.sum(f.contact("normal_force")))
    return st, conv, chg, steps, ft, fn


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe")
    ap.add_argument("--out", default="study/coulomb")
    ap.add_argument("--level", type=int, default=1)
    ap.add_argument("--factors", default="1,2,4,8,16,32")
    ap.add_argument("--reuse", action="store_true",
                    help="keep the runs already in --out that finished with the same deck and settings, and the "
                         "GetFEM references that are complete and converged for the same run's problem")
    ap.add_argument("--force", action="store_true",
                    help="replace the CSVs and PNG already in --out (refused otherwise, before any run)")
    args = ap.parse_args()
    exe = find_exe(args.exe)
    out = out_dir(args.out, "coulomb_path_study.py")
    refuse_existing("coulomb_path_study.py", [out / "coulomb_path.csv", out / "coulomb_large_mu.csv",
                                              out / "coulomb_path.png"], args.force)
    factors = [float(x) for x in args.factors.split(",")]

    rows = []
    refs = {}
    for stroke_name, stroke in STROKES.items():
        for path in ("staged", "simultaneous"):
            for mult in ("P1", "P0"):
                for f in factors:
                    tag = f"{stroke_name}_{path}_{mult}_f{f:g}"
                    h5 = out / f"{tag}.h5"
                    contact2d(exe, mult, path_sets(path, stroke, f, args.level), h5, args.reuse)
                    rows.append(dict(stroke=stroke_name, path=path, multiplier=mult, factor=f, file=str(h5)))
            # the path's quasi-static answer: GetFEM on the slowest P1 run (the path, not the ramp, matters)
            src = out / f"{stroke_name}_{path}_P1_f{max(factors):g}.h5"
            ref = out / f"{stroke_name}_{path}_getfem.h5"
            rc = getfem(src, ref, args.reuse)
            if rc != 0:
                sys.exit(f"getfem_coulomb failed on {src}")
            refs[(stroke_name, path)] = ref
    for r in rows:
        if r["multiplier"] == "P1":
            ref = refs[(r["stroke"], r["path"])]
        else:
            ref = out / f"{r['stroke']}_{r['path']}_P0_f{max(factors):g}.h5"
        res = compare(r["file"], str(ref))
        st, conv, chg, steps, ft, fn = summary(r["file"])
        with Run(ref) as g:
            st_ref = g.contact("status")
        r.update(energy=res["errors"]["energy"], status_equal=int(np.array_equal(st, st_ref)), converged=conv,
                 status_changes=chg, steps=steps, ft_over_fn=ft / fn,
                 reference="getfem" if r["multiplier"] == "P1" else "slowest P0 run")
        print(f"{r['stroke']:8s} {r['path']:12s} {r['multiplier']} ramp x{r['factor']:<4g}: energy-norm diff "
              f"{r['energy']:9.2e} vs {r['reference']:14s} statuses {'equal' if r['status_equal'] else 'DIFFER'}"
              f"  steps {steps:6d}  F_t/F_n {ft / fn:.6f}")
    path_effect = {}
    for stroke_name in STROKES:
        a, b = refs[(stroke_name, "staged")], refs[(stroke_name, "simultaneous")]
        e = compare(str(a), str(b))["errors"]["energy"]
        with Run(a) as fa, Run(b) as fb:
            sa, sb = fa.contact("status"), fb.contact("status")
            fta = float(np.sum(fa.contact("tangential_force")))
            ftb = float(np.sum(fb.contact("tangential_force")))
        path_effect[stroke_name] = e
        print(f"path effect ({stroke_name}): GetFEM staged vs simultaneous energy-norm diff {e:.3e}; statuses "
              f"{sa.tolist()} vs {sb.tolist()}; total F_t {fta:.6f} vs {ftb:.6f} N")
    with replacing(out / "coulomb_path.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=[k for k in rows[0] if k != "file"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    # large mu
    big = []
    for mu in (1.0, 2.0):
        for stroke_name, stroke in STROKES.items():
            for f in (1.0, 8.0):
                for mult in ("P1", "P0"):
                    tag = f"mu{mu:g}_{stroke_name}_{mult}_f{f:g}"
                    h5 = out / f"{tag}.h5"
                    contact2d(exe, mult, path_sets("staged", stroke, f, args.level, mu=mu), h5, args.reuse)
                    st, conv, chg, steps, ft, fn = summary(h5)
                    row = dict(mu=mu, stroke=stroke_name, multiplier=mult, factor=f, converged=conv, steps=steps,
                               status_changes=chg, n_stick=int(np.sum(st == 1)), n_slip=int(np.sum(st == 2)),
                               n_separated=int(np.sum(st == 0)), ft_over_fn=ft / fn, energy_vs_getfem=float("nan"),
                               status_equal_getfem=-1)
                    if mult == "P1":
                        ref = out / f"{tag}_getfem.h5"
                        if getfem(h5, ref, args.reuse) == 0:
                            row["energy_vs_getfem"] = compare(str(h5), str(ref))["errors"]["energy"]
                            with Run(ref) as g:
                                row["status_equal_getfem"] = int(np.array_equal(st, g.contact("status")))
                    big.append(row)
                    print(f"mu = {mu:g} {stroke_name:8s} {mult} ramp x{f:g}: converged {conv}, steps {steps}, status "
                          f"changes {chg}, stick/slip/separated {row['n_stick']}/{row['n_slip']}/{row['n_separated']}, "
                          f"F_t/F_n {ft / fn:.6f}, vs GetFEM {row['energy_vs_getfem']:.2e} "
                          f"(statuses equal: {row['status_equal_getfem']})")
    with replacing(out / "coulomb_large_mu.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(big[0]))
        w.writeheader()
        w.writerows(big)
    plot(rows, path_effect, out / "coulomb_path.png", args)


def plot(rows, path_effect, png, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, stroke_name in zip(axes, STROKES):
        for path, color in (("staged", "tab:blue"), ("simultaneous", "tab:orange")):
            for mult, ls in (("P1", "-"), ("P0", "--")):
                rr = [r for r in rows if r["stroke"] == stroke_name and r["path"] == path and r["multiplier"] == mult]
                x = np.array([6.0e-6 * r["factor"] for r in rr])
                y = np.array([max(r["energy"], 1e-16) for r in rr])
                if mult == "P0":
                    x, y = x[:-1], y[:-1]   # the slowest P0 run is its own reference
                ax.loglog(x, y, ls, marker="o", color=color,
                          label=f"{path}, {mult} vs " + ("GetFEM" if mult == "P1" else "slowest P0"))
        ax.axhline(max(path_effect[stroke_name], 1e-16), color="k", ls=":",
                   label="path effect: staged vs simultaneous (GetFEM)")
        ax.axhline(1e-6, color="grey", lw=0.8)
        ax.set_title(f"coulomb_sliding level {args.level}, stroke {STROKES[stroke_name]:g} mm ({stroke_name})")
        ax.set_xlabel("total loading time [s] (ramp duration)")
    axes[0].set_ylabel("relative energy-norm difference of the end state")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, png, args.force, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    with refusal_exits("coulomb_path_study.py"):
        main()
