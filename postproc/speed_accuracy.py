#!/usr/bin/env python3
"""Speed against accuracy on the paper scene: one line per route, the chart a user decides from.

    /usr/bin/python3 postproc/speed_accuracy.py [--levels 1-5] [--reference-dir study/paper]
                         [--out study/speed_accuracy] [--figures DIR] [--no-getfem] [--reuse] [--force]

Routes (each run at every mesh level of --levels, P1 and P0 multipliers of
inputs/baillet_sassi_2002_p1.nml / _p0.nml):
  explicit            the shipped deck (tol_residual 1e-8), OMP_NUM_THREADS=1
  explicit tol 1e-10  solver:tol_residual = 1e-10, OMP_NUM_THREADS=1
  explicit tol 1e-3  solver:tol_residual = 1e-3, tol_kinetic = 1e-6 (kinetic energy goes with the
                      square of the out-of-balance), OMP_NUM_THREADS=1; tol 1e-2 likewise (1e-4)
  explicit mass x2    solver:mass_scaling = 2 x dt_critical (dt_critical of the shipped run at that
                      level), OMP_NUM_THREADS=1
  explicit all cores  the shipped deck, OMP_NUM_THREADS unset (every core)
  static              contact2d --static (the exact static solution of the discrete problem), 1 thread
  GetFEM static       postproc/getfem_reference.py on the shipped run's problem (assembly + solve time,
                      Python start-up excluded); left out with --no-getfem
CalculiX is not a route (no ccx here).

Two errors per run, both the relative energy-norm distance of the end state (contact2d.compare):
  error_reference  against the finest reference (the level-6 runs of postproc/paper_study.py when
                   --reference-dir has them, otherwise a --static run at level max+1 made here):
                   what a user gets
  error_same_mesh  against the --static run at the same level: what the solver adds to the
                   discretisation error (the static route's error_reference)
Filled markers: error_same_mesh < 0.1 x the discretisation error of that level.

Writes speed_accuracy.csv (route, multiplier, level, elements, wall_seconds, error_reference,
error_same_mesh) and speed_accuracy.png (wall time, log, against error_reference, log; the Pareto
front dashed) into --figures (default: --out). Those already there are refused before any run (one
line, exit 2) unless --force, and each is written beside its name and moved into place
(contact2d.outfile). --reuse keeps finished runs of the same settings (their timings too) and a
getfem_*.h5 that is a complete, converged reference of the same run's problem
(contact2d.runner.reference_problem); any other is recomputed, one line says why.
"""
import argparse
import csv
import os
import subprocess
import sys
from pathlib import Path

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, keep_reference, levels_or_exit, out_dir, run
from contact2d.compare import compare
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

