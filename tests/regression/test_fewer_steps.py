#!/usr/bin/env python3
"""Fewer steps, same end state: true-limit dt, a ramp of one lowest period, mass scaling.

The paper scene (P1 and P0, Tresca) at level 2 is run four ways: the default deck; with
solver:dt_limit = 'power' (dt from the power-iteration estimate of the true stability limit,
growing-mode guard on); with ramps of 2.5e-6 s and 1.25e-6 s (about two and one periods of the
lowest mode, omega_1 ~ 5.5e6 1/s); with solver:mass_scaling at twice the element-bound step. All
must converge (relative residual < 1e-8) to the same static end state: loading is proportional
and the damping removes the kinetic energy, so the path only enters through Tresca's slip, which
the stability study (docs/stability.md section 5) found settled within one lowest period.

The variants must also save steps: the power step is longer than the element-bound step (the
element bound is conservative by 18 % on this mesh), and the ramp of one period takes fewer
steps than that of two. A
run with dt_factor = 1.05 on the power estimate starts above the true limit (the power estimate
bounds omega_max from below, so 1.05 x 2/omega_power > 2/omega_max): the guard must catch the
growing mode, fall back to the element bound, and still reach the same end state.
"""
import os

import numpy as np

import c2dtest

LEVEL = "2"
# Each run stops at a relative residual < tol_residual = 1e-8. Two such states differ in
# displacement by at most cond(K) x 1e-8 relative, cond(K) = (omega_max/omega_1)^2 ~ 85^2 ~ 7e3
# at level 2 (docs/performance.md, relaxation table): 1e-4 bounds that with margin.
RTOL = 1e-4
REASON = "two states with relative residual < 1e-8 differ by <= cond(K) 1e-8 ~ 7e-5 (cond ~ 85^2 at level 2)"


def final(run):
    with run.open() as f:
        return {"u": f["final/displacement"][()], "fn": f["final/contact/normal_force"][()],
                "steps": int(f.attrs["steps"]), "converged": int(f.attrs["converged"]),
                "dt": float(f.attrs["dt"]), "dt_critical": float(f.attrs["dt_critical"]),
                "added_mass": float(f.attrs["added_mass"]), "body_mass": float(f.attrs["body_mass"]),
                "fallback": int(f.attrs["dt_fallback_step"])}


def body(t):
    for m in ("p1", "p0"):
        deck = t.deck("baillet_sassi_2002_%s.nml" % m)
        base = t.run(deck, "--set", "mesh:level=" + LEVEL, name="%s_default" % m)
        t.expect_exit(base, 0)
        ref = final(base)
        t.check_equal(base, "converged (%s default)" % m, 1, ref["converged"])
        variants = {
            "power": ["--set", "solver:dt_limit='power'"],
            "ramp_2.5e-6": ["--set", "solver:t_ramp=2.5e-6"],
            "ramp_1.25e-6": ["--set", "solver:t_ramp=1.25e-6"],
            "mass": ["--set", "solver:mass_scaling=%r" % (2 * ref["dt_critical"])],
            # dt = 1.05 x 2/omega_power > 2/omega_max (the Rayleigh quotient bounds omega_max from below)
            "guard": ["--set", "solver:dt_limit='power'", "--set", "solver:dt_factor=1.05",
                      "--set", "solver:allow_unstable=.true."],
        }
        steps = {}
        for name, args in variants.items():
            r = t.run(deck, "--set", "mesh:level=" + LEVEL, *args, name="%s_%s" % (m, name))
            t.expect_exit(r, 0)
            got = final(r)
            steps[name] = got["steps"]
            t.check_equal(r, "converged (%s %s)" % (m, name), 1, got["converged"])
            du = np.abs(got["u"] - ref["u"]).max() / np.abs(ref["u"]).max()
            t.check(r, "max |u - u_default| / max |u_default| (%s %s)" % (m, name), du <= RTOL,
                    "<= %g" % RTOL, "%.3e" % du, "%g" % RTOL, REASON)
            dfn = np.abs(got["fn"] - ref["fn"]).max() / np.abs(ref["fn"]).max()
            t.check(r, "max |F_n - F_n default| / max F_n (%s %s)" % (m, name), dfn <= RTOL,
                    "<= %g" % RTOL, "%.3e" % dfn, "%g" % RTOL, REASON)
            if name == "power":
                t.check(r, "fewer steps than the default (%s %s)" % (m, name), got["steps"] < ref["steps"],
                        "< %d" % ref["steps"], str(got["steps"]))
            if name == "ramp_1.25e-6":
                t.check(r, "fewer steps with the ramp of one period than with two (%s)" % m,
                        got["steps"] < steps["ramp_2.5e-6"], "< %d" % steps["ramp_2.5e-6"], str(got["steps"]))
            if name == "power":
                t.check(r, "dt above the element-bound choice 0.9 dt_critical (%s)" % m,
                        got["dt"] > 0.9 * got["dt_critical"] * (1 + 1e-9), "> %.4e" % (0.9 * got["dt_critical"]),
                        "%.4e" % got["dt"])
                t.check_equal(r, "no growing mode with 100 power iterations (%s)" % m, -1, got["fallback"])
            if name == "mass":
                t.check(r, "mass added (%s)" % m, got["added_mass"] > 0, "> 0", "%.3e" % got["added_mass"])
            if name == "guard":
                t.check(r, "growing mode caught, fallback to the element bound (%s)" % m, got["fallback"] > 0,
                        "> 0", str(got["fallback"]))
                t.check(r, "guard warning on stderr (%s)" % m, "growing mode" in r.stderr, "present",
                        "present" if "growing mode" in r.stderr else "absent")

    # mass scaling is refused for a dynamic run (no damping): one line, exit 1, nothing written
    r = t.run(t.deck("baillet_sassi_2002_p1.nml"), "--set", "mesh:level=0", "--set", "solver:damping='none'",
              "--set", "solver:mass_scaling=1e-8", name="refused")
    t.expect_exit(r, 1)
    t.check(r, "nothing written (refused, no damping)", not os.path.exists(r.h5), "no out.h5",
            "present" if os.path.exists(r.h5) else "no out.h5")
    # ... and with an initial velocity (&initial), even with automatic damping
    r = t.run(t.deck("impact_bar_p1.nml"), "--set", "solver:damping='auto'", "--set", "solver:mass_scaling=1e-8",
              name="refused_velocity")
    t.expect_exit(r, 1)
    t.check(r, "error names mass scaling and the initial velocity", "mass_scaling" in r.stderr and
            "initial:velocity" in r.stderr, "both named", r.stderr.strip()[:120])
    t.check(r, "nothing written (refused, initial velocity)", not os.path.exists(r.h5), "no out.h5",
            "present" if os.path.exists(r.h5) else "no out.h5")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
