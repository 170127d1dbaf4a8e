"""Regression: bodies held by contact alone (docs/static.md "Bodies held by contact").

inputs/block_on_flat_<m>.nml: block [0, 1] x [0, 0.5] mm pressed by a uniform pressure p = 100 MPa
onto a rigid flat, frictionless, one pin u_x = 0 at the top-middle node and NO vertical support.
The patch test with the body held up by contact alone: a linear field, exact for Q1 and both
multiplier spaces, so every element's stress is (sxx, syy, sxy) = (0, -p, 0), the contact pressure
p everywhere and the total normal force p L (vertical equilibrium).
  1. --static at levels 1 and 2 (the static engine's proximal path): stress within 1e-10 p, KKT
     of (13) from the file (static_kkt.py) within 1e-12, total F_n = p L to 1e-12.
  2. explicit at tol_residual = 1e-12, levels 1 and 2: stress within 1e-8 p, total F_n = p L to
     1e-8.
inputs/block_on_flat_coulomb_<m>.nml: the same block with Coulomb friction mu = 0.3 and no
&dirichlet at all (friction stops the x translation).
  3. explicit with compare_static at levels 1 and 2: converged; the static solution within
     1e-9 (energy norm) of the explicit end state (both solve the same discrete problem; the
     load is proportional and the slip monotone at these levels); total F_n = p L to 1e-10 and
     total F_t = 0 to 1e-12 p L (odd about x = 0.5 by symmetry); --static: KKT within 1e-12,
     the Coulomb cone at every node, total F_n = p L and total F_t = 0 to 1e-12; 10 increments end
     where one does to 1e-12 of max |u| (proportional loading).
The frictionless block without its pin (bad_decks/block_no_pin.nml) is a mechanism:
  4. explicit: no load drives the x translation, so it runs with exactly one warning line naming
     it; the stress within 1e-8 p. (Its refusals by --static, compare_static and a driving
     tangential load are contract cases of test_bad_decks.py.)
"""
import os

import numpy as np

import c2dtest
import static_kkt  # tests/regression: the KKT residuals from the file alone

P, L = 100.0, 1.0
LEVELS = (1, 2)


def top_pressure(h5):
    """Consistent nodal forces of the pressure p on the top edge: -p (h_left + h_right)/2 along y."""
    x = h5["mesh/coordinates"][()]
    top = np.flatnonzero(np.abs(x[:, 1] - x[:, 1].max()) <= 1e-12)
    top = top[np.argsort(x[top, 0])]
    f = np.zeros_like(x)
    f[top, 1] = -P * c2dtest.nodal_weights(x[top, 0])
    return f


def stress_error(h5):
    s = h5["final/stress"][()]
    return float(np.abs(s - np.array([0.0, -P, 0.0])).max()) / P


def frictionless(t, mult):
    deck = t.deck("block_on_flat_%s.nml" % mult.lower())
    for level in LEVELS:
        print()
        st = t.run(deck, "--static", "--set", "mesh:level=%d" % level, name="static_level%d" % level)
        t.expect_exit(st, 0)
        t.check(st, "summary names the proximal passes", "proximal passes" in st.stdout, "proximal passes",
                "absent" if "proximal passes" not in st.stdout else "present")
        with st.open() as h5:
            t.check_equal(st, "converged", 1, int(h5.attrs["converged"]))
            t.check_le(st, "max |stress - (0, -p, 0)| / p", stress_error(h5), 1e-10)
            static_kkt.check(t, st, h5, 1e-12, fext=top_pressure(h5))
            fn = h5["final/contact/normal_force"][()]
            t.check_close(st, "total normal force = p L", P * L, float(fn.sum()), rtol=1e-12,
                          reason="a direct solve: round-off")
        ex = t.run(deck, "--set", "mesh:level=%d" % level, name="explicit_level%d" % level)
        t.expect_exit(ex, 0)
        t.check_equal(ex, "stderr lines", 0, len(ex.stderr_lines()))
        with ex.open() as h5:
            t.check_equal(ex, "converged", 1, int(h5.attrs["converged"]))
            t.check_le(ex, "max |stress - (0, -p, 0)| / p (tol_residual 1e-12)", stress_error(h5), 1e-8)
            fn = h5["final/contact/normal_force"][()]
            t.check_close(ex, "total normal force = p L", P * L, float(fn.sum()), rtol=1e-8,
                          reason="converged to tol_residual 1e-12")