FIELDS = ("route", "multiplier", "level", "elements", "wall_seconds", "error_reference", "error_same_mesh")
TIGHT = 1e-10
# route, label, colour, marker
ROUTES = (("explicit", "explicit, shipped tol 1e-8, 1 thread", "C0", "o"),
          ("explicit_tol1e-10", "explicit, tol 1e-10, 1 thread", "C1", "v"),
          ("explicit_tol1e-3", "explicit, tol 1e-3 (kinetic 1e-6), 1 thread", "C5", "<"),
          ("explicit_tol1e-2", "explicit, tol 1e-2 (kinetic 1e-4), 1 thread", "C6", ">"),
          ("explicit_mass2", "explicit, mass scaling 2 dt_c, 1 thread", "C2", "^"),
          ("explicit_all_cores", "explicit, shipped tol, all cores", "C3", "D"),
          ("static", "contact2d --static, 1 thread", "k", "s"),
          ("getfem_static", "GetFEM static solve", "C4", "P"))


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--levels", default="1-5", help="mesh levels, e.g. 1-5, 1,3 or 2 (default 1-5)")
    ap.add_argument("--reference-dir", default="study/paper", help="where paper_study.py left p1_k6.h5, p0_k6.h5")
    ap.add_argument("--out", default="study/speed_accuracy", help="folder of the runs (and of the products "
                                                                  "without --figures)")
    ap.add_argument("--figures", help="folder of speed_accuracy.csv and .png (default --out), e.g. docs/figures")
    ap.add_argument("--no-getfem", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="keep runs that finished with the same deck and settings (their timings too), and "
                         "GetFEM references that are complete and converged for the same run's problem")
    ap.add_argument("--force", action="store_true",
                    help="replace speed_accuracy.csv and .png already there (refused otherwise, before any run)")
    args = ap.parse_args()
    exe = find_exe(args.exe)
    levels = levels_or_exit(args.levels, "--levels", "speed_accuracy.py")
    out = out_dir(args.out, "speed_accuracy.py")
    figs = out_dir(args.figures, "speed_accuracy.py", "--figures") if args.figures else out
    refuse_existing("speed_accuracy.py", [figs / "speed_accuracy.csv", figs / "speed_accuracy.png"], args.force)
    all_cores = os.environ.pop("OMP_NUM_THREADS", None)   # unset for the all-cores route
    if all_cores is not None:
        print(f"OMP_NUM_THREADS={all_cores} unset for the all-cores route", flush=True)

    refs = {}
    for m in ("p1", "p0"):
        ref = Path(args.reference_dir) / f"{m}_k6.h5"
        if not ref.is_file() or levels[-1] >= 6:
            ref = out / f"ref_{m}_k{levels[-1] + 1}_static.h5"
            if not ref.is_file():
                print(f"making the reference {ref} (no {args.reference_dir}/{m}_k6.h5)", flush=True)
            res = run(exe, ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml", ref,
                      {"mesh:level": levels[-1] + 1, "output:xdmf": False}, reuse=True, static=True)
            if res.returncode != 0:
                sys.exit(res.stderr)
        refs[m] = ref
    print(f"references: {refs['p1']}, {refs['p0']}", flush=True)

    rows = []
    for m in ("p1", "p0"):
        deck = ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml"
        for k in levels:
            base = {"mesh:level": k, "output:xdmf": False}
            static_h5 = out / f"{m}_k{k}_static.h5"
            shipped_h5 = out / f"{m}_k{k}_explicit.h5"
            todo = [("static", static_h5, base, 1, True),
                    ("explicit", shipped_h5, base, 1, False),
                    ("explicit_tol1e-10", out / f"{m}_k{k}_tol1e-10.h5", {**base, "solver:tol_residual": TIGHT}, 1,
                     False),
                    ("explicit_tol1e-3", out / f"{m}_k{k}_tol1e-3.h5",
                     {**base, "solver:tol_residual": 1e-3, "solver:tol_kinetic": 1e-6}, 1, False),
                    ("explicit_tol1e-2", out / f"{m}_k{k}_tol1e-2.h5",
                     {**base, "solver:tol_residual": 1e-2, "solver:tol_kinetic": 1e-4}, 1, False),
                    ("explicit_mass2", out / f"{m}_k{k}_mass2.h5", None, 1, False),
                    ("explicit_all_cores", out / f"{m}_k{k}_all_cores.h5", base, None, False)]
            for route, h5, sets, threads, static in todo:
                if sets is None:                      # mass scaling: from the shipped run's dt_critical
                    with Run(shipped_h5) as r:
                        sets = {**base, "solver:mass_scaling": 2 * float(r.attrs["dt_critical"])}
                res = run(exe, deck, h5, sets, threads=threads, reuse=args.reuse, static=static)
                if res.returncode != 0:
                    sys.exit(f"{h5}: {res.stderr}")
                rows.append(row(route, m, k, h5, refs[m], static_h5))
            if not args.no_getfem:
                gf = out / f"getfem_{m}_k{k}.h5"
                if not keep_reference(gf, shipped_h5, args.reuse, friction="tresca"):
                    proc = subprocess.run(["/usr/bin/python3", str(ROOT / "postproc" / "getfem_reference.py"),
                                           str(shipped_h5), "-o", str(gf), "--force", "--friction", "tresca"],
                                          capture_output=True, text=True, env={**os.environ, "OMP_NUM_THREADS": "1"})
                    if proc.returncode != 0:
                        print(f"GetFEM {m} k={k}: {proc.stderr.strip()}")
                        continue
                rows.append(row("getfem_static", m, k, gf, refs[m], static_h5))

    with replacing(figs / "speed_accuracy.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {figs / 'speed_accuracy.csv'}")
    # the caption's command: --force and --reuse left out (they change no number: a reused run is one
    # of the same settings, with its own timing)
    command = "/usr/bin/python3 postproc/speed_accuracy.py " + " ".join(a for a in sys.argv[1:]
                                                                        if a not in ("--force", "--reuse"))
    plot(rows, figs / "speed_accuracy.png", args.force, command)
    print_advice(rows)


