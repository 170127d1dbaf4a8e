#!/usr/bin/env python3
"""Strong and weak scaling of the explicit step loop over MPI ranks and OpenMP threads (docs/mpi.md).

    /usr/bin/python3 postproc/bench_scaling.py [--ranks 1,2] [--threads 1,2] [--level 5] [--steps 2000]
        [--repeats 3] [--deck inputs/baillet_sassi_2002_p1.nml] [--mpirun mpirun] [--mpirun-args "..."]
        [--out study/scaling] [--figure docs/figures/scaling.png] [--force]

Every run is `contact2d DECK -q --set solver:max_steps=STEPS` (one process when ranks = 1, else
`mpirun -np ranks`), OMP_NUM_THREADS = threads; the figures are those of the step loop only: the
steps' wall time (the root attribute time_steps_seconds) and element-steps / s (the summary line;
elements x steps / time_steps_seconds when it is not printed), each the median of --repeats runs,
the cases interleaved (one run of each case per round) so that a change in the machine's load hits
all alike. Beside each figure the 1-minute load average (os.getloadavg) before its runs: median
and largest. On a shared machine a figure taken at load >= the number of cores measures the
other users as much as the code.

  strong  the same mesh (--level) for every ranks x threads: speed-up over 1 x 1 and efficiency
          (speed-up / (ranks x threads));
  weak    the mesh grows with the processes: P = ranks x threads times the grid rows of --level
          (mesh:ny and mesh:ly times P: elements of the same shape, so the same dt), efficiency =
          the 1 x 1 time over the time at P (1: perfect).

The table is printed and written to --out/scaling.json (refused if there, unless --force); with
--figure, a plot of element-steps / s against ranks x threads, strong and weak, one line per
thread count. Exit 0, or 1 when a run failed (its command and stderr printed), 2 when refused.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

import h5py

from contact2d.runner import ROOT, find_exe, out_dir

DECK = ROOT / "inputs" / "baillet_sassi_2002_p1.nml"
ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def int_list(text, option):
    """A comma-separated list of whole numbers >= 1; one line on stderr and exit 2 otherwise."""
    try:
        vals = [int(v) for v in text.split(",")]
    except ValueError:
        vals = []
    if not vals or min(vals) < 1:
        print("bench_scaling.py: refused: %s '%s': a comma-separated list of whole numbers >= 1" % (option, text),
              file=sys.stderr)
        sys.exit(2)
    return vals


def deck_mesh(deck):
    """(ny, ly) of the deck's &mesh group (the weak-scaling mesh multiplies both)."""
    text = Path(deck).read_text()
    m = re.search(r"(?ims)^\s*&mesh\b(.*?)^\s*/", text)
    if not m:
        return None
    ny = re.search(r"(?i)\bny\s*=\s*(\d+)", m.group(1))
    ly = re.search(r"(?i)\bly\s*=\s*([0-9.eEdD+-]+)", m.group(1))
    if not ny or not ly:
        return None
    return int(ny.group(1)), float(ly.group(1).replace("d", "e").replace("D", "e"))


def one_run(args, exe, ranks, threads, sets, out):
    cmd = [exe, str(args.deck), "-q", "-o", str(out), "--force"]
    for k, v in sets.items():
        cmd += ["--set", "%s=%s" % (k, v)]
    if ranks > 1:
        cmd = [args.mpirun, "-q", "--oversubscribe"] + args.mpirun_args.split() + ["-np", str(ranks)] + cmd
    env = {**os.environ, **ENV, "OMP_NUM_THREADS": str(threads)}
    load = os.getloadavg()[0]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        print("bench_scaling.py: run failed (exit %d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr.strip()),
              file=sys.stderr)
        sys.exit(1)
    with h5py.File(out, "r") as f:
        steps_s = float(f.attrs["time_steps_seconds"])
        nsteps = int(f.attrs["steps"]) if "steps" in f.attrs else None
        nel = None
        for name in ("elements", "nelem", "element_count"):
            if name in f.attrs:
                nel = int(f.attrs[name])
    m = re.search(r"element-steps / s\s+([0-9.eE+-]+)", p.stdout)
    rate = float(m.group(1)) if m else (nel * nsteps / steps_s if nel and nsteps and steps_s > 0 else float("nan"))
    return steps_s, rate, load


def measure(args, exe, cases, tmp):
    """cases: list of (kind, ranks, threads, sets); repeats interleaved; medians."""
    samples = {i: [] for i in range(len(cases))}
    for _ in range(args.repeats):
        for i, (kind, ranks, threads, sets) in enumerate(cases):
            samples[i].append(one_run(args, exe, ranks, threads, sets, tmp / ("%s_%d_%d.h5" % (kind, ranks, threads))))
    rows = []
    for i, (kind, ranks, threads, sets) in enumerate(cases):
        s = samples[i]
        rows.append({"kind": kind, "ranks": ranks, "threads": threads, "sets": sets,
                     "steps_seconds": statistics.median(x[0] for x in s),
                     "element_steps_per_s": statistics.median(x[1] for x in s),
                     "load_median": statistics.median(x[2] for x in s), "load_max": max(x[2] for x in s),
                     "runs": len(s)})
    return rows


