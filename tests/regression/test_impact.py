#!/usr/bin/env python3
"""Impact of a block on the rigid plane against the exact 1D wave solution.

inputs/impact_bar_<m>.nml: a block of height L with roller sides (uniaxial strain) moving with
-v0 hits the plane after a gap g0. Exact (deck header): contact from t0 = g0/v0 for 2L/c,
pressure rho c v0, rebound velocity +v0. Measured with contact2d.impact on a history
sample at every step, at levels 2 (shipped), 3 and 4:
- the run is dynamic: status 'dynamic', no convergence test, ends at t_end;
- initial kinetic energy = 1/2 rho L lx v0^2 (the start v^(-1/2) = v0);
- contact starts within one step of t0 (forward increment: the force acts at the step before
  the bottom would penetrate, t0 - dt <= t_first < t0);
- duration = 2L/c within 2 % plus two steps; contact over before t_end;
- mean pressure over the contact = rho c v0 within 2 % (at level 4; levels 2 and 3 printed);
- rebound velocity within 3 % of v0 at the shipped level, closer at each finer level; the
  normal contact work (kinetic energy removed by the forward increment) shrinks with the mesh;
- no penetration: per node (P1) or per dual cell (P0), <= 1e-12 g0 at every step;
- energy balance (initial kinetic energy and normal contact work included) <= 1e-10 at every step.
--multiplier penalty runs inputs/impact_bar_penalty.nml at the shipped level: the penetration
plateau rho c v0 / k_p (spring bed in series with the bar) within 5 %, balance <= 1e-10.
"""
import numpy as np

import c2dtest
from contact2d.h5 import Run
from contact2d.impact import exact, measure

LEVELS = (2, 3, 4)
SHIPPED = 2


