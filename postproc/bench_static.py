#!/usr/bin/env python3
"""Benchmark of the static engine on the paper scene: prints its figures (docs/static.md).

    /usr/bin/python3 postproc/bench_static.py [--levels 4-6] [--repeats 3] [--explicit-repeats 1]
                                              [--threads 1] [--multiplier P1] [--out study/bench_static]
                                              [--force]

For each mesh level k (13 2^k x 3 2^k elements), on one thread (OMP_NUM_THREADS=1) unless --threads
lists several counts (e.g. 1,2: the static runs are then repeated on each, interleaved, and each row
gives the speed-up against the first count, medians measured side by side, and the largest
difference of the end state's displacement to the first count's, max|du| / max|u|, or "bitwise"):
  1. static solve time (contact2d --static: assembly + CHOLMOD factorisation, condensation onto
     Gamma_c, active-set iteration and solves; the file's time_*_seconds attributes) and its wall
     time, medians of --repeats runs;
  2. the explicit run's wall time to its quasi-static end state (the shipped deck, relative
     residual 1e-8), median of --explicit-repeats runs, interleaved with the static runs so that
     both see the same machine load, and the ratio explicit / static;
  3. the static targets: static solve within 2x of 0.43 s (level 5) and 1.9 s (level 6), PASS/MISS.
Timings are wall-clock on a possibly shared machine: medians, ratios of things measured side by side;
the CPU time of the whole static run (user + system, from the child's resource usage) is printed
beside them, as it is less sensitive to the machine's load, with the load average before and after
and the BLAS the executable loads (ldd: OpenBLAS or the system's libblas.so.3, docs/static.md "BLAS").
The runs go to --out as static_kK.h5 and explicit_kK.h5 and are removed once read; a file of those
names already there is refused before any run (one line, exit 2) unless --force.
postproc/bench_speed.py can call static_times() for its own tables.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, levels_or_exit, out_dir, run
from contact2d.outfile import refuse_existing

PROG = "bench_static.py"
TARGETS = {5: 0.43, 6: 1.9}     # CHOLMOD with the contact condensed [s]; target within 2x (docs/static.md)


def static_times(exe, deck, out, level, threads=1, displacement=None):
    """One static run on `threads` OpenMP threads (the BLAS of the factorisation follows them,
    docs/static.md "Threads"): (solve seconds, wall seconds, factor, condense, increments seconds,
    CPU seconds). With a list `displacement`, the end state's displacement is appended to it."""
    h5 = out / f"static_k{level}.h5"
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    res = run(exe, deck, h5, {"mesh:level": level, "solver:method": "static", "output:xdmf": False},
              threads=threads)
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if res.returncode != 0:
        sys.exit(f"static run failed (level {level}): {res.stderr.strip()}")
    with Run(h5) as r:
        parts = [float(r.attrs[k]) for k in ("time_factor_seconds", "time_condense_seconds", "time_solve_seconds")]
        wall = float(r.attrs["wall_seconds"])
        if displacement is not None:
            displacement.append(r.read("final/displacement"))
    h5.unlink()
    cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
    return sum(parts), wall, *parts, cpu


def difference(u, ref):
    """max|u - ref| / max|ref| of two displacement fields, or 0 when they are bitwise equal."""
    return float(abs(u - ref).max() / abs(ref).max()) if not (u == ref).all() else 0.0