def coulomb(t, mult):
    deck = t.deck("block_on_flat_coulomb_%s.nml" % mult.lower())
    for level in LEVELS:
        print()
        ex = t.run(deck, "--set", "mesh:level=%d" % level, "--set", "solver:compare_static=.true.",
                   name="coulomb_explicit_level%d" % level)
        t.expect_exit(ex, 0)
        t.check_equal(ex, "stderr lines", 0, len(ex.stderr_lines()))
        with ex.open() as h5:
            t.check_equal(ex, "converged", 1, int(h5.attrs["converged"]))
            t.check_equal(ex, "static_converged (compare_static)", 1, int(h5.attrs["static_converged"]))
            t.check_le(ex, "static_distance_energy", float(h5.attrs["static_distance_energy"]), 1e-9)
            fn = h5["final/contact/normal_force"][()]
            ft = h5["final/contact/tangential_force"][()]
            t.check_close(ex, "total normal force = p L", P * L, float(fn.sum()), rtol=1e-10,
                          reason="converged to tol_residual 1e-12")
            t.check_close(ex, "total tangential force = 0 (symmetry)", 0.0, float(ft.sum()), atol=1e-12 * P * L,
                          reason="odd about x = 0.5: round-off")
            t.check_ge(ex, "some tangential force (friction acts)", float(np.abs(ft).max()), 1e-3 * P * L / len(ft))
        st = t.run(deck, "--static", "--set", "mesh:level=%d" % level, name="coulomb_static_level%d" % level)
        t.expect_exit(st, 0)
        with st.open() as h5:
            t.check_equal(st, "converged", 1, int(h5.attrs["converged"]))
            static_kkt.check(t, st, h5, 1e-12, fext=top_pressure(h5))
            fn = h5["final/contact/normal_force"][()]
            ft = h5["final/contact/tangential_force"][()]
            t.check_le(st, "Coulomb cone max(|F_t| - mu F_n) / (mu max F_n)",
                       float(np.max(np.abs(ft) - 0.3 * fn)) / (0.3 * float(fn.max())), 1e-12)
            t.check_close(st, "total normal force = p L", P * L, float(fn.sum()), rtol=1e-12, reason="round-off")
            t.check_close(st, "total tangential force = 0 (symmetry)", 0.0, float(ft.sum()), atol=1e-12 * P * L,
                          reason="round-off")
            u1 = h5["final/displacement"][()]
        # proportional loading, monotone slip: ten increments end where one does (each increment
        # starts its proximal passes from the last one's state)
        ten = t.run(deck, "--static", "--set", "mesh:level=%d" % level, "--set", "solver:static_increments=10",
                    name="coulomb_static10_level%d" % level)
        t.expect_exit(ten, 0)
        with ten.open() as h5:
            t.check_equal(ten, "converged", 1, int(h5.attrs["converged"]))
            u10 = h5["final/displacement"][()]
        t.check_le(ten, "max |u(N=10) - u(N=1)| / max |u|", float(np.abs(u10 - u1).max() / np.abs(u1).max()), 1e-12)


def mechanism(t, mult):
    if mult != "P1":
        return
    print()
    path = os.path.join(t.here, "bad_decks", "block_no_pin.nml")
    ex = t.run(path, name="no_pin_explicit")
    t.expect_exit(ex, 0)
    lines = ex.stderr_lines()
    t.check_equal(ex, "stderr lines", 1, len(lines))
    first = lines[0] if lines else ""
    t.check(ex, "one warning naming the free x translation",
            first.startswith("contact2d: warning: body 'body' is free to translate along x"),
            "contact2d: warning: body 'body' is free to translate along x ...", first)
    with ex.open() as h5:
        t.check_equal(ex, "converged", 1, int(h5.attrs["converged"]))
        t.check_le(ex, "max |stress - (0, -p, 0)| / p (tol_residual 1e-12)", stress_error(h5), 1e-8)


def body(t):
    mult = t.args.multiplier
    frictionless(t, mult)
    coulomb(t, mult)
    mechanism(t, mult)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0],
                 [(("--multiplier",), dict(required=True, choices=["P1", "P0"]))]).main(body)