def lagrange(t, name):
    deck = t.deck("impact_bar_%s.nml" % name)
    rebound_err, work = [], []
    for level in LEVELS:
        run = t.run(deck, "--set", "mesh:level=%d" % level, "--set", "output:history_interval=1",
                    name="level%d" % level)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with Run(run.h5) as r:
            ex = exact(r)
            me = measure(r, ex)
            status = c2dtest.attr_str(r.attrs["status"])
            dynamic, converged = int(r.attrs["dynamic"]), int(r.attrs["converged"])
            kin0 = float(r.history("kinetic_energy")[0])
            multiplier = c2dtest.attr_str(r.attrs["multiplier"])
        dt = me["dt"]
        t.check_equal(run, "multiplier", name.upper(), multiplier)
        t.check_equal(run, "(status, dynamic, converged)", ("dynamic", 1, 0), (status, dynamic, converged),
                      reason="non-zero initial velocity and damping = 'none': a dynamic run, no convergence test")
        t.check_close(run, "initial kinetic energy = 1/2 rho L lx v0^2 [mJ]", ex["kinetic"],
                      me["initial_kinetic"], rtol=1e-12, reason="v^(-1/2) = v0 on every node; lumped masses sum to rho L lx")
        t.check_close(run, "kinetic energy of the first history sample [mJ]", ex["kinetic"], kin0, rtol=1e-12,
                      reason="the t = 0 sample shows the initial state")
        t.require(me["contact"], "no contact force at all")
        t.info(run, "dt [s], dt/dt_crit, steps", "%.4e, %.3f, %d" % (dt, me["dt_ratio"], me["steps"]))
        t.check_ge(run, "contact start t_first [s] >= t0 - dt", me["start"], ex["t0"] - dt * (1 + 1e-9),
                   reason="within one step of t0 = g0/v0")
        t.check_le(run, "contact start t_first [s] < t0", me["start"], ex["t0"] * (1 - 1e-12),
                   reason="the forward increment acts at the step before the bottom would penetrate")
        t.check(run, "contact over before t_end", me["ended"], "last force before the last step",
                "ended" if me["ended"] else "still in contact")
        t.info(run, "force-free steps inside the contact (chatter)", me["gaps_inside"])
        tol = 0.02 * ex["duration"] + 2 * dt
        t.check_close(run, "contact duration [s] = 2L/c", ex["duration"], me["duration"], atol=tol,
                      reason="2 %% plus two steps (%.3e s)" % tol)
        perr = me["pressure_mean"] / ex["pressure"] - 1
        t.info(run, "mean pressure / rho c v0 - 1", "%+.4f (plateau, middle 80 %%: %+.4f; rms oscillation %.4f)"
               % (perr, me["pressure_plateau"] / ex["pressure"] - 1, me["pressure_osc_rms"]))
        if level == LEVELS[-1]:
            t.check_close(run, "mean pressure over the contact [MPa] = rho c v0", ex["pressure"],
                          me["pressure_mean"], rtol=0.02,
                          reason="2 %; the mean is impulse/duration, both biased O(h) (lost kinetic "
                                 "energy, up to two extra steps): 2.4 % low at level 2, 1.9 % at 3, 1.0 % at 4")
        verr = abs(me["rebound_velocity"] / ex["v0"] - 1)
        t.info(run, "rebound velocity / v0", "%.5f (normal contact work / E0 %.5f)" % (
            me["rebound_velocity"] / ex["v0"], me["normal_work"]))
        if level == SHIPPED:
            # the rebound loses the normal contact work (each node stopped perfectly inelastically,
            # an O(h) energy loss) and the vibration energy left in the bar: measured 2.44 % low at
            # level 2, 1.47 % at 3, 0.90 % at 4 (order 0.7); 3 % is the level-2 value with a margin
            # of 1.23
            t.check_close(run, "rebound velocity [mm/s] = +v0 (shipped level)", ex["v0"], me["rebound_velocity"],
                          rtol=0.03, reason="O(h) inelastic node stops; measured 2.44 % at the shipped level")
        t.check_ge(run, "normal contact work / E0 >= 0", me["normal_work"], 0.0,
                   reason="the forward increment only removes kinetic energy (perfectly inelastic node stops)")
        t.check_le(run, "penetration (max over steps) [mm]", me["penetration_max"], 1e-12 * ex["gap"],
                   reason="multipliers close the gap exactly (P1 per node, P0 per dual cell), to round-off")
        t.check_le(run, "energy balance error (max over steps)", me["balance_error_max"], 1e-10,
                   reason="the discrete balance with E_kin0 and W_normal closes to round-off")
        rebound_err.append(verr)
        work.append(me["normal_work"])
    where = "levels %s" % (LEVELS,)
    t.check(where, "rebound error |v_reb/v0 - 1| shrinks at every finer level",
            all(b < a for a, b in zip(rebound_err, rebound_err[1:])), "strictly decreasing",
            ", ".join("%.5f" % e for e in rebound_err))
    t.check(where, "normal contact work / E0 shrinks at every finer level",
            all(b < a for a, b in zip(work, work[1:])), "strictly decreasing",
            ", ".join("%.5f" % w for w in work))


def penalty(t):
    run = t.run(t.deck("impact_bar_penalty.nml"), "--set", "output:history_interval=1", name="penalty")
    t.expect_exit(run, 0)
    t.expect_output(run)
    with Run(run.h5) as r:
        ex = exact(r)
        me = measure(r, ex)
        kp = float(r.deck["contact"]["penalty_stiffness"])
    t.require(me["contact"], "no contact force at all")
    t.check_close(run, "max penetration [mm] = rho c v0 / k_p", ex["pressure"] / kp, me["penetration_max"],
                  rtol=0.05, reason="spring bed in series with the bar, k_p d = rho c (v0 - d'): first order, no "
                                    "overshoot; 5 % as for the static penalty test")
    t.check_le(run, "energy balance error (max over steps)", me["balance_error_max"], 1e-10,
               reason="the balance closes for the penalty too (its work is the normal contact work)")
    t.info(run, "duration / (2L/c), rebound / v0, W_normal / E0", "%.4f, %.4f, %.5f" % (
        me["duration"] / ex["duration"], me["rebound_velocity"] / ex["v0"], me["normal_work"]))


def body(t):
    if t.args.multiplier == "penalty":
        penalty(t)
    else:
        lagrange(t, t.args.multiplier.lower())


if __name__ == "__main__":
    c2dtest.Test("impact on the rigid plane against the exact 1D wave solution",
                 extra_args=[(("--multiplier",), {"choices": ["P1", "P0", "penalty"], "required": True})]).main(body)
