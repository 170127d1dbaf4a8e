#!/usr/bin/python3
"""Self-test of contact2d.getfem_reference (standard library unittest; needs python3-getfem).

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_getfem_reference.py [-v]

The inputs are synthetic contact2d-layout files (mesh, effective deck, contact boundary) written
here, so the test needs neither the contact2d binary nor a previous run. It checks the reference
against closed-form answers (SPEC section 7) and against itself (P1 nodal brick = basic brick),
and the -o rules (contact2d.outfile) of postproc/getfem_reference.py and getfem_coulomb.py.
"""
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

# postproc/: the command-line scripts getfem_reference.py and getfem_coulomb.py
POSTPROC = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "postproc")
SCRIPT = os.path.join(POSTPROC, "getfem_reference.py")

E, NU = 7.0e4, 0.3


def write_input(path, lx, ly, nx, ny, groups, contact=None):
    """A contact2d-layout input: structured mesh (node (i, j) id i + (nx+1) j + 1), the effective
    deck text, and Gamma_c = the bottom edge when `contact` (dict of &contact entries) is given."""
    xs, ys = np.linspace(0, lx, nx + 1), np.linspace(0, ly, ny + 1)
    X, Y = np.meshgrid(xs, ys)
    coords = np.stack([X.ravel(), Y.ravel()], 1)
    conn = []
    for j in range(ny):
        for i in range(nx):
            n0 = i + (nx + 1) * j + 1
            conn.append([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1])
    lines = ["&mesh", "   lx = %r" % lx, "   ly = %r" % ly, "   nx = %d" % nx, "   ny = %d" % ny, "   level = 0", "/",
             "&material", "   young = %r" % E, "   poisson = %r" % NU, "   density = 2.7e-9", "/"]
    for name, g in groups:
        lines.append("&" + name)
        for k, v in g.items():
            lines.append("   %s = %s" % (k, "'%s'" % v if isinstance(v, str) else ", ".join(repr(float(a)) for a in np.atleast_1d(v))))
        lines.append("/")
    if contact is not None:
        lines.append("&contact")
        for k, v in contact.items():
            lines.append("   %s = %s" % (k, "'%s'" % v if isinstance(v, str) else ", ".join(repr(float(a)) for a in np.atleast_1d(v))))
        lines.append("/")
    with h5py.File(path, "w") as f:
        f.attrs["program"] = "synthetic"
        f.attrs["effective_deck"] = "\n".join(lines) + "\n"
        f.attrs["multiplier"] = contact.get("multiplier", "P1") if contact else "none"
        f.attrs["nx"], f.attrs["ny"] = np.int32(nx), np.int32(ny)
        f.create_dataset("mesh/coordinates", data=coords)
        f.create_dataset("mesh/connectivity", data=np.array(conn, np.int32))
        if contact is not None:
            h = lx / nx
            w = np.full(nx + 1, h)
            w[[0, -1]] = h / 2
            f.create_dataset("contact/nodes", data=np.arange(1, nx + 2, dtype=np.int32))
            f.create_dataset("contact/abscissa", data=xs)
            f.create_dataset("contact/weight", data=w)
            f.create_dataset("contact/gap", data=np.zeros(nx + 1))


def run(inp, out, *extra, script=SCRIPT):
    return subprocess.run([sys.executable, script, inp, "-o", out, *extra], capture_output=True, text=True)


def read(path):
    with h5py.File(path, "r") as f:
        d = {k: f["final/" + k][()] for k in ("displacement", "stress")}
        if "final/contact" in f:
            d.update({k: f["final/contact/" + k][()] for k in f["final/contact"]})
        d["attrs"] = dict(f.attrs)
        d["x"] = f["mesh/coordinates"][()]
    return d


PATCH = [("dirichlet", {"edge": "top", "component": "y", "values": -1e-3}),
         ("dirichlet", {"edge": "top", "xmin": 0.5, "xmax": 0.5, "component": "x", "values": 0.0})]
PAPER = [("dirichlet", {"edge": "top", "xmin": 0.0, "xmax": 0.5, "component": "x", "values": 0.0}),
         ("dirichlet", {"edge": "top", "xmin": 0.0, "xmax": 0.5, "component": "y", "values": -2e-3}),
         ("dirichlet", {"edge": "right", "ymin": 0.1, "ymax": 0.3, "component": "x", "values": -2e-3})]


