#!/usr/bin/env python3
"""Speed benchmark of contact2d on the paper scene: prints its figures (docs/performance.md).

    /usr/bin/python3 postproc/bench_speed.py [--levels 3-6] [--repeats 3] [--out study/bench] [--force]

For each mesh level k (13 2^k x 3 2^k elements):
  1. step throughput: element-steps per second of the step loop (contact included) with 1 and 2
     OpenMP threads, median of --repeats runs of a fixed number of steps, and the ratio 2/1;
  2. time to the quasi-static end state: steps and wall time of the default deck (P1, Tresca,
     relative residual 1e-8), best thread count;
  3. the same problem solved by the GetFEM static reference on the same mesh, timed in the same
     run (median of --repeats; postproc/getfem_reference.py, Tresca when it converges, else the
     frictionless variant for both codes), and the ratio explicit / static.
Then the speed targets with PASS/MISS (docs/performance.md, "Targets not met"), and the rows of
the table in --out/bench.json; a bench.json already there is refused before any run (one line,
exit 2) unless --force, and it is written beside its name and moved into place
(contact2d.outfile). Timings are wall-clock on a
shared machine: medians, and ratios of two things measured side by side.

More figures (each section can be chosen with --sections; speed is the list above):
  base     ns per element-step on one thread, this binary against --base-exe (the previous
           commit built apart), interleaved runs, median ratio;
  steps    steps and wall time to the end state with the default deck, solver:dt_limit =
           'power', the ramp of one lowest period (t_ramp = 1.25e-6 s), both, and mass scaling
           at twice the element-bound step; the end-state difference from the default;
  threads  the thread-robustness benchmark: the script starts a CPU-bound process itself (one
           core busy), runs one thread, the default settings (OMP_NUM_THREADS unset: the run
           picks its thread count), two fixed threads (the program's short spin, GOMP_SPINCOUNT),
           two passively waiting threads (OMP_WAIT_POLICY=passive) and two actively waiting threads
           (OMP_WAIT_POLICY=active), interleaved, then stops the load and runs one and default
           again: the ratios default / one thread (target <= 1.3 under load) and one / default
           idle (target >= 1.9 at k = 5-6);
  mass     mass scaling on the graded Hertz meshes (inputs/hertz_cylinder_p1.nml, hertz_indenter_p1.nml,
           --mass-levels): steps and wall to the end state without and with solver:mass_scaling =
           F x dt_critical (--mass-factors), frictionless (end state must not move) and Tresca
           (--tresca-threshold; the path effect is reported), added mass, end-state difference;
  static   the built-in static engine (`contact2d DECK --static`) beside the explicit end state
           when the binary has it, else n/a;
  general  the price of the general (Gmsh) path: ns per element-step on the Hertz Gmsh meshes
           (inputs/hertz_cylinder_p1.nml, hertz_indenter_p1.nml, --general-levels) against a
           structured mesh of the same size, one thread, interleaved runs, medians of the per-run
           ratio (target <= 1.5); with --base-exe also the base binary on the Hertz meshes.
"""
import argparse
import json
import os
import statistics

import numpy as np
import subprocess
import sys
import time
from pathlib import Path

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, out_dir, parse_levels, run
from contact2d.outfile import refusal_exits, refuse_existing, replacing

DECK = ROOT / "inputs" / "baillet_sassi_2002_p1.nml"
HERTZ_DECKS = ("hertz_cylinder_p1.nml", "hertz_indenter_p1.nml")
PYTHON = "/usr/bin/python3"
PROG = "bench_speed.py"