def row(route, m, k, h5, ref, static_h5):
    with Run(h5) as r:
        wall = float(r.attrs["wall_seconds"])
    res = compare(h5, ref)
    err_ref = res["errors"]["energy"]
    elements = res["a"]["nx"] * res["a"]["ny"]
    err_same = compare(h5, static_h5)["errors"]["energy"]
    print(f"{m.upper()} k={k} {route:20s} {wall:9.3f} s  error: reference {err_ref:.3e}, same mesh {err_same:.3e}",
          flush=True)
    return dict(route=route, multiplier=m.upper(), level=k, elements=elements, wall_seconds=f"{wall:.6g}",
                error_reference=f"{err_ref:.6e}", error_same_mesh=f"{err_same:.6e}")


def discretisation(rows):
    """(multiplier, level) -> the static route's error against the reference."""
    return {(r["multiplier"], r["level"]): float(r["error_reference"]) for r in rows if r["route"] == "static"}


def resolved(r, disc):
    d = disc.get((r["multiplier"], r["level"]))
    return d is not None and float(r["error_same_mesh"]) < 0.1 * d


def print_advice(rows):
    disc = discretisation(rows)
    print("solver error / discretisation error (filled markers: < 0.1):")
    for m in ("P1", "P0"):
        for k in sorted({r["level"] for r in rows if r["multiplier"] == m}):
            parts = [f"{r['route']} {float(r['error_same_mesh']) / disc[(m, k)]:.2e}" for r in rows
                     if r["multiplier"] == m and r["level"] == k and r["route"] != "static" and (m, k) in disc]
            print(f"  {m} k={k} (discretisation {disc.get((m, k), float('nan')):.3e}): " + ", ".join(parts))


def pareto(points):
    """The non-dominated (wall, error) points, sorted by wall time."""
    front, best = [], float("inf")
    for w, e in sorted(points):
        if e < best:
            front.append((w, e))
            best = e
    return front


def plot(rows, path, force, command):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    disc = discretisation(rows)
    fig, axes = plt.subplots(1, 2, figsize=(14, 6.8), sharey=True)
    handles = {}
    for ax, m in zip(axes, ("P1", "P0")):
        pts = []
        for route, label, color, mk in ROUTES:
            rs = sorted((r for r in rows if r["route"] == route and r["multiplier"] == m), key=lambda r: r["level"])
            if not rs:
                continue
            x = [float(r["wall_seconds"]) for r in rs]
            y = [float(r["error_reference"]) for r in rs]
            pts += list(zip(x, y))
            (h,) = ax.loglog(x, y, "-", color=color, lw=1.2, alpha=0.8)
            for r, xi, yi in zip(rs, x, y):
                filled = route in ("static", "getfem_static") or resolved(r, disc)
                ax.loglog([xi], [yi], mk, color=color, ms=7, mfc=color if filled else "white", mew=1.4)
            handles[label] = plt.Line2D([], [], color=color, marker=mk, ms=7, lw=1.2)
            if route == "static":
                for r, xi, yi in zip(rs, x, y):
                    ax.annotate(f"k={r['level']}", (xi, yi), textcoords="offset points", xytext=(-4, -13),
                                fontsize=8, ha="right")
        front = pareto(pts)
        (h,) = ax.loglog([p[0] for p in front], [p[1] for p in front], "--", color="0.4", lw=2.5, alpha=0.45,
                         zorder=0)
        handles["Pareto front (fastest for its error)"] = h
        ax.set_title(f"{m} multipliers: end state against the fine reference")
        ax.set_xlabel("wall time [s] (log)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("relative energy-norm error against the fine reference (log)")
    handles["hollow: solver error > 0.1 x discretisation error"] = plt.Line2D([], [], color="0.3", marker="o",
                                                                               mfc="white", ls="none")
    handles["filled: solver error < 0.1 x discretisation error"] = plt.Line2D([], [], color="0.3", marker="o",
                                                                              ls="none")
    fig.legend(list(handles.values()), list(handles), loc="center left", bbox_to_anchor=(0.745, 0.55), fontsize=8.5,
               frameon=False)
    threads = os.cpu_count()
    fig.text(0.01, 0.01, f"Paper scene (Tresca), mesh levels k connected (labels at the static route). {cpu_name()}, "
                         f"{threads} cores: 1 thread (OMP_NUM_THREADS=1) except 'all cores' ({threads} threads).\n"
                         f"Solver error = energy-norm distance to --static on the same mesh; discretisation error = "
                         f"the static route's error. CalculiX: not run (no ccx installed).\n{command}",
             fontsize=8, va="bottom")
    fig.tight_layout(rect=(0, 0.08, 0.74, 1))
    save_figure(fig, path, force, dpi=130)
    print(f"wrote {path}")


if __name__ == "__main__":
    with refusal_exits("speed_accuracy.py"):
        main()