def contact(multiplier, friction="frictionless", threshold=0.0):
    return {"edge": "bottom", "obstacle_point": [0.0, 0.0], "obstacle_normal": [0.0, 1.0], "origin": [0.0, 0.0],
            "direction": "ccw", "multiplier": multiplier, "friction": friction, "threshold": threshold,
            "tresca_scope": "all", "method": "lagrange"}


class GetfemReference(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def solve(self, name, lx, ly, nx, ny, groups, cont, *extra):
        inp = os.path.join(self.dir, name + "_in.h5")
        out = os.path.join(self.dir, name + "_ref.h5")
        write_input(inp, lx, ly, nx, ny, groups, cont)
        p = run(inp, out, *extra)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        return read(out)

    def test_patch_uniform_pressure(self):
        """SPEC 7 patch test: p = E delta / (H (1 - nu^2)) at every node (P1) and dual cell (P0)."""
        p = E * 1e-3 / (0.5 * (1 - NU ** 2))
        for mult in ("P1", "P0"):
            for nx, ny in ((8, 4), (32, 16)):
                with self.subTest(multiplier=mult, nx=nx):
                    r = self.solve("patch_%s_%d" % (mult, nx), 1.0, 0.5, nx, ny, PATCH, contact(mult))
                    np.testing.assert_allclose(r["pressure"], p, rtol=1e-10, atol=0)
                    self.assertAlmostEqual(r["normal_force"].sum(), p * 1.0, delta=1e-10 * p)
                    x = r["x"]
                    exact = np.stack([NU * (1 + NU) * p / E * (x[:, 0] - 0.5), -1e-3 * x[:, 1] / 0.5], 1)
                    np.testing.assert_allclose(r["displacement"], exact, rtol=0, atol=1e-10 * 1e-3)
                    np.testing.assert_allclose(r["stress"][:, 1], -p, rtol=1e-10)
                    self.assertTrue(np.all(r["status"] == 2))
                    self.assertEqual(r["attrs"]["program"], "getfem_reference")
                    self.assertEqual(int(r["attrs"]["converged"]), 1)

    def test_p1_nodal_brick_equals_basic_brick(self):
        """The paper scene (k = 1): GetFEM's nodal rigid-obstacle brick and the basic brick with B_N = N."""
        a = self.solve("paper_nodal", 1.3, 0.3, 26, 6, PAPER, contact("P1"))
        b = self.solve("paper_basic", 1.3, 0.3, 26, 6, PAPER, contact("P1"), "--p1-brick", "basic")
        np.testing.assert_allclose(a["displacement"], b["displacement"], rtol=0, atol=1e-12 * 2e-3)
        np.testing.assert_allclose(a["normal_force"], b["normal_force"], rtol=0, atol=1e-10 * a["normal_force"].max())
        self.assertTrue(np.array_equal(a["status"], b["status"]))
        # the body lifts off the obstacle near x ~ 0.7 mm (SPEC 7)
        first = np.nonzero(a["status"] == 0)[0][0] / 26 * 1.3
        self.assertTrue(0.6 < first < 0.85, first)

    def test_p0_conditions(self):
        """P0: mu >= 0, (D d)_i <= 0, complementarity, and F_n = D^T mu."""
        r = self.solve("paper_p0", 1.3, 0.3, 26, 6, PAPER, contact("P0"))
        h = 1.3 / 26
        n = 27
        D = np.diag(np.full(n, 3 * h / 4)) + np.diag(np.full(n - 1, h / 8), 1) + np.diag(np.full(n - 1, h / 8), -1)
        D[0, 0] = D[-1, -1] = 3 * h / 8
        mu = r["pressure"]
        Dd = D @ (-r["displacement"][:n, 1])
        self.assertGreaterEqual(mu.min(), -1e-12 * mu.max())
        self.assertLessEqual(Dd.max(), 1e-14 * 2e-3 * h)
        self.assertLessEqual(np.abs(mu * Dd).max(), 1e-12 * mu.max() * 2e-3 * h)
        np.testing.assert_allclose(r["normal_force"], D @ mu, rtol=0, atol=1e-12 * r["normal_force"].max())

    def test_tresca_sliding_total_force(self):
        """SPEC 7 tresca_sliding (one shot): the block slides, total tangential force s L = 100 N."""
        groups = [("dirichlet", {"edge": "top", "component": "y", "values": -1e-3}),
                  ("dirichlet", {"edge": "top", "component": "x", "values": 5e-3})]
        for mult in ("P1", "P0"):
            with self.subTest(multiplier=mult):
                r = self.solve("sliding_" + mult, 1.0, 0.5, 16, 8, groups, contact(mult, "tresca", 100.0))
                w = np.full(17, 1 / 16)
                w[[0, -1]] /= 2
                np.testing.assert_allclose(r["tangential_force"], 100.0 * w, rtol=1e-12)
                self.assertAlmostEqual(r["tangential_force"].sum(), 100.0, delta=1e-10)
                self.assertTrue(np.all(r["status"][r["status"] != 0] == 2))
                self.assertGreater((r["status"] == 2).sum(), 10)

    def test_tresca_large_threshold_sticks(self):
        """A threshold far above the shear load: every contact node sticks (u_t = 0, status 1)."""
        r = self.solve("stick", 1.3, 0.3, 26, 6, PAPER, contact("P1", "tresca", 1e6))
        self.assertLessEqual(np.abs(r["displacement"][:27, 0]).max(), 1e-14 * 2e-3)
        st = r["status"]
        self.assertTrue(np.all(st[st != 0] == 1))
        self.assertGreater((st == 1).sum(), 10)

    def test_refuses_penalty(self):
        inp = os.path.join(self.dir, "penalty_in.h5")
        cont = contact("P1")
        cont["method"] = "penalty"
        cont["penalty_stiffness"] = 1e6
        write_input(inp, 1.0, 0.5, 8, 4, PATCH, cont)
        p = run(inp, os.path.join(self.dir, "penalty_ref.h5"))
        self.assertEqual(p.returncode, 2)
        self.assertIn("refused", p.stderr)
        self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)



