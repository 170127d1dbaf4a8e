#!/usr/bin/python3
"""contact2d.calculix and the Hertz measures of the speed-accuracy chart (contact2d.hertz, .chart).

    CONTACT2D=build/bin/contact2d PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_calculix.py [-v]

Algebra on small fields (no runs): the L2 measure on Gamma_c is exact for a field of its own kind,
the P1 recovery inverts the P1 boundary mass. On a static run of inputs/hertz_cylinder_p1.nml
(level 0, the build's contact2d): K u computed element by element equals the run's contact forces
at Gamma_c (equilibrium, SPEC section 3: no other load acts there) and M_c^-1 of them its pressure;
the CalculiX input has the run's nodes and elements, the slave faces along Gamma_c and the stated
penalty; the Tresca paper scene is refused in one line naming Coulomb. Where ccx is installed
(Debian calculix-ccx; otherwise those tests are skipped with one line): the penalty law holds
(penetration = pressure / slope at the centre) and the distance to the static solution falls as
1/slope.
"""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/contact2d/
from contact2d import calculix, hertz  # noqa: E402
from contact2d.chart import hertz_errors  # noqa: E402
from contact2d.h5 import Run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.environ.get("CONTACT2D")


class Measures(unittest.TestCase):
    """The pressure measures on a polyline, against hand values."""

    def setUp(self):
        # a straight Gamma_c along x with uneven segments (lengths 0.5, 1, 1.5)
        self.xc = np.array([[0.0, 0.0], [0.5, 0.0], [1.5, 0.0], [3.0, 0.0]])

    def test_l2_of_a_linear_field_is_exact(self):
        p = 2.0 + 3.0 * self.xc[:, 0]
        err, ref = hertz.profile_l2(self.xc, p, "P1", lambda x: 2.0 + 3.0 * x)
        self.assertLess(err, 1e-12 * ref)
        # ||2 + 3x||^2 on [0, 3] = int (2 + 3x)^2 = ((2 + 9)^3 - 2^3) / 9 = 147
        # midpoint rule, 64 points per segment: error sum L_i (L_i/64)^2/24 f'' = 8.2e-4 of 147
        self.assertAlmostEqual(ref, np.sqrt(147.0), delta=1e-5 * np.sqrt(147.0))

    def test_l2_between_p0_fields(self):
        a = np.array([1.0, 2.0, 3.0, 4.0])
        b = a + np.array([1.0, 0.0, 0.0, 0.0])        # differs on node 0's dual cell [0, 0.25] only
        err, _ = hertz.profile_l2(self.xc, a, "P0", b)
        self.assertAlmostEqual(err, np.sqrt(0.25), delta=1e-12)

    def test_p1_pressure_inverts_the_boundary_mass(self):
        lam = np.array([1.0, -2.0, 0.5, 3.0])
        h = np.diff(self.xc[:, 0])
        fn = np.zeros(4)                              # F = M_c lambda, M_c = [2 1; 1 2] h/6 per segment
        for i in range(3):
            fn[i] += h[i] / 6 * (2 * lam[i] + lam[i + 1])
            fn[i + 1] += h[i] / 6 * (lam[i] + 2 * lam[i + 1])
        np.testing.assert_allclose(hertz.p1_pressure(self.xc, fn), lam, rtol=0, atol=1e-13)

    def test_hertz_errors_of_the_exact_profile(self):
        E, nu, R, P = 7e4, 0.3, 10.0, 1600.0
        a, p0 = hertz.hertz(P, R, E, nu)
        xc = np.column_stack([np.linspace(0, 2 * a, 2001), np.zeros(2001)])
        p = p0 * np.sqrt(np.clip(1 - (xc[:, 0] / a) ** 2, 0, None))
        err_ref, err_same = hertz_errors(xc, p, "P1", P, R, E, nu, p)
        self.assertEqual(err_same, 0.0)
        self.assertLess(err_ref, 5e-3)                # interpolation error of the square-root edge only


@unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
class OnARun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory()
        cls.dir = cls._tmp.name
        cls.static = os.path.join(cls.dir, "hertz_static.h5")
        cls.paper = os.path.join(cls.dir, "paper_static.h5")
        env = dict(os.environ, OMP_NUM_THREADS="1")
        for deck, h5 in (("hertz_cylinder_p1.nml", cls.static), ("baillet_sassi_2002_p1.nml", cls.paper)):
            subprocess.run([EXE, os.path.join(ROOT, "inputs", deck), "--static", "-q", "-o", h5, "--set",
                            "mesh:level=0", "--set", "output:xdmf=.false."], check=True, capture_output=True, env=env)
        with Run(cls.static) as r:
            cls.x, cls.conn, cls.cn = r.coordinates, r.connectivity - 1, r.contact_nodes
            cls.E, cls.nu, _ = r.material
            cls.u, cls.fn, cls.p = r.displacement, r.contact("normal_force"), r.contact("pressure")

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def test_internal_forces_are_the_contact_forces(self):
        f = calculix.internal_forces(self.x, self.conn, self.u, self.E, self.nu)
        np.testing.assert_allclose(f[self.cn, 1], self.fn, rtol=0, atol=1e-10 * np.max(self.fn))
        np.testing.assert_allclose(hertz.p1_pressure(self.x[self.cn], self.fn), self.p, rtol=0,
                                   atol=1e-12 * np.max(self.p))

    def test_input_is_the_runs_mesh(self):
        inp = os.path.join(self.dir, "model.inp")
        n = calculix.write_hertz_cylinder(self.static, inp, 2.5e8)
        self.assertEqual(n, len(self.x))
        with open(inp) as fh:
            text = fh.read()
        lines = text.splitlines()

        def block(keyword):
            rest = lines[lines.index(keyword) + 1:]
            return rest[:next(i for i, ln in enumerate(rest) if ln.startswith("*"))]

        nodes = block("*NODE, NSET=NBODY")
        self.assertLessEqual(max(len(w.strip()) for ln in nodes for w in ln.split(",")), 20)  # ccx reads 20
        np.testing.assert_allclose(np.array([[float(v) for v in ln.split(",")[1:]] for ln in nodes]), self.x,
                                   rtol=0, atol=1e-12 * np.max(np.abs(self.x)))
        body = block("*ELEMENT, TYPE=CPE4, ELSET=EBODY")
        np.testing.assert_array_equal(np.array([[int(v) for v in ln.split(",")[1:]] for ln in body]),
                                      self.conn + 1)
        slave = block("*SURFACE, NAME=SSLAVE, TYPE=ELEMENT")
        self.assertEqual(len(slave), len(self.cn) - 1)                # one face per segment of Gamma_c
        self.assertIn("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n250000000.0,", text)
        self.assertIn("*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE\nSSLAVE, SRIGID", text)
        self.assertNotIn("*FRICTION", text)

    def test_tresca_scene_refused(self):
        inp = os.path.join(self.dir, "paper.inp")
        with self.assertRaises(calculix.CalculixUnsupported) as ctx:
            calculix.write_hertz_cylinder(self.paper, inp, 1e8)
        msg = str(ctx.exception)
        self.assertNotIn("\n", msg)
        self.assertIn("Coulomb", msg)
        self.assertFalse(os.path.exists(inp))                           # nothing written

    @unittest.skipUnless(calculix.available(), "ccx not installed (Debian: calculix-ccx): CalculiX runs skipped")
    def test_penalty_solutions(self):
        dist, xc = {}, self.x[self.cn]
        for slope in (1e7, 1e8):
            folder = os.path.join(self.dir, "k%g" % slope)
            os.mkdir(folder)
            inp = os.path.join(folder, "h.inp")
            n = calculix.write_hertz_cylinder(self.static, inp, slope)
            calculix.solve(inp)
            u = calculix.read_displacement(os.path.join(folder, "h.dat"), n)
            fn = calculix.internal_forces(self.x, self.conn, u, self.E, self.nu)[self.cn, 1]
            p = hertz.p1_pressure(xc, fn)
            # penalty law at the centre (x = 0, the largest pressure): penetration = p / slope; 3 %:
            # CalculiX lumps the force on the node's area, M_c^-1 recovers a consistent P1 field
            penetration = -(xc[0, 1] + u[self.cn[0], 1])
            self.assertAlmostEqual(penetration * slope / p[0], 1.0, delta=0.03)
            _, dist[slope] = hertz_errors(xc, p, "P1", 2 * fn.sum(), 10.0, self.E, self.nu, self.p)
        ratio = dist[1e7] / dist[1e8]
        self.assertGreater(ratio, 8.0, dist)           # O(1/slope): 10, within 20 %
        self.assertLess(ratio, 12.0, dist)


if __name__ == "__main__":
    unittest.main()
