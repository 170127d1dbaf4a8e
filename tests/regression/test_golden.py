#!/usr/bin/env python3
"""Golden end states: the shipped decks end where the stored reference says (a refactoring guard).

A golden file is the one sanctioned test against the program's own earlier output: it says
nothing about physics (the other regression tests do), it guards a restructuring of the code
against any change of the result. tests/regression/golden/ holds, for each case of
golden_cases.CASES, the final displacement (golden.npz) and the steps, status, dt, final time
and total contact forces (golden.json), written by regenerate_golden.py with OMP_NUM_THREADS=1,
and the identity of the build that wrote them (`contact2d --version`: flags and SIMD lanes; with
-march=native also the instruction set gfortran picks on that CPU).

Same build identity (the same arithmetic in the same order): every case must match within 1e-12
of max |u| (the force totals within 1e-12 of the larger total), the same steps, status and dt;
the test says whether each is bitwise equal. The level-4 paper deck (10 241 nodes, above the
4096-node threshold where the kernels go parallel) runs with OMP_NUM_THREADS=2 and must give the
one-thread golden bits exactly: every parallel sum has a fixed order (regression_threads).

Another build (-DCONTACT2D_NATIVE=OFF, another CPU's -march=native: 4 instead of 8 SIMD lanes,
fused multiply-adds or not) does not do the same arithmetic. Measured on 2026-11-27 (AMD EPYC,
AVX-512, golden from -O3 -march=native, 8 lanes; compared with -O3, 4 lanes) max |u - u_golden| /
max |u_golden| = 9.2e-13 and 9.4e-13 (paper deck level 3, P1 and P0), 3.8e-12 (level 4),
8.6e-15 (Hertz), 2.1e-14 (impact), <= 1e-15 (patch, sliding, Lame); the same steps and statuses.
The Debug build (-O0, no vectorisation) against the same golden files: 1.17e-12 and 1.19e-12
(level 3), 4.8e-12 (level 4), 8.8e-15 (Hertz), 1.3e-14 (impact), <= 1.1e-15 (the others).
So the 1e-12 bound is not a property of the program across builds (level 4 exceeds it, level 3
is at its edge), and the test does not apply it there. Against another build it checks, stated
as such, the round-off bound of cross_build_bound (cond(K) gamma_18 for a converged run: 2.4e-10
at level 4, 14 to 250 times the measured differences; steps gamma_18 for the dynamic impact run),
the same status, and the 2-thread run against a 1-thread run of that build, bit for bit.
"""
import json

import numpy as np

import c2dtest
import golden_cases as gc

RTOL = 1e-12


def compare(t, run, u, s, u0, s0, same_build):
    """Check one case against its golden state; return the relative displacement difference."""
    if u.shape != u0.shape:
        t.check_equal(run, "final displacement shape", u0.shape, u.shape)
        return np.inf
    scale = float(np.max(np.abs(u0)))
    rel = float(np.max(np.abs(u - u0))) / scale
    bitwise = bool(np.array_equal(u, u0))
    t.info(run, "final displacement bitwise equal to the golden file",
           "yes" if bitwise else "no: max |u - u_golden| / max |u_golden| = %.3e" % rel)
    fscale = max(abs(s0["normal_force_total"]), abs(s0["tangential_force_total"]))
    if same_build:
        t.check_close(run, "final displacement (golden, same build)", u0, u, rtol=RTOL,
                      reason="same build: same arithmetic; 1e-12 of max |u| leaves room for a reordered sum only")
        t.check_equal(run, "steps", s0["steps"], s["steps"])
        t.check_equal(run, "status", s0["status"], s["status"])
        t.check_equal(run, "dt", s0["dt"], s["dt"], reason="set-up arithmetic (element bound) is unchanged")
        for k in ("normal_force_total", "tangential_force_total"):
            t.check_close(run, k + " (sum of /final/contact)", s0[k], s[k], rtol=RTOL, scale=fscale,
                          reason="same build; relative to the larger total force")
    else:
        check_other_build(t, run, u, s, u0, s0, scale, fscale)
    return rel


