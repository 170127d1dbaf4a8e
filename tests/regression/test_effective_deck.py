"""Regression 8: the effective deck stored in the file is a complete, exact deck.

For each case: run a deck (with --set overrides), write the file's 'effective_deck' attribute to
effective.nml, run that with no overrides, and check that
- the second run's effective_deck text is identical to the first's (the echo is a fixed point:
  reading it back gives the same values, so printing them again gives the same text);
- the final displacement is bitwise identical (same values in -> same arithmetic -> same bits:
  every real must be echoed with enough digits to round-trip exactly);
- dt, steps and the status are identical too.
Cases cover no contact, contact with multi-stage loads and snapshots, P0 with coordinate
ranges on the Dirichlet groups, and a dynamic run with an initial velocity.
"""
import numpy as np

import c2dtest

# name, deck, overrides, values the echo must show: (group, occurrence, variable, value).
# Reals with 17 significant digits check that the echo round-trips every bit.
CASES = [
    ("uniaxial", "uniaxial_compression.nml",
     ["--set", "mesh:level=1", "--set", "solver:dt_factor=0.83333333333333337"],
     [("mesh", 0, "level", 1), ("solver", 0, "dt_factor", 0.83333333333333337)]),
    ("tresca_p1", "tresca_sliding_p1.nml", ["--set", "contact:threshold=93.123456789012345"],
     [("contact", 0, "threshold", 93.123456789012345)]),
    ("coulomb_p0", "coulomb_sliding_p0.nml", ["--set", "contact:friction_coefficient=0.31234567890123457"],
     [("contact", 0, "friction_coefficient", 0.31234567890123457)]),
    ("baillet_p0", "baillet_sassi_2002_p0.nml",
     ["--set", "mesh:level=1", "--set", "dirichlet#3:values=-1.2345678901234567e-3"],
     [("mesh", 0, "level", 1), ("dirichlet", 3, "values", [-1.2345678901234567e-3])]),
    # &initial and a dynamic run (no convergence test, ends at t_end)
    ("impact_p1", "impact_bar_p1.nml",
     ["--set", "initial:velocity=0,-987.65432109876543", "--set", "output:history_interval=7"],
     [("initial", 0, "velocity", [0.0, -987.65432109876543]), ("solver", 0, "convergence_test", "auto")]),
]


def body(t):
    for name, deck, extra, shown in CASES:
        print()
        print("## case %s" % name)
        first = t.run(t.deck(deck), *extra, name=name + "_first")
        t.expect_exit(first, 0)
        t.expect_output(first)
        with first.open() as f:
            eff1 = c2dtest.attr_str(f.attrs["effective_deck"])
            u1 = f["final/displacement"][()]
            meta1 = (float(f.attrs["dt"]), int(f.attrs["steps"]), c2dtest.attr_str(f.attrs["status"]))
        # the overrides must show in the echo, exactly (otherwise the round trip would prove little)
        parsed = c2dtest.parse_effective_deck(eff1)
        for group, k, var, value in shown:
            grp = parsed[group][k - 1] if k else parsed[group]
            t.check_equal(first, "echo of --set %s%s:%s" % (group, "#%d" % k if k else "", var), value, grp.get(var))
        t.info(first, "effective deck", "%d lines, groups %s" % (len(eff1.splitlines()),
                                                                ", ".join(k for k in parsed if parsed[k])))
        cwd2 = t.subdir(name + "_second")
        path = cwd2 + "/effective.nml"
        with open(path, "w") as fh:
            fh.write(eff1)
        second = t.run(path, cwd=cwd2, output="out.h5")
        t.expect_exit(second, 0)
        t.expect_output(second)
        with second.open() as f:
            eff2 = c2dtest.attr_str(f.attrs["effective_deck"])
            u2 = f["final/displacement"][()]
            meta2 = (float(f.attrs["dt"]), int(f.attrs["steps"]), c2dtest.attr_str(f.attrs["status"]))
        t.check_lines_equal(second, "effective_deck text identical to the first run's", eff1.splitlines(),
                            eff2.splitlines())
        t.check_equal(second, "effective_deck identical as a whole string", True, eff1 == eff2)
        t.check_equal(second, "(dt, steps, status) identical", meta1, meta2)
        same = u1.shape == u2.shape and u1.dtype == u2.dtype and u1.tobytes() == u2.tobytes()
        ndiff = int(np.count_nonzero(u1 != u2)) if u1.shape == u2.shape else -1
        t.check(second, "final displacement bitwise identical", same, "identical bytes (%d values)" % u1.size,
                "identical" if same else "%d values differ, max |diff| %.3e" % (
                    ndiff, float(np.max(np.abs(u1 - u2))) if ndiff > 0 else float("nan")))


if __name__ == "__main__":
    c2dtest.Test("effective deck round trip: same echo, bitwise identical result").main(body)
