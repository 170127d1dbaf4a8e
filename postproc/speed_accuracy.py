#!/usr/bin/env python3
"""Speed against accuracy on the paper scene: error of the end state against wall time.

    /usr/bin/python3 postproc/speed_accuracy.py [--levels 1-5] [--reference-dir study/paper]
                                               [--out study/speed_accuracy] [--threads 1] [--reuse] [--force]

Sweeps mesh level x multiplier (P1, P0) x load ramp x convergence tolerance (tol_residual = tol,
tol_kinetic = tol^2, since kinetic energy goes with the square of the out-of-balance), runs contact2d,
measures its wall time and the relative energy-norm error of its end state against the finest
reference (the level-6 runs of postproc/paper_study.py when --reference-dir has them, otherwise
a level-(max+1) run made here), and solves the same problem on the same meshes with the GetFEM
static reference (postproc/getfem_reference.py; its assembly + solve time, Python start-up
excluded). Writes speed_accuracy.csv and speed_accuracy.png (log-log, GetFEM on the same axes);
those already in --out are refused before any run (one line, exit 2) unless --force, and each is
written beside its name and moved into place (contact2d.outfile). --reuse keeps finished runs of
the same settings and a getfem_*.h5 that is a complete, converged reference of the same run's problem
(contact2d.runner.reference_problem); any other is recomputed, one line says why.
"""
import argparse
import csv
import subprocess
import sys
from pathlib import Path

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, keep_reference, levels_or_exit, out_dir, run
from contact2d.compare import compare
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

RAMPS = (0.5e-6, 2.5e-6, 1.0e-5)
TOLS = (1e-4, 1e-6, 1e-8)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--levels", default="1-5", help="mesh levels, e.g. 1-5, 1,3 or 2 (default 1-5)")
    ap.add_argument("--reference-dir", default="study/paper", help="where paper_study.py left p1_k6.h5, p0_k6.h5")
    ap.add_argument("--out", default="study/speed_accuracy")
    ap.add_argument("--threads", type=int, default=1, help="OMP_NUM_THREADS of the timed runs (default 1)")
    ap.add_argument("--no-getfem", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="keep runs that finished with the same deck and settings (their timings too), and "
                         "GetFEM references that are complete and converged for the same run's problem")
    ap.add_argument("--force", action="store_true",
                    help="replace speed_accuracy.csv and .png already in --out (refused otherwise, before any run)")
    args = ap.parse_args()
    exe = find_exe(args.exe)
    levels = levels_or_exit(args.levels, "--levels", "speed_accuracy.py")
    out = out_dir(args.out, "speed_accuracy.py")
    refuse_existing("speed_accuracy.py", [out / "speed_accuracy.csv", out / "speed_accuracy.png"], args.force)

    refs = {}
    for m in ("p1", "p0"):
        ref = Path(args.reference_dir) / f"{m}_k6.h5"
        if not ref.is_file():
            ref = out / f"ref_{m}_k{levels[-1] + 1}.h5"
            if not ref.is_file():
                print(f"making the reference {ref} (no {args.reference_dir}/{m}_k6.h5)", flush=True)
            res = run(exe, ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml", ref,
                      {"mesh:level": levels[-1] + 1, "solver:tol_residual": 1e-10, "output:xdmf": False},
                      reuse=True)
            if res.returncode != 0:
                sys.exit(res.stderr)
        refs[m] = ref
    print(f"references: {refs['p1']}, {refs['p0']}")

    rows = []
    for m in ("p1", "p0"):
        deck = ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml"
        for k in levels:
            for tr in RAMPS:
                for tol in TOLS:
                    h5 = out / f"{m}_k{k}_t{tr:.1e}_tol{tol:.0e}.h5"
                    res = run(exe, deck, h5, {"mesh:level": k, "solver:t_ramp": tr, "solver:tol_residual": tol,
                                              "solver:tol_kinetic": tol**2,
                                              "solver:power_iterations": 0, "output:xdmf": False},
                              threads=args.threads, reuse=args.reuse)
                    if res.returncode != 0:
                        sys.exit(f"{h5}: {res.stderr}")
                    with Run(h5) as r:
                        wall = float(r.attrs["wall_seconds"])
                        steps = int(r.attrs["steps"])
                    err = compare(h5, refs[m])["errors"]
                    rows.append(dict(code="contact2d", multiplier=m.upper(), level=k, t_ramp=tr, tol=tol, steps=steps,
                                     wall_seconds=wall, energy_error=err["energy"], pressure_error=err["pressure_l2"]))
                    print(f"{m.upper()} k={k} t_ramp={tr:.1e} tol={tol:.0e}: {steps:6d} steps {wall:8.3f} s  "
                          f"energy error {err['energy']:.3e}", flush=True)
            if not args.no_getfem:
                src = out / f"{m}_k{k}_t{RAMPS[1]:.1e}_tol{TOLS[-1]:.0e}.h5"
                gf = out / f"getfem_{m}_k{k}.h5"
                if not keep_reference(gf, src, args.reuse, friction="tresca"):
                    proc = subprocess.run(["/usr/bin/python3", str(ROOT / "postproc" / "getfem_reference.py"), str(src),
                                           "-o", str(gf), "--force", "--friction", "tresca"], capture_output=True, text=True)
                    if proc.returncode != 0:
                        print(f"GetFEM {m} k={k}: {proc.stderr.strip()}")
                        continue
                with Run(gf) as r:
                    wall = float(r.attrs["wall_seconds"])
                err = compare(gf, refs[m])["errors"]
                rows.append(dict(code="GetFEM static", multiplier=m.upper(), level=k, t_ramp=0, tol=0, steps=0,
                                 wall_seconds=wall, energy_error=err["energy"], pressure_error=err["pressure_l2"]))
                print(f"GetFEM {m.upper()} k={k}: {wall:8.3f} s  energy error {err['energy']:.3e}", flush=True)

    with replacing(out / "speed_accuracy.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {out / 'speed_accuracy.csv'}")
    plot(rows, out / "speed_accuracy.png", levels, args.force)


