#!/usr/bin/env python3
"""The static engine takes an increment that does not settle again in halves (solver:static_splits).

An increment whose active-set iteration cycles or needs more than solver:static_iterations
iterations is taken again from the last settled state in two halves, each of which may be halved
in turn (docs/static.md "Increments that do not settle"). A half is an ordinary increment: the run
must then be the run whose deck asks for the halves itself. Facts checked on mindlin_cylinder
(Coulomb partial slip, P1 and P0), one increment with static_iterations = 8 (its single increment
needs 18-20 active-set iterations, each half fewer than 8):
1. the run converges, says so in its summary, and records one halving and two steps
   (static_splits = 1, static_steps = 2; history times 0, T/2, T);
2. its end state is the one of static_increments = 2 (the same two increments from the same
   states: equal to 1e-12 of max |u|, measured bitwise);
3. with static_splits = 0 the same cap is reported, not hidden: exit 2, one error line naming
   solver:static_iterations, the file written with converged = 0;
4. out-of-range values are refused before anything is written: one line, exit 1;
5. the shipped mindlin decks use solver:mass_scaling, which the static engine has no use for (no
   mass, no time step): --static runs them as they are, with one warning naming it, and writes
   added_mass = 0.
"""
import os

import numpy as np

import c2dtest

CAP = ["--set", "solver:static_iterations=8"]


def body(t):
    for m in ("p1", "p0"):
        deck = t.deck("mindlin_cylinder_%s.nml" % m)
        split = t.run(deck, "--static", "--set", "solver:static_increments=1", *CAP, name="split_%s" % m,
                      quiet=False)
        t.expect_exit(split, 0)
        two = t.run(deck, "--static", "--set", "solver:static_increments=2", name="two_%s" % m)
        t.expect_exit(two, 0)
        t.check(split, "summary names the halving (%s)" % m, "1 halving(s)" in split.stdout, "a halving line",
                "present" if "1 halving(s)" in split.stdout else "absent")
        warned = [l for l in split.stderr_lines() if "warning" in l and "solver:mass_scaling" in l]
        t.check(split, "one warning: mass_scaling not used by the static engine (%s)" % m, len(warned) == 1,
                "one line", repr(warned))
        with split.open() as a, two.open() as b:
            t.check_equal(split, "converged (%s)" % m, 1, int(a.attrs["converged"]))
            t.check_equal(split, "added_mass (%s)" % m, 0.0, float(a.attrs["added_mass"]))
            t.check_equal(split, "static_splits (%s)" % m, 1, int(a.attrs["static_splits"]))
            t.check_equal(split, "static_steps (%s)" % m, 2, int(a.attrs["static_steps"]))
            times = a["history/time"][()]
            tb = b["history/time"][()]
            t.check(split, "history times 0, T/2, T (%s)" % m, len(times) == 3 and np.array_equal(times, tb),
                    str(tb.tolist()), str(times.tolist()))
            ua, ub = a["final/displacement"][()], b["final/displacement"][()]
            d = np.abs(ua - ub).max() / np.abs(ub).max()
            t.check_le(split, "end state against static_increments = 2 (%s)" % m, d, 1e-12,
                       reason="the same two increments from the same states")
        # no halving allowed: the cap is reported, the file written as not converged
        capped = t.run(deck, "--static", "--set", "solver:static_increments=1", "--set", "solver:static_splits=0",
                       *CAP, name="capped_%s" % m)
        t.expect_exit(capped, 2, stop=False)
        errors = capped.error_lines()
        t.check(capped, "one error line naming solver:static_iterations (%s)" % m,
                len(errors) == 1 and "solver:static_iterations" in errors[0], "one line", repr(errors))
        if os.path.exists(capped.h5):
            with capped.open() as f:
                t.check_equal(capped, "file written with converged = 0 (%s)" % m, 0, int(f.attrs["converged"]))
        else:
            t.check(capped, "file written (%s)" % m, False, "present", "absent")
    deck = t.deck("mindlin_cylinder_p1.nml")
    for setting in ("solver:static_iterations=0", "solver:static_splits=-1", "solver:static_splits=21"):
        bad = t.run(deck, "--static", "--set", setting, name="bad")
        t.expect_exit(bad, 1, stop=False)
        name = setting.split("=")[0]
        t.check(bad, "%s refused in one line" % setting,
                len(bad.error_lines()) == 1 and name in bad.error_lines()[0], "one line naming " + name,
                repr(bad.error_lines()))
        t.check(bad, "nothing written (%s)" % setting, os.listdir(bad.cwd) == [], "[]", repr(os.listdir(bad.cwd)))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
