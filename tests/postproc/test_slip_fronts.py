#!/usr/bin/python3
"""Tests of contact2d.slip_fronts: the elastic wave speeds and the slip-front detector (no runs).

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_slip_fronts.py [-v]

Facts:
- Rayleigh's equation R(xi) = (2 - xi^2)^2 - 4 sqrt(1 - xi^2) sqrt(1 - kappa xi^2), kappa =
  (c_s/c_p)^2 = (1 - 2 nu)/(2 (1 - nu)) in plane strain: the returned root makes R vanish to
  round-off and R changes sign across it; squared and divided by xi^2 the equation is the cubic
  eta^3 - 8 eta^2 + (24 - 16 kappa) eta - 16 (1 - kappa) = 0 in eta = xi^2, whose root in (0, 1)
  (numpy.roots, an independent route) is xi^2; at nu = 1/4 the cubic factors, (eta - 4)(eta^2 - 4
  eta + 8/3), and xi = sqrt(2 - 2/sqrt(3)) = 0.91940 exactly; c_R/c_s grows with nu; c_p/c_s =
  sqrt(2 (1 - nu)/(1 - 2 nu)); a nu outside (-1, 0.5) is refused.
- On a synthetic space-time slip field with a front that reaches node i at sample k0 + m i (speed
  c = h/(m dt) exactly): the stick-to-slip events are those samples, fronts() links them into one
  front of speed c (to round-off), a front running towards -x has speed -c, two fronts apart in
  time are two; primary_front's onsets (a slip distance of j samples of sliding) are the arrival
  shifted by j - 1 samples, their fit gives c; a front that changes speed half way gives each
  half's speed in window_speeds.
"""
import math
import unittest

import numpy as np

from contact2d.slip_fronts import (fronts, onsets, plane_strain_kappa, primary_front, rayleigh_ratio,
                                   rayleigh_residual, wave_speeds, window_speeds)

NUS = (-0.5, 0.0, 0.1, 0.2, 0.25, 0.3, 1.0 / 3.0, 0.4, 0.45, 0.49)


class Rayleigh(unittest.TestCase):
    def test_root_solves_the_equation(self):
        for nu in NUS:
            xi = rayleigh_ratio(nu)
            self.assertTrue(0.0 < xi < 1.0, nu)
            self.assertLess(abs(rayleigh_residual(xi, nu)), 1e-13, nu)
            self.assertLess(rayleigh_residual(xi - 1e-9, nu), 0.0, nu)
            self.assertGreater(rayleigh_residual(xi + 1e-9, nu), 0.0, nu)

    def test_root_is_the_cubic_root(self):
        for nu in NUS:
            k = plane_strain_kappa(nu)
            roots = np.roots([1.0, -8.0, 24.0 - 16.0 * k, -16.0 * (1.0 - k)])
            real = [r.real for r in roots if abs(r.imag) < 1e-12 and 0.0 < r.real < 1.0]
            self.assertEqual(len(real), 1, nu)
            self.assertAlmostEqual(rayleigh_ratio(nu) ** 2, real[0], delta=1e-13, msg=nu)

    def test_poisson_solid_exact(self):
        self.assertAlmostEqual(rayleigh_ratio(0.25), math.sqrt(2.0 - 2.0 / math.sqrt(3.0)), delta=1e-14)
        self.assertEqual(round(rayleigh_ratio(0.25), 4), 0.9194)
        # the cubic's root at nu = 0.3 (kappa = 2/7): 0.92741, not 0.9325 (that is nu = 0.33 or so)
        self.assertEqual(round(rayleigh_ratio(0.3), 4), 0.9274)

    def test_grows_with_nu(self):
        xs = [rayleigh_ratio(nu) for nu in NUS]
        self.assertEqual(xs, sorted(xs))

    def test_wave_speeds(self):
        e, nu, rho = 7.0e4, 0.3, 2.7e-9
        c = wave_speeds(e, nu, rho)
        self.assertAlmostEqual(c["c_s"] ** 2 * rho / (e / 2.6), 1.0, delta=1e-14)
        self.assertAlmostEqual((c["c_p"] / c["c_s"]) ** 2, 2 * 0.7 / 0.4, delta=1e-13)
        self.assertAlmostEqual(c["c_R"] / c["c_s"], rayleigh_ratio(nu), delta=1e-15)

    def test_refuses_bad_nu(self):
        for nu in (0.5, -1.0, 0.7):
            with self.assertRaises(ValueError):
                rayleigh_ratio(nu)