def plot(rows, path, levels, force):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    cmap = plt.get_cmap("viridis")
    for ax, m in zip(axes, ("P1", "P0")):
        for k in levels:
            color = cmap((k - levels[0]) / max(1, len(levels) - 1))
            for tr, mk in zip(RAMPS, ("v", "o", "^")):
                pts = [r for r in rows if r["code"] == "contact2d" and r["multiplier"] == m and r["level"] == k
                       and r["t_ramp"] == tr]
                ax.loglog([r["wall_seconds"] for r in pts], [r["energy_error"] for r in pts], mk, color=color,
                          mfc="none" if tr != RAMPS[1] else color, ms=6,
                          label=f"k={k}, t_ramp={tr:.1e} s" if m == "P1" else None)
            gf = [r for r in rows if r["code"] == "GetFEM static" and r["multiplier"] == m and r["level"] == k]
            if gf:
                ax.loglog([gf[0]["wall_seconds"]], [gf[0]["energy_error"]], "s", color=color, mec="k", ms=9,
                          label=f"GetFEM static, k={k}" if m == "P1" else None)
        ax.set_title(f"{m}: end state against the level-6 reference")
        ax.set_xlabel("wall time [s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("relative energy-norm error")
    axes[0].legend(fontsize=6, ncol=2)
    fig.suptitle("Speed against accuracy, paper scene (Tresca): contact2d (tolerances 1e-4, 1e-6, 1e-8 "
                 "per marker group) and GetFEM's static solve (squares)")
    fig.tight_layout()
    save_figure(fig, path, force, dpi=130)
    print(f"wrote {path}")


if __name__ == "__main__":
    with refusal_exits("speed_accuracy.py"):
        main()
