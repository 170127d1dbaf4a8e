#!/usr/bin/env python3
"""How a run ends and what it says about it (a new user's review).

- solver:t_end: a run without convergence stops at the first step n with t_n >= t_end (within a
  relative 1e-12), the rule dynamic runs always followed with a history sample at every step:
  t_end <= final time < t_end + dt, steps = that n, whatever the history and check intervals
  (the chunk of steps between two checks is cut at t_end; the old code ran on to the next
  check: 3900 steps instead of 3892 on the paper scene with check_interval = 50). A run cut at
  every step (history_interval = check_interval = 1) must give bit for bit the same end state.
- output:snapshot_times after the end of the run (the paper scene converges at 5.06e-6 s;
  times 1e-6, 5e-5, 6e-5 s): one summary line names the times not reached and the root attribute
  snapshot_times_not_reached lists them (the old code dropped them silently); a run that reaches
  all its times has neither.
- A load ramp of a few steps (the units off: material:young in Pa and density in kg/m^3 with
  lengths in mm make dt 1000 x too long, and the paper scene's 2.5e-6 s ramp 3.1 steps): one
  warning line on stderr naming the stage, its duration, dt and the units; the run is not
  refused. The bound is 10 steps (9.5 warned, 10.5 not); no shipped deck is warned about (the
  old code never warned).
- The SIGINT and blow-up error lines give their reals as the summary does, 4 significant digits
  (t = 6.220E-07 s, not 6.219569585794207e-7), and the value is the file's.
"""
import glob
import os
import re
import signal
import subprocess
import time

import h5py
import numpy as np

import c2dtest

PAPER = "baillet_sassi_2002_p1.nml"
IMPACT = "impact_bar_p1.nml"


def end_step(dt, t_end):
    """The first n >= 1 with n dt >= t_end (1 - 1e-12), n dt formed as the solver forms t_n."""
    limit = t_end * (1 - 1e-12)
    n = 1
    while n * dt < limit:
        n += 1
    return n


def final(run):
    with run.open() as f:
        return {"steps": int(f.attrs["steps"]), "final_time": float(f.attrs["final_time"]),
                "dt": float(f.attrs["dt"]), "status": c2dtest.attr_str(f.attrs["status"]),
                "hist_time": float(f["history/time"][-1]), "hist_step": int(f["history/step"][-1]),
                "u": f["final/displacement"][()], "v": f["final/velocity"][()]}


def check_t_end(t, label, deck, t_end, args, status):
    """A run to t_end with the given chunking against the same run cut at every step (the later
    --set of a variable wins)."""
    chunked = t.run(t.deck(deck), "--set", "solver:t_end=%r" % t_end, *args, name=label)
    t.expect_exit(chunked, 0)
    every = t.run(t.deck(deck), "--set", "solver:t_end=%r" % t_end, *args, "--set", "output:history_interval=1",
                  "--set", "solver:check_interval=1", name=label + "_every_step")
    t.expect_exit(every, 0)
    a, b = final(chunked), final(every)
    t.check_equal(chunked, "status (t_end reached)", status, a["status"])
    n = end_step(a["dt"], t_end)
    t.check_equal(chunked, "steps = first n with n dt >= t_end", n, a["steps"],
                  reason="t_end = %r, dt = %r: t_end/dt = %.6f" % (t_end, a["dt"], t_end / a["dt"]))
    t.check(chunked, "final_time in [t_end, t_end + dt)", t_end * (1 - 1e-12) <= a["final_time"] < t_end + a["dt"],
            "[%r, %r)" % (t_end, t_end + a["dt"]), repr(a["final_time"]))
    t.check_equal(chunked, "last history sample at the end (time)", a["final_time"], a["hist_time"])
    t.check_equal(chunked, "last history sample at the end (step)", a["steps"], a["hist_step"])
    t.check_equal(chunked, "steps = those of the run cut at every step", b["steps"], a["steps"])
    t.check(chunked, "final displacement and velocity bit for bit those of the run cut at every step",
            np.array_equal(a["u"], b["u"]) and np.array_equal(a["v"], b["v"]), True,
            np.array_equal(a["u"], b["u"]) and np.array_equal(a["v"], b["v"]))