def synthetic(n=20, m=3, k0=5, extra=20, backwards=False, v=1000.0, h=0.1, dt=1e-8):
    """Slip field: node i sticks (0) until sample k0 + m j (j = i, or n - 1 - i backwards), then
    slips at -v. Speed c = h / (m dt)."""
    x = h * np.arange(n)
    nk = k0 + m * n + extra
    t = dt * np.arange(nk)
    arrive = k0 + m * (np.arange(n)[::-1] if backwards else np.arange(n))
    s = np.where(np.arange(nk)[:, None] >= arrive[None, :], -v, 0.0)
    return t, x, s, arrive, h / (m * dt)


class Fronts(unittest.TestCase):
    def test_events_are_the_arrivals(self):
        t, x, s, arrive, c = synthetic()
        k, i = onsets(s)
        self.assertEqual(sorted(zip(i.tolist(), k.tolist())), list(enumerate(arrive.tolist())))

    def test_one_front_exact_speed(self):
        for back in (False, True):
            t, x, s, arrive, c = synthetic(backwards=back)
            fr = fronts(t, x, s, window=3.5 * (t[1] - t[0]))
            self.assertEqual(len(fr), 1)
            self.assertEqual(fr[0]["nodes"], len(x))
            self.assertAlmostEqual(fr[0]["speed"] / ((-c) if back else c), 1.0, delta=1e-12)

    def test_window_shorter_than_the_lag_splits(self):
        t, x, s, arrive, c = synthetic()
        # neighbours start 3 samples apart: a window of 2.5 samples links nothing
        self.assertEqual(fronts(t, x, s, window=2.5 * (t[1] - t[0])), [])

    def test_two_fronts(self):
        t, x, s, arrive, c = synthetic(extra=60)
        # the whole interface sticks again for 10 samples from sample 80, then a second front at c
        s2 = s.copy()
        again = 80 + 3 * np.arange(len(x))
        for i in range(len(x)):
            s2[80:again[i], i] = 0.0
        fr = fronts(t, x, s2, window=3.5 * (t[1] - t[0]))
        self.assertEqual(len(fr), 2)
        for f in fr:
            self.assertAlmostEqual(f["speed"] / c, 1.0, delta=1e-12)
        self.assertLess(fr[0]["t1"], fr[1]["t0"])

    def test_primary_front_distance(self):
        t, x, s, arrive, c = synthetic()
        dt, v = t[1] - t[0], 1000.0
        for j in (1, 4):
            pf = primary_front(t, x, s, distance=j * v * dt * (1 - 1e-12))
            self.assertEqual(pf["t_stick"], 0.0)
            np.testing.assert_allclose(pf["onset"], t[arrive + j - 1], rtol=0, atol=1e-20)
            (speed,) = window_speeds(x, pf["onset"], [x[0], x[-1]])
            self.assertAlmostEqual(speed / c, 1.0, delta=1e-12)

    def test_never_slipping_node_has_no_onset(self):
        t, x, s, arrive, c = synthetic()
        s[:, 7] = 0.0
        pf = primary_front(t, x, s, distance=1e-6)
        self.assertTrue(math.isnan(pf["onset"][7]))
        self.assertEqual(int(np.count_nonzero(np.isnan(pf["onset"]))), 1)

    def test_two_speeds_by_window(self):
        # arrival 3 samples per node on the left half, 1 per node on the right half: c and 3c
        n, dt, h, v = 21, 1e-8, 0.1, 1000.0
        x = h * np.arange(n)
        arrive = np.where(np.arange(n) <= 10, 5 + 3 * np.arange(n), 35 + (np.arange(n) - 10))
        t = dt * np.arange(80)
        s = np.where(np.arange(80)[:, None] >= arrive[None, :], -v, 0.0)
        pf = primary_front(t, x, s, distance=0.5 * v * dt)
        left, right = window_speeds(x, pf["onset"], [x[0], x[10], x[-1]])
        self.assertAlmostEqual(left / (h / (3 * dt)), 1.0, delta=1e-12)
        self.assertAlmostEqual(right / (h / dt), 1.0, delta=1e-12)


if __name__ == "__main__":
    unittest.main()