def blas_of(exe):
    """The BLAS library the executable loads (from ldd), for the header line. `contact2d` is a
    launcher (src/app/contact2d_launch.f90): the solver beside it is what links BLAS."""
    solver = os.path.join(os.path.dirname(exe), "contact2d-solver")
    if os.path.exists(solver):
        exe = solver
    try:
        text = subprocess.run(["ldd", exe], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown (ldd failed)"
    libs = [line.split("=>")[1].split("(")[0].strip() for line in text.splitlines()
            if "=>" in line and ("blas" in line.lower())]
    return ", ".join(libs) if libs else "none found by ldd"


def explicit_time(exe, deck, out, level):
    """Wall seconds and steps of an explicit run to its quasi-static end state (one thread)."""
    h5 = out / f"explicit_k{level}.h5"
    res = run(exe, deck, h5, {"mesh:level": level, "output:xdmf": False}, threads=1)
    if res.returncode != 0:
        sys.exit(f"explicit run failed (level {level}): {res.stderr.strip()}")
    with Run(h5) as r:
        wall, steps = float(r.attrs["wall_seconds"]), int(r.attrs["steps"])
    h5.unlink()
    return wall, steps


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="4-6", help="mesh levels, e.g. 4-6 (default)")
    ap.add_argument("--repeats", type=int, default=3, help="static runs per level (median)")
    ap.add_argument("--explicit-repeats", type=int, default=1, help="explicit runs per level (0: skip)")
    ap.add_argument("--threads", default="1",
                    help="OpenMP thread counts of the static runs, comma-separated (default 1); with several, "
                         "the speed-up and end-state difference against the first")
    ap.add_argument("--multiplier", default="P1", choices=["P1", "P0"])
    ap.add_argument("--out", default=str(ROOT / "study" / "bench_static"), help="scratch directory")
    ap.add_argument("--exe", help="contact2d executable (default: $CONTACT2D or build/bin/contact2d)")
    ap.add_argument("--force", action="store_true",
                    help="replace static_kK.h5 / explicit_kK.h5 already in --out (refused otherwise, before any run)")
    args = ap.parse_args()
    try:
        threads = [int(t) for t in args.threads.split(",")]
        if not threads or min(threads) < 1:
            raise ValueError
    except ValueError:
        print(f"{PROG}: refused: --threads '{args.threads}': give thread counts >= 1, e.g. 1,2", file=sys.stderr)
        sys.exit(2)
    exe = find_exe(args.exe)
    deck = ROOT / "inputs" / f"baillet_sassi_2002_{args.multiplier.lower()}.nml"
    levels = levels_or_exit(args.levels, "--levels", PROG)
    out = out_dir(args.out, PROG)
    kinds = [kind for kind, n in (("static", args.repeats), ("explicit", args.explicit_repeats)) if n > 0]
    refuse_existing(PROG, [out / f"{kind}_k{k}.h5" for k in levels for kind in kinds], args.force)

    on = "one thread" if threads == [1] else f"static runs on {args.threads} thread(s), explicit on one"
    print(f"static engine benchmark, paper scene {args.multiplier} Tresca, {on}; "
          f"medians of {args.repeats} static / {args.explicit_repeats} explicit run(s)")
    print(f"executable {exe}; BLAS libraries loaded: {blas_of(exe)}")
    print("load average before: %.2f %.2f %.2f (%d cores)" % (*os.getloadavg(), os.cpu_count() or 0))
    header = (f"{'level':>5} {'elements':>9} {'static s':>9} {'(factor':>8} {'condense':>9} {'solve)':>8} "
              f"{'wall s':>8} {'cpu s':>7} {'explicit s':>11} {'steps':>8} {'expl/static':>12}")
    if len(threads) > 1:
        header = f"{'threads':>7} " + header + f" {'speed-up':>9} {'max|du|/max|u|':>15}"
    print(header)
    rows = {}
    for level in levels:
        st = {t: [] for t in threads}
        disp = {t: [] for t in threads}
        ex = []
        for i in range(max(args.repeats, args.explicit_repeats)):
            if i < args.repeats:
                for t in threads:
                    st[t].append(static_times(exe, deck, out, level, t, disp[t] if len(threads) > 1 else None))
            if i < args.explicit_repeats:
                ex.append(explicit_time(exe, deck, out, level))
        ewall = statistics.median(e[0] for e in ex) if ex else float("nan")
        esteps = ex[0][1] if ex else 0
        base = None
        for t in threads:
            med = [statistics.median(x[j] for x in st[t]) for j in range(6)]
            line = (f"{level:>5} {39 * 4**level:>9} {med[0]:>9.3f} {med[2]:>8.3f} {med[3]:>9.3f} {med[4]:>8.3f} "
                    f"{med[1]:>8.3f} {med[5]:>7.3f} {ewall:>11.3f} {esteps:>8} {ewall / med[0]:>12.1f}")
            if len(threads) > 1:
                if base is None:
                    base = med[0]
                diff = max(difference(u, disp[threads[0]][0]) for u in disp[t])
                line = (f"{t:>7} " + line + f" {base / med[0]:>9.2f} "
                        + (f"{'bitwise':>15}" if diff == 0 else f"{diff:>15.1e}"))
            else:
                rows[level] = med[0]
            print(line)
            sys.stdout.flush()
    print("load average after:  %.2f %.2f %.2f" % os.getloadavg())
    for level, ref in TARGETS.items():
        if level in rows:
            verdict = "PASS" if rows[level] <= 2 * ref else "MISS"
            print(f"target level {level}: static solve {rows[level]:.3f} s <= 2 x {ref} s: {verdict}")


if __name__ == "__main__":
    main()