def table(rows, kind):
    base = next((r for r in rows if r["kind"] == kind and r["ranks"] == 1 and r["threads"] == 1), None)
    print("%s scaling (medians of %d runs; load: 1-minute load average before the runs, median / max; %d cores)"
          % (kind, rows[0]["runs"], os.cpu_count()))
    print("%6s %8s %12s %16s %9s %11s %13s" % ("ranks", "threads", "steps [s]", "element-steps/s", "speed-up",
                                                 "efficiency", "load"))
    for r in (r for r in rows if r["kind"] == kind):
        p = r["ranks"] * r["threads"]
        if base:
            if kind == "strong":
                up = base["steps_seconds"] / r["steps_seconds"]
                eff = up / p
            else:
                up = r["element_steps_per_s"] / base["element_steps_per_s"]
                eff = base["steps_seconds"] / r["steps_seconds"]
            r["speedup"], r["efficiency"] = up, eff
            extra = "%9.2f %11.2f" % (up, eff)
        else:
            extra = "%9s %11s" % ("n/a", "n/a")
        print("%6d %8d %12.4f %16.4g %s %6.2f / %4.2f" % (r["ranks"], r["threads"], r["steps_seconds"],
                                                         r["element_steps_per_s"], extra, r["load_median"],
                                                         r["load_max"]))


def figure(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for ax, kind in zip(axes, ("strong", "weak")):
        for t in sorted({r["threads"] for r in rows if r["kind"] == kind}):
            pts = sorted((r["ranks"] * r["threads"], r["element_steps_per_s"], r["load_median"])
                         for r in rows if r["kind"] == kind and r["threads"] == t)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label="%d thread%s" % (t, "s" * (t > 1)))
            for p in pts:
                ax.annotate("load %.1f" % p[2], (p[0], p[1]), fontsize=7, textcoords="offset points", xytext=(3, 3))
        ax.set_xlabel("ranks x threads")
        ax.set_ylabel("element-steps / s")
        ax.set_title(kind + " scaling")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    tmp = Path(str(path) + ".partial.png")
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", help="contact2d (default: $CONTACT2D or build/bin/contact2d)")
    ap.add_argument("--deck", default=str(DECK), help="a deck of the built-in mesh (default the paper scene P1)")
    ap.add_argument("--ranks", default="1,2", help="MPI ranks, a comma-separated list")
    ap.add_argument("--threads", default="1,2", help="OpenMP threads per rank, a comma-separated list")
    ap.add_argument("--level", type=int, default=5, help="mesh:level of the strong-scaling mesh and the weak base")
    ap.add_argument("--steps", type=int, default=2000, help="solver:max_steps of every run")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sections", default="strong,weak", help="strong, weak or both")
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--mpirun-args", default="", help="more mpirun options, e.g. '--bind-to none --mca "
                    "mpi_yield_when_idle 1'")
    ap.add_argument("--out", default="study/scaling", help="folder of scaling.json and the runs' files")
    ap.add_argument("--figure", help="PNG of the figures (e.g. docs/figures/scaling.png)")
    ap.add_argument("--force", action="store_true", help="replace an existing scaling.json")
    args = ap.parse_args()
    args.ranks = int_list(args.ranks, "--ranks")
    args.threads = int_list(args.threads, "--threads")
    if args.repeats < 1 or args.steps < 1 or args.level < 0:
        print("bench_scaling.py: refused: --repeats and --steps must be >= 1, --level >= 0", file=sys.stderr)
        sys.exit(2)
    sections = [s.strip() for s in args.sections.split(",") if s.strip()]
    if not sections or any(s not in ("strong", "weak") for s in sections):
        print("bench_scaling.py: refused: --sections %r: strong, weak or both" % args.sections, file=sys.stderr)
        sys.exit(2)
    out = out_dir(args.out, "bench_scaling.py")
    result = out / "scaling.json"
    if result.exists() and not args.force:
        print("bench_scaling.py: refused: %s exists (--force replaces it)" % result, file=sys.stderr)
        sys.exit(2)
    mesh = deck_mesh(args.deck)
    if "weak" in sections and mesh is None:
        print("bench_scaling.py: refused: weak scaling needs a deck whose &mesh has ny and ly (the built-in "
              "mesh): %s" % args.deck, file=sys.stderr)
        sys.exit(2)
    exe = find_exe(args.exe)
    cases = []
    for kind in sections:
        for t in args.threads:
            for r in args.ranks:
                sets = {"mesh:level": args.level, "solver:max_steps": args.steps}
                if kind == "weak":
                    p = r * t
                    sets.update({"mesh:ny": mesh[0] * p, "mesh:ly": repr(mesh[1] * p)})
                cases.append((kind, r, t, sets))
    t0 = time.monotonic()
    rows = measure(args, exe, cases, out)
    for kind in sections:
        table(rows, kind)
    tmp = Path(str(result) + ".partial")
    tmp.write_text(json.dumps({"deck": str(args.deck), "level": args.level, "steps": args.steps,
                               "mpirun_args": args.mpirun_args, "cores": os.cpu_count(), "rows": rows}, indent=1))
    os.replace(tmp, result)
    if args.figure:
        figure(rows, args.figure)
        print("figure: %s" % args.figure)
    print("(%d runs in %.1f s; table in %s)" % (len(cases) * args.repeats, time.monotonic() - t0, result))


if __name__ == "__main__":
    main()