class OutputRefusals(unittest.TestCase):
    """-o is checked before anything is read or solved (so these need no GetFEM)."""
    script = SCRIPT

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.inp = os.path.join(self.dir, "run.h5")
        self.write_input(self.inp)

    def tearDown(self):
        self.tmp.cleanup()

    def write_input(self, path):
        write_input(path, 1.0, 0.5, 4, 2, PATCH, contact("P1"))

    def run_script(self, inp, out, *extra):
        return run(inp, out, *extra, script=self.script)

    def refused(self, proc, pattern):
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)
        self.assertRegex(proc.stderr, pattern)

    def test_never_the_input(self):
        # the old code solved and then wrote the reference over the user's contact2d run
        for extra in ((), ("--force",)):
            self.refused(self.run_script(self.inp, self.inp, *extra), "is an input")
            self.refused(self.run_script(self.inp, os.path.join(self.dir, ".", "run.h5"), *extra), "is an input")
        with h5py.File(self.inp, "r") as f:
            self.assertEqual(f.attrs["program"], "synthetic")

    def test_existing_output_needs_force(self):
        out = os.path.join(self.dir, "ref.h5")
        with open(out, "w") as fh:
            fh.write("the user's file\n")
        self.refused(self.run_script(self.inp, out), "exists .*--force")
        with open(out) as fh:
            self.assertEqual(fh.read(), "the user's file\n")

    def test_missing_folder(self):
        self.refused(self.run_script(self.inp, os.path.join(self.dir, "no_such_dir", "ref.h5")), "does not exist")


class CoulombOutputRefusals(OutputRefusals):
    """The same -o rules for getfem_coulomb.py (the old code wrote over the input or an existing file,
    in place: h5py mode 'w', then 'r+'), on an input it solves (a Coulomb patch)."""
    script = os.path.join(POSTPROC, "getfem_coulomb.py")

    def write_input(self, path):
        write_input(path, 1.0, 0.5, 4, 2, PATCH, dict(contact("P1", "coulomb"), friction_coefficient=0.3))
        with h5py.File(path, "r+") as f:
            f.attrs["program"] = "synthetic"
            f.create_dataset("final/reaction", data=np.zeros((15, 2)))
            f.create_dataset("contact/normal", data=np.tile([0.0, -1.0], (5, 1)))

    def test_force_replaces(self):
        out = os.path.join(self.dir, "ref.h5")
        with open(out, "w") as fh:
            fh.write("the user's file\n")
        p = self.run_script(self.inp, out, "--force", "--increments", "2")
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with h5py.File(out, "r") as f:
            self.assertEqual(f.attrs["program"], "getfem_coulomb")
            self.assertEqual(int(f.attrs["increments"]), 2)
        self.assertEqual(sorted(os.listdir(self.dir)), ["ref.h5", "run.h5"])   # no temporary file left


if __name__ == "__main__":
    unittest.main()