def throughput(exe, out, level, repeats):
    """Element-steps/s of the step loop with 1 and 2 threads over `repeats` runs of a fixed number
    of steps, the two thread counts interleaved (1, 2, 1, 2, ...) so that both see the same
    machine load; medians, and the median of the per-pair ratios."""
    nel = 39 * 4**level
    steps = max(200, int(3e8 / nel))          # about 3e8 element-steps per run
    rates = {1: [], 2: []}
    for i in range(repeats):
        for threads in (1, 2):
            h5 = out / f"tp_k{level}_t{threads}_{i}.h5"
            res = run(exe, DECK, h5, {"mesh:level": level, "solver:max_steps": steps, "solver:t_end": 1.0,
                                      "solver:tol_residual": 1e-300, "solver:power_iterations": 0,
                                      "output:history_interval": steps, "output:xdmf": False}, threads=threads)
            if res.returncode != 0:
                sys.exit(f"throughput run failed: {res.stderr}")
            with Run(h5) as r:
                rates[threads].append(int(r.attrs["steps"]) * int(r.attrs["element_count"])
                                      / float(r.attrs["time_steps_seconds"]))
            h5.unlink()
    ratios = [b / a for a, b in zip(rates[1], rates[2])]
    return statistics.median(rates[1]), statistics.median(rates[2]), statistics.median(ratios), steps


def end_state(exe, out, level, threads, repeats, sets):
    """Median wall time to the converged end state, and its steps."""
    walls, steps = [], None
    for i in range(repeats):
        h5 = out / f"end_k{level}_{i}.h5"
        res = run(exe, DECK, h5, {"mesh:level": level, "output:xdmf": False, **sets}, threads=threads)
        if res.returncode != 0:
            sys.exit(f"end-state run failed: {res.stderr}")
        with Run(h5) as r:
            if int(r.attrs["converged"]) != 1:
                sys.exit(f"k={level}: the end-state run did not converge")
            walls.append(float(r.attrs["wall_seconds"]))
            steps = int(r.attrs["steps"])
        if i < repeats - 1:
            h5.unlink()
    return statistics.median(walls), steps, h5


def getfem_time(src, out, level, friction, repeats):
    """Median GetFEM wall time (assembly + solve, as the script reports it) and total process time."""
    walls, procs = [], []
    for i in range(repeats):
        ref = out / f"gf_k{level}_{friction}_{i}.h5"
        t0 = time.perf_counter()
        proc = subprocess.run([PYTHON, str(ROOT / "postproc" / "getfem_reference.py"), str(src), "-o", str(ref),
                               "--friction", friction], capture_output=True, text=True)
        procs.append(time.perf_counter() - t0)
        if proc.returncode != 0:
            return None, None, proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed"
        with Run(ref) as r:
            walls.append(float(r.attrs["wall_seconds"]))
        ref.unlink()
    return statistics.median(walls), statistics.median(procs), None


def general_path(exe, out, repeats, levels=(1,), base=None):
    """ns per element-step of the step loop (1 thread, fixed steps, medians of interleaved runs) on
    the Hertz Gmsh meshes (inputs/hertz_cylinder_p1.nml and hertz_indenter_p1.nml at each level:
    the general path, src/kernels/contact2d_rows.f90) and on a built-in structured mesh of about
    as many elements (the paper deck with nx x ny set accordingly: the structured sweep), and
    their ratio (target: <= 1.5). With base, the Hertz runs are repeated with that
    binary too (the previous commit), interleaved."""
    common = {"solver:t_end": 1.0, "solver:tol_residual": 1e-300, "solver:power_iterations": 0,
              "output:xdmf": False}
    res = []
    print(f"\n== general path: ns per element-step, 1 thread, median of {repeats} interleaved runs", flush=True)
    for deck_name in HERTZ_DECKS:
        hertz_deck = ROOT / "inputs" / deck_name
        for level in levels:
            probe = out / "general_probe.h5"
            if run(exe, hertz_deck, probe, {"mesh:level": level, "solver:max_steps": 1, **common}).returncode != 0:
                sys.exit("general-path probe run failed")
            with Run(probe) as r:
                nel = int(r.attrs["element_count"])
            probe.unlink()
            ny = max(1, int(round(np.sqrt(nel * 3 / 13))))
            nx = max(1, int(round(nel / ny)))
            steps = max(200, int(1e8 / nel))
            kinds = ["gmsh", "structured"] + (["gmsh_base"] if base else [])
            ns = {k: [] for k in kinds}
            for i in range(repeats):
                for kind in kinds:
                    h5 = out / f"general_{kind}_{i}.h5"
                    if kind.startswith("gmsh"):
                        res_ = run(base if kind == "gmsh_base" else exe, hertz_deck, h5,
                                   {"mesh:level": level, "solver:max_steps": steps,
                                    "output:history_interval": steps, **common}, threads=1)
                    else:
                        res_ = run(exe, DECK, h5, {"mesh:level": 0, "mesh:nx": nx, "mesh:ny": ny,
                                                   "solver:max_steps": steps, "output:history_interval": steps,
                                                   **common}, threads=1)
                    if res_.returncode != 0:
                        sys.exit(f"general-path run failed: {res_.stderr}")
                    with Run(h5) as r:
                        ns[kind].append(1e9 * float(r.attrs["time_steps_seconds"])
                                        / (int(r.attrs["steps"]) * int(r.attrs["element_count"])))
                    h5.unlink()
            g, s_ = statistics.median(ns["gmsh"]), statistics.median(ns["structured"])
            ratio = statistics.median([a / b for a, b in zip(ns["gmsh"], ns["structured"])])
            line = (f"  {deck_name} level {level} ({nel} elements, {steps} steps): {g:.2f} ns per element-step; "
                    f"structured {nx} x {ny} = {nx * ny}: {s_:.2f}; ratio general / structured {ratio:.2f} "
                    f"[{'PASS' if ratio <= 1.5 else 'MISS'} <= 1.5]")
            if base:
                gb = statistics.median(ns["gmsh_base"])
                line += f"; base binary {gb:.2f} (base/new {statistics.median([b / a for a, b in zip(ns['gmsh'], ns['gmsh_base'])]):.2f}x)"
            print(line, flush=True)
            res.append({"deck": deck_name, "level": level, "elements": nel, "ns_gmsh": g, "ns_structured": s_,
                        "ratio": ratio})
    return res


