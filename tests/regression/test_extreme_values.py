"""Values at the ends of the accepted ranges (|value| <= 1e30) give the same answer in the Release
and the Debug build (FPE traps): a run or a one-line refusal, never a signal.

- solver:dt = 1e30 s: refused (exit 1, one stderr line) as beyond dt_critical, with the ratio
  dt / dt_critical of the two values the line prints (to 4 digits; it was printed as 0 after an
  integer overflow of nint, and trapped in Debug);
- solver:dt_factor = 1e-310 (a subnormal number): refused as out of range [1e-30, 1e30] (the step
  count t_end/dt overflowed, a trap in Debug);
- output:snapshot_times = 1e30 s: the run ends normally (exit 0) and the summary names the time as
  not reached (the step of the snapshot overflowed a 64-bit integer, a trap in Debug).
"""
import re

import c2dtest

DECK = "uniaxial_compression.nml"


def one_error_line(t, run):
    t.expect_exit(run, 1, stop=False)
    lines = run.stderr_lines()
    t.check_equal(run, "one line on stderr", 1, len(lines))
    t.check_equal(run, "nothing written", [], sorted(__import__("os").listdir(run.cwd)))
    return lines[0] if lines else ""


def body(t):
    run = t.run(t.deck(DECK), "--set", "solver:dt=1e30", name="dt_1e30")
    line = one_error_line(t, run)
    m = re.search(r"dt = (\S+) s exceeds dt_critical = (\S+) s \(ratio (\S+)\)", line)
    t.check(run, "message names dt, dt_critical and their ratio", m is not None, "dt = ... (ratio ...)", line)
    if m:
        dt, crit, ratio = (float(g) for g in m.groups())
        t.check_close(run, "ratio = dt / dt_critical", dt / crit, ratio, rtol=1e-3)

    run = t.run(t.deck(DECK), "--set", "solver:dt_factor=1e-310", name="dt_factor_subnormal")
    line = one_error_line(t, run)
    t.check(run, "message names dt_factor and its range",
            re.search(r"solver:dt_factor = 1e-310 is out of range \[1e-30, 1e30\]", line) is not None,
            "solver:dt_factor = 1e-310 is out of range [1e-30, 1e30]", line)

    run = t.run(t.deck(DECK), "--set", "output:snapshot_times=1e30", name="snapshot_1e30")
    t.expect_exit(run, 0, stop=False)
    t.check(run, "summary names the snapshot time as not reached",
            re.search(r"snapshots +not reached: output:snapshot_times 1e30", run.stdout) is not None,
            "'snapshots           not reached: output:snapshot_times 1e30 ...'",
            [l for l in run.stdout.splitlines() if "snapshot" in l])


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