def body(t):
    # ---- 1. solver:t_end is not overshot ------------------------------------------------------
    # quasi-static, not converged by t_end (the load ends at 2.5e-6 s, convergence at 5.06e-6 s)
    check_t_end(t, "t_end_check50", PAPER, 3.1e-6, ["--set", "solver:check_interval=50"], "not converged")
    # the history interval cuts the chunks too
    check_t_end(t, "t_end_hist37", PAPER, 3.1e-6, ["--set", "output:history_interval=37"], "not converged")
    # a t_end on a step (dt given: 6200 dt = 3.1e-6 up to rounding) is reached at that step
    check_t_end(t, "t_end_on_a_step", PAPER, 3.1e-6, ["--set", "solver:dt=5e-10", "--set", "solver:check_interval=60",
                                                              "--set", "output:history_interval=30"],
                "not converged")
    # a dynamic run (no convergence test) with a history sample every 10 steps
    check_t_end(t, "t_end_dynamic", IMPACT, 6.0e-7, ["--set", "output:history_interval=10"], "dynamic")

    # ---- 2. snapshot times after the end of the run -------------------------------------------
    run = t.run(t.deck(PAPER), "--set", "output:snapshot_times=1e-6,5e-5,6e-5", name="snapshots_missed")
    t.expect_exit(run, 0)
    lines = [l for l in run.stdout.splitlines() if l.strip().startswith("snapshots")]
    t.check_equal(run, "summary lines about snapshots", 1, len(lines))
    line = lines[0] if lines else ""
    t.check(run, "the line names the times not reached", "not reached" in line and "5e-5, 6e-5 s" in line
            and "1 of 3 written" in line, "not reached: ... 5e-5, 6e-5 s ...; 1 of 3 written", line)
    with run.open() as f:
        t.check_equal(run, "converged (before the last two times)", 1, int(f.attrs["converged"]))
        t.check(run, "final_time between the first and the second time", 1e-6 <= float(f.attrs["final_time"]) < 5e-5,
                "[1e-6, 5e-5)", float(f.attrs["final_time"]))
        missed = f.attrs.get("snapshot_times_not_reached")
        t.check(run, "root attribute snapshot_times_not_reached", missed is not None
                and np.array_equal(np.asarray(missed, dtype=float), [5e-5, 6e-5]), [5e-5, 6e-5],
                None if missed is None else list(missed))
        t.check_equal(run, "snapshot groups", 1, len(f["fields"]))
    run = t.run(t.deck(PAPER), "--set", "output:snapshot_times=1e-6,5e-6", name="snapshots_all")
    t.expect_exit(run, 0)
    t.check_equal(run, "no summary line about snapshots when all are written", [],
                  [l for l in run.stdout.splitlines() if l.strip().startswith("snapshots")])
    with run.open() as f:
        t.check_equal(run, "no snapshot_times_not_reached attribute", False, "snapshot_times_not_reached" in f.attrs)
        t.check_equal(run, "snapshot groups", 2, len(f["fields"]))

    # ---- 3. a load ramp of a few steps is warned about ----------------------------------------
    def ramp_lines(run):
        return [l for l in run.stderr_lines() if "warning" in l and "load ramp" in l]

    run = t.run(t.deck(PAPER), "--set", "material:young=7e10", "--set", "material:density=2700", name="ramp_si_units")
    t.expect_exit(run, 0)
    lines = ramp_lines(run)
    t.check_equal(run, "one warning about the load ramp", 1, len(lines))
    line = lines[0] if lines else ""
    with run.open() as f:
        dt = float(f.attrs["dt"])
    t.check(run, "the warning names the stage, its duration, its steps, dt and the units",
            line.startswith("contact2d: warning: ") and "dirichlet#2 (stage 1)" in line and "2.500E-06 s" in line
            and "only %.1f step(s)" % (2.5e-6 / dt) in line and "dt = %.3E s" % dt in line and "units" in line,
            "dirichlet#2 (stage 1) ... 2.500E-06 s, only %.1f step(s) of dt = %.3E s ... units" % (2.5e-6 / dt, dt), line)
    t.check(run, "the run went on (summary printed)", "dt / dt_critical" in run.stdout, True, "dt / dt_critical" in run.stdout)
    for steps, warned in ((9.5, True), (10.5, False)):
        run = t.run(t.deck(PAPER), "--set", "solver:dt=5e-10", "--set", "solver:t_ramp=%r" % (steps * 5e-10),
                    "--set", "solver:max_steps=1", name="ramp_%g_steps" % steps)
        t.expect_exit(run, 0)
        t.check_equal(run, "warned about a ramp of %g steps" % steps, warned, len(ramp_lines(run)) == 1)
    decks = sorted(glob.glob(os.path.join(t.inputs, "*.nml")) + glob.glob(os.path.join(t.here, "decks", "*.nml")))
    t.check(t.workdir, "shipped decks found", len(decks) >= 20, ">= 20", len(decks))
    for deck in decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        run = t.run(deck, "--set", "solver:max_steps=1", name="ramp_shipped_" + name)
        t.expect_exit(run, 0)
        t.check_equal(run, "no load-ramp warning for " + name, [], ramp_lines(run))

    # ---- 4. the SIGINT and blow-up lines at the summary's precision -----------------------------
    sci = r"-?\d\.\d{3}E[+-]\d{2}"     # Fortran es10.3, the summary's sci()
    run = t.run(t.deck("uniaxial_compression.nml"), "--set", "solver:dt_factor=2", "--set", "solver:allow_unstable=.true.",
                name="blow_up")
    t.expect_exit(run, 2, stop=False)
    err = run.error_lines()
    line = err[0] if err else ""
    m = re.search(r"blew up at step (\d+) \(t = (\S+) s\): kinetic energy (\S+) mJ exceeds 1000 x the work put in "
                  r"\((\S+) mJ\)", line)
    t.check(run, "blow-up line: t, kinetic energy and work in with 4 significant digits",
            m is not None and all(re.fullmatch(sci, g) for g in m.groups()[1:]), "t = d.dddE+dd s ... d.dddE+dd mJ", line)
    if m is not None and os.path.exists(run.h5):
        with run.open() as f:
            t.check_equal(run, "blow-up line: the file's final time", "%.3E" % float(f.attrs["final_time"]), m.group(2))
            t.check_equal(run, "blow-up line: the file's steps", int(f.attrs["steps"]), int(m.group(1)))

    folder = t.subdir("sigint")
    cmd = [t.exe, t.deck("baillet_sassi_2002_p0.nml"), "-o", "out.h5", "-q", "--set", "mesh:level=2",
           "--set", "solver:tol_residual=1e-300", "--set", "solver:t_end=1.0"]
    print("-- start (cd %s && %s)" % (folder, " ".join(cmd)))
    proc = subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    t0 = time.monotonic()
    while not glob.glob(os.path.join(folder, "out.h5.*.partial")) and time.monotonic() - t0 < 60:
        time.sleep(0.05)
    time.sleep(0.5)
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=120)
    lines = [l for l in stderr.decode("utf-8", "replace").splitlines() if l.strip()]
    print("   exit %d; stderr: %s" % (proc.returncode, " | ".join(lines)))
    t.check_equal("sigint", "exit code", 130, proc.returncode)
    line = lines[0] if lines else ""
    m = re.search(r"interrupted by SIGINT at step (\d+) \(t = (\S+) s\)", line)
    t.check("sigint", "SIGINT line: t with 4 significant digits", m is not None and re.fullmatch(sci, m.group(2)),
            "at step N (t = d.dddE+dd s)", line)
    if m is not None:
        with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
            t.check_equal("sigint", "SIGINT line: the file's final time", "%.3E" % float(f.attrs["final_time"]), m.group(2))
            t.check_equal("sigint", "SIGINT line: the file's steps", int(f.attrs["steps"]), int(m.group(1)))


if __name__ == "__main__":
    c2dtest.Test("run end: t_end, snapshot times not reached, short load ramp, message precision").main(body)
