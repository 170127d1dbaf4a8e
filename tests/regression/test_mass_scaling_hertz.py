#!/usr/bin/env python3
"""Mass scaling on the graded Hertz meshes and the general-path sweep's thread bits.

The Hertz decks (hertz_cylinder_p1, hertz_indenter_p1, level 0, frictionless) run twice: as
shipped and with solver:mass_scaling = 4 dt_critical (dt_critical the element bound of the
unscaled mesh). Frictionless contact of a linear elastic body is a convex minimisation with a
unique minimiser, independent of the masses: both runs must converge to the same end state.
Two states whose relative residual is below tol_residual differ by at most cond(K) tol_residual,
cond(K) = (omega_max / omega_1)^2 taken from the default run itself (omega_max from its power
iteration, omega_1 = half its final automatic damping). The scaled run must also take fewer than
half the steps: its step is 4 times longer, so the ramp (a fixed time) takes 4 times fewer, and
the relaxation (about (omega_max / omega_1) ln(1 / tol) / 2 steps) falls by 4 / sqrt(1 + added
mass / body mass) at least (the added mass lowers omega_1 by at most that factor) -- more than
2 for the added mass allowed here (<= 1 body mass, checked).

The general (Gmsh) path's sweep (src/kernels/contact2d_rows.f90) sums in fixed chunks: one and two
OpenMP threads must give the same bits, and so must a run whose thread count changes while it runs
(CONTACT2D_THREAD_SWITCHES: the team, then one thread, then the team ..., at the listed steps).
Checked on hertz_cylinder_p1 at level 1 (5721 nodes, above the 4096-node threshold of the parallel
loops), 1500 steps with a ramp of 2e-6 s (contact active). The switched run's summary must say that
its team had 2 threads: Gmsh sets OpenMP's thread count to 1 when it starts, and a run on a Gmsh
mesh that did not set its own count back compared one thread with one thread.
"""
import os
import re

import numpy as np

import c2dtest


def final(run):
    with run.open() as f:
        return {"u": f["final/displacement"][()], "v": f["final/velocity"][()],
                "fn": f["final/contact/normal_force"][()], "steps": int(f.attrs["steps"]),
                "converged": int(f.attrs["converged"]), "dt": float(f.attrs["dt"]),
                "dt_critical": float(f.attrs["dt_critical"]), "added_mass": float(f.attrs["added_mass"]),
                "body_mass": float(f.attrs["body_mass"]), "omega_max": float(f.attrs["omega_max_power"]),
                "alpha": float(f["history/damping_alpha"][-1]), "ekin": f["history/kinetic_energy"][()]}