def cross_build_bound(run, s):
    """The looser bound for another build, relative to max |u|, and its reason.

    Both builds do the same steps with different rounding (each force evaluation K u rounds a sum
    of at most 18 terms per row, a relative error of at most gamma_18 = 18 u / (1 - 18 u), u = 2^-53:
    Higham, Accuracy and Stability of Numerical Algorithms, 2002, section 3.1).
    A run with a convergence test ends at the fixed point of the damped iteration, whose
    sensitivity to a relative perturbation of the forces is cond(K) = (omega_max / omega_1)^2,
    omega_max from the power iteration (the element bound when there is none) and omega_1 = half
    the final automatic damping (as test_mass_scaling_hertz): bound cond(K) gamma_18. A dynamic
    run has no fixed point, but its undamped central-difference march is stable (dt < dt_crit:
    the amplification matrix has eigenvalues of modulus 1), so rounding adds up at most linearly:
    bound steps x gamma_18. A stick/slip or contact decision flipped by rounding could exceed
    either bound; none did in the measurement of the docstring."""
    unit = np.finfo(float).eps / 2        # unit round-off of IEEE double (Higham's u)
    gamma = 18 * unit / (1 - 18 * unit)
    with run.open() as f:
        omega_max = float(f.attrs.get("omega_max_power", f.attrs["omega_max_element"]))
        alpha = float(f["history/damping_alpha"][-1])
        dynamic = int(f.attrs.get("dynamic", 0)) == 1 or int(f.attrs.get("convergence_test", 1)) == 0
    if dynamic or alpha <= 0:
        return s["steps"] * gamma, "other build: stable undamped march, rounding adds up linearly: " \
            "steps %d x gamma_18 %.2e" % (s["steps"], gamma)
    cond = (omega_max / (alpha / 2)) ** 2
    return cond * gamma, "other build: rounding of the forces x cond(K) = %.3g (omega_max %.4g, omega_1 = " \
        "alpha/2 = %.4g) x gamma_18 %.2e" % (cond, omega_max, alpha / 2, gamma)


def check_other_build(t, run, u, s, u0, s0, scale, fscale):
    """Against another build's golden file: the round-off bound of cross_build_bound, not 1e-12."""
    rtol, reason = cross_build_bound(run, s)
    t.check_close(run, "final displacement (golden, other build)", u0, u, rtol=rtol, reason=reason)
    t.check_equal(run, "status", s0["status"], s["status"])
    t.info(run, "steps (golden, this build)", "%d, %d" % (s0["steps"], s["steps"]))
    for k in ("normal_force_total", "tangential_force_total"):
        t.check_close(run, k + " (sum of /final/contact)", s0[k], s[k], rtol=rtol, scale=fscale,
                      reason=reason + "; relative to the larger total force")


def body(t):
    with open(gc.JSON) as fh:
        meta = json.load(fh)
    ref = np.load(gc.NPZ)
    here = gc.build_identity(t.exe)
    same_build = here == meta["build"]
    t.info("golden", "golden files written by", json.dumps(meta["build"]))
    t.info("golden", "this build", json.dumps(here))
    t.info("golden", "same build identity", "yes: 1e-12 bound" if same_build else
           "no: the looser cross-build bound (docstring)")
    t.check_equal("golden", "cases stored", sorted(c[0] for c in gc.CASES), sorted(meta["cases"]))
    worst = {}
    for name, deck, extra, threads in gc.CASES:
        print()
        print("## case %s (%d thread%s)" % (name, threads, "s" if threads > 1 else ""))
        s0 = meta["cases"][name]
        t.check_equal("golden", name + ": deck and arguments", [s0["deck"], s0["args"]], [deck, extra])
        run = t.run(t.deck(deck), *extra, name=name, env={"OMP_NUM_THREADS": str(threads)}, timeout=300)
        t.expect_exit(run, 0)
        u, s = gc.end_state(run.h5)
        worst[name] = compare(t, run, u, s, ref[name], s0, same_build)
        if threads > 1:
            if same_build:
                t.check(run, "%d threads: final displacement bitwise equal to the 1-thread golden" % threads,
                        np.array_equal(u, ref[name]), "bitwise equal", "bitwise equal"
                        if np.array_equal(u, ref[name]) else "differs", reason="fixed summation order")
            else:
                one = t.run(t.deck(deck), *extra, name=name + "_1thread", env={"OMP_NUM_THREADS": "1"},
                            timeout=300)
                t.expect_exit(one, 0)
                u1, _ = gc.end_state(one.h5)
                t.check(run, "%d threads: final displacement bitwise equal to 1 thread (this build)" % threads,
                        np.array_equal(u, u1), "bitwise equal", "bitwise equal"
                        if np.array_equal(u, u1) else "differs", reason="fixed summation order")
    print()
    t.info("golden", "max |u - u_golden| / max |u_golden| per case",
           ", ".join("%s %.3e" % kv for kv in worst.items()))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