def timed(exe, level, sets=None, env_threads="1", extra_env=None, out=None, name="x"):
    """One run; env_threads None: OMP_NUM_THREADS removed (the default settings). Returns the
    root attributes of the output and the final displacement."""
    import os
    h5 = out / f"{name}.h5"
    args = [exe, str(DECK), "-q", "-o", str(h5), "--force", "--set", f"mesh:level={level}",
            "--set", "output:xdmf=F"]
    for key, value in (sets or {}).items():
        args += ["--set", f"{key}={value}"]
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    if env_threads is not None:
        env["OMP_NUM_THREADS"] = env_threads
    env.update(extra_env or {})
    proc = subprocess.run(args, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        sys.exit(f"run failed: {' '.join(args)}: {proc.stderr}")
    with Run(h5) as r:
        attrs = dict(r.attrs)
        u = np.array(r.file["final/displacement"][()])
    h5.unlink()
    return attrs, u


def ns_per_element_step(attrs):
    return 1e9 * float(attrs["time_steps_seconds"]) / (int(attrs["steps"]) * int(attrs["element_count"]))


def section_base(exe, base, out, levels, repeats):
    """ns per element-step, one thread, this binary and the base binary interleaved."""
    print("\n== one sweep per step: ns per element-step, one thread, against the base binary", flush=True)
    res = []
    for k in levels:
        nel = 39 * 4**k
        steps = max(200, int(1e8 / nel))
        sets = {"solver:max_steps": steps, "solver:t_end": 1.0, "solver:tol_residual": 1e-300,
                "solver:power_iterations": 0, "output:history_interval": steps}
        ns = {"new": [], "base": []}
        for i in range(repeats):
            for tag, e in (("new", exe), ("base", base)):
                if e is None:
                    continue
                a, _ = timed(e, k, sets, "1", out=out, name=f"base_{tag}")
                ns[tag].append(ns_per_element_step(a))
        m_new = statistics.median(ns["new"])
        m_base = statistics.median(ns["base"]) if ns["base"] else None
        ratio = statistics.median([b / a for a, b in zip(ns["new"], ns["base"])]) if ns["base"] else None
        print(f"  k={k}: {m_new:.2f} ns/element-step" + (f", base {m_base:.2f}, base/new {ratio:.2f}x" if m_base else
                                                         ", base n/a (no --base-exe)") +
              f"   [{'PASS' if m_new <= 1.5 else 'MISS'} <= 1.5 ns]", flush=True)
        res.append((k, m_new, m_base, ratio))
    return res


def section_steps(exe, out, levels, repeats, threads):
    """Steps and wall time to the end state for the step-saving options."""
    print("\n== fewer steps: steps and wall to the end state (P1, Tresca), difference from the default", flush=True)
    for k in levels:
        base_attrs, u0 = timed(exe, k, {}, threads, out=out, name="st_default")
        dtc = float(base_attrs["dt_critical"])
        variants = [("default", {}), ("dt_limit=power", {"solver:dt_limit": "'power'"}),
                    ("t_ramp=1.25e-6", {"solver:t_ramp": 1.25e-6}),
                    ("power + ramp", {"solver:dt_limit": "'power'", "solver:t_ramp": 1.25e-6}),
                    ("mass_scaling=2dt_c", {"solver:mass_scaling": repr(2 * dtc)})]
        ref_steps = int(base_attrs["steps"])
        for name, sets in variants:
            walls, a, u = [], None, None
            for i in range(repeats):
                a, u = timed(exe, k, sets, threads, out=out, name="st")
                walls.append(float(a["wall_seconds"]))
            du = np.abs(u - u0).max() / np.abs(u0).max()
            extra = f", added mass {float(a['added_mass']) / float(a['body_mass']):.2f} x body" \
                if float(a.get("added_mass", 0)) > 0 else ""
            print(f"  k={k} {name:20s} steps {int(a['steps']):7d} ({int(a['steps']) / ref_steps:.3f} of default), "
                  f"wall {statistics.median(walls):8.3f} s, max|du|/max|u| {du:.1e}{extra}", flush=True)



def section_mass(exe, out, levels, factors, threads, tresca_threshold):
    """Mass scaling on the graded Hertz meshes: steps and wall to the end state without
    and with solver:mass_scaling = F x dt_critical (the unscaled element bound), frictionless
    (the end state is the unique static solution: it must not move beyond the tolerance) and a
    Tresca variant (contact:threshold; the path enters through the slip: the difference is
    reported, not judged). Prints max |u - u_0| / max |u_0| and the relative change of the total
    normal force against the unscaled run, and the added mass as a fraction of the body mass."""
    print("\n== mass scaling on the graded Hertz meshes: steps to the end state without and with "
          "solver:mass_scaling = F x dt_critical", flush=True)
    res = []
    for deck_name in HERTZ_DECKS:
        deck = ROOT / "inputs" / deck_name
        for friction in ("frictionless", "tresca"):
            fsets = {} if friction == "frictionless" else {"contact:friction": "tresca",
                                                           "contact:threshold": tresca_threshold}
            for k in levels:
                def one(extra, name):
                    h5 = out / f"mass_{name}.h5"
                    r = run(exe, deck, h5, {"mesh:level": k, "output:xdmf": False, **fsets, **extra},
                            threads=threads)
                    if r.returncode != 0:
                        sys.exit(f"mass-scaling run failed ({deck_name}, k={k}, {extra}): {r.stderr}")
                    with Run(h5) as f:
                        a = dict(f.attrs)
                        u = np.array(f.file["final/displacement"][()])
                        fn = float(np.sum(f.file["final/contact/normal_force"][()]))
                    h5.unlink()
                    if int(a["converged"]) != 1:
                        sys.exit(f"mass-scaling run did not converge ({deck_name}, k={k}, {extra})")
                    return a, u, fn
                a0, u0, fn0 = one({}, "ref")
                dtc = float(a0["dt_critical"])
                s0 = int(a0["steps"])
                print(f"  {deck_name} k={k} {friction} ({int(a0['element_count'])} elements): unscaled "
                      f"{s0} steps, {float(a0['wall_seconds']):.2f} s", flush=True)
                for fac in factors:
                    a, u, fn = one({"solver:mass_scaling": fac * dtc}, "scaled")
                    du = np.abs(u - u0).max() / np.abs(u0).max()
                    dfn = abs(fn - fn0) / abs(fn0)
                    ratio = s0 / int(a["steps"])
                    added = float(a["added_mass"]) / float(a["body_mass"])
                    print(f"     F={fac:<4g} {int(a['steps']):7d} steps ({ratio:.2f}x fewer"
                          f"{'' if friction != 'frictionless' else (', PASS' if ratio >= 3 else ', MISS')} >= 3x), "
                          f"{float(a['wall_seconds']):.2f} s, added mass {added:.3f} x body, "
                          f"max|du|/max|u| {du:.1e}, |dF_n|/F_n {dfn:.1e}", flush=True)
                    res.append({"deck": deck_name, "friction": friction, "level": k, "factor": fac,
                                "steps_ref": s0, "steps": int(a["steps"]), "ratio": ratio, "added": added,
                                "du": du, "dfn": dfn})
    return res


def section_threads(exe, out, levels, repeats):
    """The thread-robustness benchmark: a CPU-bound load on one core, started and stopped here."""
    print("\n== threads under load: a CPU-bound process occupies one core (started by this script)", flush=True)
    for k in levels:
        nel = 39 * 4**k
        steps = max(400, int(2e7 / nel))
        sets = {"solver:max_steps": steps, "solver:t_end": 1.0, "solver:tol_residual": 1e-300,
                "solver:power_iterations": 0, "output:history_interval": steps}
        # the program spins briefly then sleeps (GOMP_SPINCOUNT) unless told otherwise
        modes = [("1 thread", "1", {}), ("default", None, {}), ("2 threads", "2", {}),
                 ("2 passive", "2", {"OMP_WAIT_POLICY": "passive"}), ("2 active", "2", {"OMP_WAIT_POLICY": "active"})]
        load = subprocess.Popen([PYTHON, "-c", "while True: pass"])
        try:
            time.sleep(0.5)
            walls = {m[0]: [] for m in modes}
            for i in range(repeats):
                for name, thr, env in modes:
                    a, _ = timed(exe, k, sets, thr, env, out=out, name="thr")
                    walls[name].append(float(a["time_steps_seconds"]))
        finally:
            load.kill()
            load.wait()
        idle = {"1 thread": [], "default": [], "2 threads": []}
        for i in range(repeats):
            for name, thr in (("1 thread", "1"), ("default", None), ("2 threads", "2")):
                a, _ = timed(exe, k, sets, thr, out=out, name="thr")
                idle[name].append(float(a["time_steps_seconds"]))
        one = walls["1 thread"]
        print(f"  k={k}, {steps} steps, step-loop seconds (median of {repeats}), under load:")
        for name, _, _ in modes:
            r = statistics.median([w / o for w, o in zip(walls[name], one)])
            print(f"    {name:10s} {statistics.median(walls[name]):8.3f} s  = {r:.2f} x one thread"
                  + (f"   [{'PASS' if r <= 1.3 else 'MISS'} <= 1.3]" if name == "default" else ""))
        r = statistics.median([o / d for o, d in zip(idle["1 thread"], idle["default"])])
        r2 = statistics.median([o / d for o, d in zip(idle["1 thread"], idle["2 threads"])])
        print(f"    load stopped: one thread {statistics.median(idle['1 thread']):.3f} s, default "
              f"{statistics.median(idle['default']):.3f} s, 2 threads {statistics.median(idle['2 threads']):.3f} s: "
              f"speed-up {r:.2f}x (default), {r2:.2f}x (2 threads)"
              f"   [{'PASS' if r >= 1.9 else 'MISS'} >= 1.9 at k = 5-6; other processes' load "
              f"is not under this script's control]", flush=True)


def section_static(exe, out, levels, threads):
    """The static engine beside the explicit end state, when the binary has it."""
    print("\n== static engine (contact2d DECK --static) beside the explicit end state", flush=True)
    helptext = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
    has_static = "--static" in helptext
    for k in levels:
        a, _ = timed(exe, k, {}, threads, out=out, name="ex")
        line = f"  k={k}: explicit {float(a['wall_seconds']):.3f} s"
        if has_static:
            h5 = out / "static.h5"
            t0 = time.perf_counter()
            proc = subprocess.run([exe, str(DECK), "--static", "-q", "-o", str(h5), "--force",
                                   "--set", f"mesh:level={k}"], capture_output=True, text=True)
            ts = time.perf_counter() - t0
            line += f", static {ts:.3f} s (explicit/static {float(a['wall_seconds']) / ts:.2f})" \
                if proc.returncode == 0 else f", static failed: {proc.stderr.strip()[:80]}"
        else:
            line += ", static n/a (this binary has no --static)"
        print(line, flush=True)
    print("  graded Hertz mesh: ns per element-step on the general path in the 'general' section, "
          "steps with/without mass scaling on it in the 'mass' section", flush=True)


def machine_line():
    """The CPU the figures come from (figures of two CPUs do not compare: docs/performance.md)."""
    info = {}
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            key, _, val = line.partition(":")
            info.setdefault(key.strip(), val.strip())
    except OSError:
        return "machine: /proc/cpuinfo not readable"
    flags = info.get("flags", "").split()
    vec = "AVX-512" if "avx512f" in flags else ("AVX2" if "avx2" in flags else "no AVX2")
    load = ""
    try:
        load = ", load average " + Path("/proc/loadavg").read_text().split()[0]
    except OSError:
        pass
    return (f"machine: {info.get('model name', '?')}, family {info.get('cpu family', '?')} model "
            f"{info.get('model', '?')}, {vec}, {os.cpu_count()} CPUs{load}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--levels", default="3-6", help="mesh levels (default 3-6)")
    ap.add_argument("--repeats", type=int, default=7, help="runs per timing (median; default 7)")
    ap.add_argument("--out", default="study/bench", help="work directory")
    ap.add_argument("--no-getfem", action="store_true", help="skip the GetFEM reference")
    ap.add_argument("--sections", default="speed,base,steps,mass,threads,static,general",
                    help="comma list of speed, base, steps, mass, threads, static, general (default all)")
    ap.add_argument("--base-exe", help="the previous commit's contact2d, for the base section")
    ap.add_argument("--thread-levels", default="5", help="levels of the threads section (default 5)")
    ap.add_argument("--general-levels", default="1-2", help="Hertz mesh levels of the general section (default 1-2)")
    ap.add_argument("--mass-levels", default="0-2", help="Hertz mesh levels of the mass section (default 0-2)")
    ap.add_argument("--mass-factors", default="4",
                    help="comma list of mass-scaling targets in units of dt_critical (default 4)")
    ap.add_argument("--tresca-threshold", type=float, default=200.0,
                    help="Tresca threshold [MPa] of the mass section's friction variant (default 200)")
    ap.add_argument("--force", action="store_true",
                    help="replace bench.json already in --out (refused otherwise, before any run)")
    args = ap.parse_args()
    sections = set(args.sections.split(","))
    out = out_dir(args.out, PROG)
    if "speed" in sections:
        refuse_existing(PROG, [out / "bench.json"], args.force)
    print(machine_line(), flush=True)
    exe = find_exe(args.exe)
    for tag, e in (("build", exe), ("base build", args.base_exe)):
        if e:
            # the second line of `contact2d --version`: compiler, flags, the sweep's lanes
            lines = subprocess.run([str(e), "--version"], stdout=subprocess.PIPE, text=True).stdout.splitlines()
            print(f"{tag}: {lines[1] if len(lines) > 1 else '(no build line: an older binary)'}", flush=True)
    levels = parse_levels(args.levels)
    if "base" in sections:
        section_base(exe, args.base_exe, out, levels, args.repeats)
    if "steps" in sections:
        section_steps(exe, out, levels, max(1, args.repeats // 3), "1")
    if "mass" in sections:
        section_mass(exe, out, parse_levels(args.mass_levels), [float(x) for x in args.mass_factors.split(",")],
                     "1", args.tresca_threshold)
    if "threads" in sections:
        section_threads(exe, out, parse_levels(args.thread_levels), args.repeats)
    if "static" in sections:
        section_static(exe, out, levels, "1")
    if "general" in sections:
        general_path(exe, out, args.repeats, parse_levels(args.general_levels), args.base_exe)
    if "speed" not in sections:
        return

    rows = []
    for k in parse_levels(args.levels):
        row = {"level": k, "elements": 39 * 4**k}
        row["rate_1"], row["rate_2"], row["speedup"], row["throughput_steps"] = throughput(exe, out, k, args.repeats)
        threads = 2 if row["speedup"] > 1 else 1
        row["threads"] = threads
        print(f"k={k} ({row['elements']} elements): {row['rate_1']:.3e} element-steps/s on 1 thread, "
              f"{row['rate_2']:.3e} on 2 (median ratio {row['speedup']:.2f}x)", flush=True)
        # Tresca first; if GetFEM cannot do it, both codes solve the frictionless variant
        for friction in ("tresca", "frictionless"):
            sets = {} if friction == "tresca" else {"contact:friction": "frictionless", "contact:threshold": 0.0}
            wall, steps, h5 = end_state(exe, out, k, threads, args.repeats, sets)
            gf_wall, gf_proc, why = (None, None, "skipped") if args.no_getfem else \
                getfem_time(h5, out, k, friction, args.repeats)
            if gf_wall is not None or args.no_getfem:
                break
            print(f"   GetFEM {friction}: {why}; trying the frictionless variant")
        row.update(friction=friction, end_wall=wall, end_steps=steps, getfem_wall=gf_wall, getfem_process=gf_proc,
                   ratio=(wall / gf_wall) if gf_wall else None)
        # relaxation after the ramp against 1/2 (omega_max/omega_1) ln(1/tol), the step count of
        # optimally damped relaxation with dt = 2/omega_max (omega_1 = final alpha / 2)
        with Run(h5) as r:
            dt, wmax = float(r.attrs["dt"]), float(r.attrs["omega_max_power"])
            w1 = float(r.history("damping_alpha")[-1]) / 2
            ramp = int(round(float(r.deck["solver"]["t_ramp"]) / dt))
            tol = float(r.deck["solver"]["tol_residual"])
        row.update(ramp_steps=ramp, relax_steps=steps - ramp, relax_estimate=0.5 * wmax / w1 * np.log(1 / tol),
                   omega_ratio=wmax / w1)
        print(f"   end state ({friction}, {threads} thread(s)): {steps} steps, {wall:.3f} s" +
              (f"; GetFEM static {gf_wall:.3f} s (process {gf_proc:.2f} s): explicit/static = {wall / gf_wall:.2f}"
               if gf_wall else ""), flush=True)
        rows.append(row)

    print("\n level  elements   1 thread    2 threads  speedup | steps to end  wall [s]  GetFEM [s]  explicit/static")
    for r in rows:
        gf = f"{r['getfem_wall']:10.3f}  {r['ratio']:15.2f}" if r["getfem_wall"] else f"{'-':>10s}  {'-':>15s}"
        print(f" {r['level']:5d} {r['elements']:9d} {r['rate_1']:10.3e} {r['rate_2']:10.3e} {r['speedup']:7.2f}x | "
              f"{r['end_steps']:12d} {r['end_wall']:9.3f} {gf}")
    print("\nrelaxation after the ramp (tol 1e-8) against 1/2 (omega_max/omega_1) ln(1/tol):")
    for r in rows:
        print(f"  k={r['level']}: omega_max/omega_1 = {r['omega_ratio']:.0f}, {r['ramp_steps']} ramp steps, "
              f"{r['relax_steps']} relaxation steps, estimate {r['relax_estimate']:.0f} "
              f"(ratio {r['relax_steps'] / r['relax_estimate']:.2f})")
    print("\ntargets:")
    for r in rows:
        if r["level"] == 4:
            print(f"  {'PASS' if r['rate_1'] >= 1e8 else 'MISS'} >= 1e8 element-steps/s on one thread at k = 4: "
                  f"{r['rate_1']:.3e} ({1e9 / r['rate_1']:.2f} ns per element and step)")
            if r["getfem_wall"]:
                print(f"  {'PASS' if r['ratio'] <= 1 else 'MISS'} time to the end state <= GetFEM static at k = 4: "
                      f"{r['end_wall']:.3f} s against {r['getfem_wall']:.3f} s ({r['friction']})")
        if r["level"] >= 5:
            print(f"  {'PASS' if r['speedup'] >= 1.7 else 'MISS'} >= 1.7x on two threads at k = {r['level']}: "
                  f"{r['speedup']:.2f}x")
    with replacing(out / "bench.json", args.force) as tmp:
        Path(tmp).write_text(json.dumps(rows, indent=1))
    print(f"wrote {out / 'bench.json'}")


if __name__ == "__main__":
    with refusal_exits(PROG):
        main()
