#!/usr/bin/python3
"""Tests of contact2d.cattaneo_mindlin: algebraic facts of the Hertz and Cattaneo-Mindlin forms.

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_cattaneo_mindlin.py [-v]
"""
import math
import sys
import unittest

import numpy as np

sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/contact2d/
from contact2d import cattaneo_mindlin as cm  # noqa: E402


def integrate(f, lo, hi, n=200001):
    """Integral of f over [lo, hi] after x = (lo+hi)/2 + (hi-lo)/2 sin(theta) (smooth at the ends)."""
    th = np.linspace(-math.pi / 2, math.pi / 2, n)
    x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * np.sin(th)
    y = f(x) * 0.5 * (hi - lo) * np.cos(th)
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(th)))


class TestCattaneoMindlin(unittest.TestCase):
    P, R, E, NU, MU = 50.0, 10.0, 7.0e4, 0.3, 0.3

    def test_hertz_pressure_carries_P(self):
        a, p0 = cm.hertz(self.P, self.R, self.E, self.NU)
        self.assertAlmostEqual(self.P, integrate(lambda x: cm.pressure(x, a, p0), -a, a), delta=1e-8 * self.P)

    def test_shear_carries_Q_and_bounds(self):
        a, p0 = cm.hertz(self.P, self.R, self.E, self.NU)
        for ratio in (0.1, 0.5, 0.9):
            Q = ratio * self.MU * self.P
            c = cm.stick_half_width(a, Q, self.MU, self.P)
            # in three pieces: the integrand has square-root ends at +-a and a kink at +-c
            f = lambda x: cm.shear(x, a, c, self.MU, p0)  # noqa: E731
            total = integrate(f, -a, -c) + integrate(f, -c, c) + integrate(f, c, a)
            self.assertAlmostEqual(Q, total, delta=1e-8 * Q)
            xs = np.linspace(-a, a, 2001)
            q, mup = cm.shear(xs, a, c, self.MU, p0), self.MU * cm.pressure(xs, a, p0)
            slip = np.abs(xs) >= c
            stick = np.abs(xs) < c
            np.testing.assert_allclose(q[slip], mup[slip], rtol=0, atol=1e-12 * self.MU * p0)
            self.assertTrue(np.all(q[stick] < mup[stick]))
            self.assertTrue(np.all(q >= -1e-12 * p0))

    def test_limits_of_the_stick_zone(self):
        a, _ = cm.hertz(self.P, self.R, self.E, self.NU)
        self.assertEqual(a, cm.stick_half_width(a, 0.0, self.MU, self.P))
        self.assertEqual(0.0, cm.stick_half_width(a, self.MU * self.P, self.MU, self.P))
        with self.assertRaises(ValueError):
            cm.stick_half_width(a, 1.01 * self.MU * self.P, self.MU, self.P)

    def test_dundurs_beta(self):
        self.assertAlmostEqual(0.4 / 1.4, cm.dundurs_beta_rigid(0.3), places=15)
        self.assertEqual(0.0, cm.dundurs_beta_rigid(0.5))


if __name__ == "__main__":
    unittest.main()