def body(t):
    for scene in ("cylinder", "indenter"):
        deck = t.deck("hertz_%s_p1.nml" % scene)
        base = t.run(deck, name="%s_default" % scene)
        t.expect_exit(base, 0)
        ref = final(base)
        t.check_equal(base, "converged (%s default)" % scene, 1, ref["converged"])
        target = 4 * ref["dt_critical"]
        r = t.run(deck, "--set", "solver:mass_scaling=%r" % target, name="%s_mass" % scene)
        t.expect_exit(r, 0)
        got = final(r)
        t.check_equal(r, "converged (%s mass scaling)" % scene, 1, got["converged"])
        t.check(r, "mass added (%s)" % scene, got["added_mass"] > 0, "> 0", "%.3e" % got["added_mass"])
        ratio = got["added_mass"] / got["body_mass"]
        t.check_le(r, "added mass / body mass (%s)" % scene, ratio, 1.0,
                   reason="the step-count argument below assumes <= 1")
        t.check(r, "dt >= dt_factor x target (%s)" % scene, got["dt"] >= 0.9 * target * (1 - 1e-12),
                ">= %.4e" % (0.9 * target), "%.4e" % got["dt"])
        cond = (ref["omega_max"] / (ref["alpha"] / 2)) ** 2
        rtol = cond * 1e-8
        reason = "two states with relative residual < 1e-8 differ by <= cond(K) 1e-8, cond = %.3g" % cond
        du = np.abs(got["u"] - ref["u"]).max() / np.abs(ref["u"]).max()
        t.check(r, "max |u - u_default| / max |u_default| (%s)" % scene, du <= rtol, "<= %.3g" % rtol,
                "%.3e" % du, "%.3g" % rtol, reason)
        dfn = np.abs(got["fn"] - ref["fn"]).max() / np.abs(ref["fn"]).max()
        t.check(r, "max |F_n - F_n default| / max F_n (%s)" % scene, dfn <= rtol, "<= %.3g" % rtol,
                "%.3e" % dfn, "%.3g" % rtol, reason)
        t.check(r, "fewer than half the default's steps (%s)" % scene, 2 * got["steps"] < ref["steps"],
                "< %d" % (ref["steps"] // 2), str(got["steps"]),
                reason="4x the step: the ramp takes 4x fewer, the relaxation >= 4/sqrt(2)x fewer")

    # the general path's sweep: the same bits on one and two threads
    deck = t.deck("hertz_cylinder_p1.nml")
    args = ["--set", "mesh:level=1", "--set", "solver:max_steps=1500", "--set", "solver:t_end=1.0",
            "--set", "solver:t_ramp=2e-6"]   # a short ramp: contact is active within the 1500 steps
    runs = {}
    for n in ("1", "2"):
        env = dict(os.environ, OMP_NUM_THREADS=n)
        runs[n] = t.run(deck, *args, name="threads_%s" % n, env=env)
        t.expect_exit(runs[n], 0)
    # switches at chunk ends (check_interval = 10): the team, 1 from step 100, the team from 330, ...
    switches = "100,330,340,900,1210"
    runs["switched"] = t.run(deck, *args, name="threads_switched", quiet=False,
                             env=dict(os.environ, OMP_NUM_THREADS="2", CONTACT2D_THREAD_SWITCHES=switches))
    t.expect_exit(runs["switched"], 0)
    line = re.search(r"threads +forced: (\d+) on (\d+) steps, 1 on (\d+) \((\d+) switches", runs["switched"].stdout)
    team, on_team, on_one, count = (int(g) for g in line.groups()) if line else (0, 0, 0, 0)
    t.check(runs["switched"], "team of the switched run (Gmsh must not leave OpenMP on 1 thread)", team == 2,
            "2", str(team))
    # steps 1-100 and 331-340 and 901-1210 on the team: 100 + 10 + 310 = 420, the rest (1080) on one
    t.check(runs["switched"], "steps on the team and on one thread", (on_team, on_one, count) == (420, 1080, 5),
            "(420, 1080, 5)", str((on_team, on_one, count)))
    a = final(runs["1"])
    for n in ("2", "switched"):
        b = final(runs[n])
        for key in ("u", "v", "fn", "ekin"):
            same = np.array_equal(a[key], b[key])
            t.check(runs[n], "%s bitwise equal on 1 thread and %s (general path)" % (key, n), same, "identical",
                    "identical" if same else "max diff %.3e" % np.abs(a[key] - b[key]).max())
    # a schedule that is not increasing: one line, exit 1, nothing written
    bad = t.run(deck, *args, name="threads_bad_schedule",
                env=dict(os.environ, OMP_NUM_THREADS="2", CONTACT2D_THREAD_SWITCHES="100,50"))
    t.expect_exit(bad, 1, stop=False)
    t.check(bad, "one error line naming CONTACT2D_THREAD_SWITCHES", len(bad.stderr_lines()) >= 1 and
            "CONTACT2D_THREAD_SWITCHES" in bad.stderr_lines()[-1] and len(bad.error_lines()) == 1,
            "one line", repr(bad.error_lines()))
    t.check(bad, "nothing written", os.listdir(bad.cwd) == [], "[]", repr(os.listdir(bad.cwd)))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
