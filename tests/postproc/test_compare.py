#!/usr/bin/python3
"""Tests of contact2d.compare and postproc/compare.py (SPEC section 9 measures) on synthetic output files.

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_compare.py [-v]

Each test writes small HDF5 files in the layout of SPEC section 8 (the subset compare.py reads)
into a temporary directory, with fields whose errors are known in closed form.
If the environment variable CONTACT2D names a contact2d executable, one more test runs the
patch scene at two levels and checks the self-comparison and the nesting logic on real output.
"""
import json
import math
import os
import subprocess
import sys
import unittest

from tmpcase import TempDirCase  # noqa: E402 (tests/postproc)

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
POSTPROC = os.path.join(ROOT, "postproc")   # the command-line script compare.py
sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/

from contact2d import compare as cmp  # noqa: E402
from contact2d import fem_q1  # noqa: E402

E, NU = 7.0e4, 0.3
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))


def write_run(path, lx, ly, nx, ny, u, multiplier="P1", pressure=None, shear=None,
              young=E, poisson=NU, contact_edge="bottom", x0=0.0, y0=0.0, with_contact=True,
              connectivity=None, converged=1):
    """A minimal contact2d-like output file. u: callable (x, y) -> (ux, uy), or (nnode, 2)."""
    xs = x0 + lx * np.arange(nx + 1) / nx
    ys = y0 + ly * np.arange(ny + 1) / ny
    gx, gy = np.meshgrid(xs, ys, indexing="xy")
    X = np.stack([gx.ravel(), gy.ravel()], axis=1)
    U = np.array(u(X[:, 0], X[:, 1])).T if callable(u) else np.asarray(u, float)
    conn = fem_q1.structured_connectivity(nx, ny) + 1 if connectivity is None else connectivity
    deck = ("&mesh\n   lx = %r\n   ly = %r\n   nx = %d\n   ny = %d\n   level = 0\n/\n"
            "&material\n   young = %r\n   poisson = %r\n   density = 2.7e-9\n/\n"
            % (lx, ly, nx, ny, young, poisson))
    with h5py.File(path, "w") as f:
        f.attrs["nx"], f.attrs["ny"] = nx, ny
        f.attrs["multiplier"] = multiplier
        f.attrs["converged"] = converged
        f.create_dataset("mesh/coordinates", data=X)
        f.create_dataset("mesh/connectivity", data=np.asarray(conn, dtype=np.int32))
        f.create_dataset("final/displacement", data=U)
        if with_contact:
            if contact_edge == "bottom":
                nodes = np.arange(nx + 1)
            else:  # top edge, counter-clockwise: right to left
                nodes = (nx + 1) * ny + np.arange(nx, -1, -1)
            s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(X[nodes], axis=0), axis=1))])
            n = nodes.size
            p = np.zeros(n) if pressure is None else np.asarray(pressure, float)
            t = np.zeros(n) if shear is None else np.asarray(shear, float)
            f.create_dataset("contact/nodes", data=(nodes + 1).astype(np.int32))
            f.create_dataset("contact/abscissa", data=s)
            f.create_dataset("final/contact/pressure", data=p)
            f.create_dataset("final/contact/shear", data=t)
            f.create_dataset("final/contact/status", data=np.where(p > 0, 1, 0).astype(np.int32))
            f.create_dataset("final/contact/normal_force", data=p * (lx / nx))
            f.create_dataset("final/contact/tangential_force", data=t * (lx / nx))
            deck += "&contact\n   edge = '%s'\n   multiplier = '%s'\n/\n" % (contact_edge, multiplier)
        f.attrs["effective_deck"] = deck
    return path


def energy_density(G):
    """eps:C:eps for a constant displacement gradient G (2x2), plane strain."""
    eps = 0.5 * (G + G.T)
    return LAM * np.trace(eps) ** 2 + 2 * MU * np.sum(eps * eps)


class Base(TempDirCase):
    pass


class SelfAndProlongation(Base):
    def test_file_against_itself_is_zero(self):
        # e = u - u = 0 exactly, so every absolute error is 0.0 (not merely small).
        rng = np.random.default_rng(1)
        for mult in ("P1", "P0"):
            p = write_run(self.path("self_%s.h5" % mult), 1.3, 0.3, 13, 3, rng.normal(size=(56, 2)),
                          multiplier=mult, pressure=rng.random(14), shear=rng.normal(size=14))
            res = cmp.compare(p, p)
            self.assertEqual(res["refinement_ratio"], 1)
            self.assertEqual(res["reference"], "b")
            for k in cmp.ERROR_KEYS:
                self.assertEqual(res["absolute"][k], 0.0, k)
                self.assertEqual(res["errors"][k], 0.0, k)
            self.assertGreater(res["reference_norms"]["energy"], 0.0)

    def test_global_bilinear_field_is_prolonged_exactly(self):
        # a + b x + c y + d xy is Q1 on every rectangle grid, so P u_c equals the field at the fine
        # nodes and every error vanishes to round-off; ratios 2, 3 (not a power of 2) and 4.
        def u(x, y):
            return (1e-3 * (1 + 2 * x - 3 * y + 5 * x * y), 1e-3 * (-2 + x + 4 * y - 7 * x * y))

        pres = lambda s: 100 + 30 * s  # noqa: E731  linear: P1 interpolation is exact
        for r in (2, 3, 4):
            c = write_run(self.path("c.h5"), 2.0, 1.0, 4, 2, u, x0=0.3, y0=-0.2,
                          pressure=pres(np.linspace(0, 2, 5)), shear=-pres(np.linspace(0, 2, 5)))
            f = write_run(self.path("f%d.h5" % r), 2.0, 1.0, 4 * r, 2 * r, u, x0=0.3, y0=-0.2,
                          pressure=pres(np.linspace(0, 2, 4 * r + 1)),
                          shear=-pres(np.linspace(0, 2, 4 * r + 1)))
            res = cmp.compare(c, f)
            self.assertEqual(res["refinement_ratio"], r)
            self.assertEqual(res["reference"], "b")
            for k in cmp.ERROR_KEYS:
                self.assertLess(res["errors"][k], 1e-13, (r, k))

    def test_piecewise_bilinear_coarse_field_ratio_2(self):
        # A coarse Q1 field with random nodal values; its exact values on the ratio-2 mesh are the
        # coarse values at coarse nodes, edge averages at edge midpoints and 4-node averages at
        # element centres (bilinear interpolation at xi = 1/2), built here by hand.
        rng = np.random.default_rng(7)
        nx, ny = 5, 3
        uc = rng.normal(size=((ny + 1), (nx + 1), 2))
        uf = np.zeros((2 * ny + 1, 2 * nx + 1, 2))
        uf[::2, ::2] = uc
        uf[::2, 1::2] = 0.5 * (uc[:, :-1] + uc[:, 1:])
        uf[1::2, ::2] = 0.5 * (uc[:-1, :] + uc[1:, :])
        uf[1::2, 1::2] = 0.25 * (uc[:-1, :-1] + uc[:-1, 1:] + uc[1:, :-1] + uc[1:, 1:])
        c = write_run(self.path("c.h5"), 1.0, 0.6, nx, ny, uc.reshape(-1, 2))
        f = write_run(self.path("f.h5"), 1.0, 0.6, 2 * nx, 2 * ny, uf.reshape(-1, 2))
        res = cmp.compare(f, c)  # order does not matter: the finer file is the reference
        self.assertEqual(res["reference"], "a")
        for k in ("energy", "h1", "l2", "max"):
            self.assertLess(res["errors"][k], 1e-14, k)


class KnownErrors(Base):
    lx, ly = 1.3, 0.3

    def pair(self, uc, uf, nc=(13, 3), r=4):
        c = write_run(self.path("c.h5"), self.lx, self.ly, nc[0], nc[1], uc)
        f = write_run(self.path("f.h5"), self.lx, self.ly, r * nc[0], r * nc[1], uf)
        return cmp.compare(c, f)

    def test_rigid_body_difference(self):
        # e = t + w (-y, x): eps(e) = 0 so ||e||_a = 0; grad e = [[0, -w], [w, 0]] so
        # |e|_1^2 = 2 w^2 A; ||e||_0^2 = int (tx - w y)^2 + (ty + w x)^2 over [0,lx] x [0,ly].
        lx, ly = self.lx, self.ly
        G = np.array([[1e-3, 2e-4], [-5e-4, -2e-3]])      # uniform strain part of both fields
        tx, ty, w = 3e-4, -1e-4, 2e-3

        def base(x, y):
            return (G[0, 0] * x + G[0, 1] * y, G[1, 0] * x + G[1, 1] * y)

        def moved(x, y):
            bx, by = base(x, y)
            return (bx + tx - w * y, by + ty + w * x)

        res = self.pair(base, moved)
        A = lx * ly
        ref_energy = math.sqrt(A * energy_density(G))
        self.assertAlmostEqual(res["reference_norms"]["energy"] / ref_energy, 1.0, places=12)
        self.assertLess(res["errors"]["energy"], 1e-12)
        self.assertAlmostEqual(res["absolute"]["h1"] / math.sqrt(2 * w * w * A), 1.0, places=12)

        def int_sq(a, b, L, M):  # int_0^L int_0^M (a + b t)^2 dt ds, t the second variable
            return L * (a * a * M + a * b * M * M + b * b * M ** 3 / 3)

        l2sq = int_sq(tx, -w, lx, ly) + int_sq(ty, w, ly, lx)
        self.assertAlmostEqual(res["absolute"]["l2"] / math.sqrt(l2sq), 1.0, places=12)
        corners = [(0, 0), (lx, 0), (lx, ly), (0, ly)]
        emax = max(math.hypot(tx - w * y, ty + w * x) for x, y in corners)
        self.assertAlmostEqual(res["absolute"]["max"] / emax, 1.0, places=12)

    def test_uniform_strain_difference(self):
        # u_c = G1 x, u_f = (G1 + G0) x: e = G0 x, so ||e||_a^2 = A eps0:C:eps0,
        # ||u_f||_a^2 = A eps(G1+G0):C:eps(G1+G0), |e|_1^2 = A |G0|_F^2.
        G1 = np.array([[-1e-3, 3e-4], [1e-4, -2e-3]])
        G0 = np.array([[2e-5, -1e-5], [4e-5, 3e-5]])
        res = self.pair(lambda x, y: G1 @ np.array([x, y]),
                        lambda x, y: (G1 + G0) @ np.array([x, y]), nc=(13, 3), r=2)
        A = self.lx * self.ly
        expect = math.sqrt(energy_density(G0) / energy_density(G1 + G0))
        self.assertAlmostEqual(res["errors"]["energy"] / expect, 1.0, places=12)
        self.assertAlmostEqual(res["absolute"]["energy"] / math.sqrt(A * energy_density(G0)), 1.0,
                               places=12)
        self.assertAlmostEqual(res["errors"]["h1"] / (np.linalg.norm(G0) / np.linalg.norm(G1 + G0)),
                               1.0, places=12)

    def test_energy_norm_is_the_assembled_stiffness(self):
        # sqrt(e^T K e) with K from explicit B-matrix element stiffnesses (fem_q1.element_stiffness,
        # a separate code path), on a uniform mesh and on a graded (non-uniform) tensor grid.
        rng = np.random.default_rng(3)
        for xs, ys in ((np.linspace(0, 1.3, 14), np.linspace(0, 0.3, 4)),
                       (np.array([0, .1, .15, .4, .5, .9]), np.array([0, .05, .3]))):
            nx, ny = xs.size - 1, ys.size - 1
            gx, gy = np.meshgrid(xs, ys, indexing="xy")
            X = np.stack([gx.ravel(), gy.ravel()], axis=1)
            conn = fem_q1.structured_connectivity(nx, ny)
            u = rng.normal(size=X.shape)
            geo = fem_q1.Q1Geometry(X, conn)
            a1 = geo.energy_norm_sq(u, E, NU)
            a2 = fem_q1.energy_from_element_matrices(X, conn, u, E, NU)
            self.assertAlmostEqual(a1 / a2, 1.0, places=12)
            self.assertEqual(geo.uniform, bool(np.allclose(np.diff(xs), np.diff(xs)[0]) and
                                               np.allclose(np.diff(ys), np.diff(ys)[0])))
        # K_e annihilates the three rigid modes and has exactly 5 positive eigenvalues.
        xy = np.array([[0, 0], [0.1, 0], [0.1, 0.05], [0, 0.05]])
        K = fem_q1.element_stiffness(xy, E, NU)
        rigid = np.array([[1, 0] * 4, [0, 1] * 4,
                          np.ravel([[-y, x] for x, y in xy])])
        self.assertLess(np.max(np.abs(K @ rigid.T)), 1e-9 * np.max(np.abs(K)))
        ev = np.linalg.eigvalsh(K)
        self.assertEqual(int(np.sum(ev > 1e-9 * ev[-1])), 5)

    def test_graded_nested_grid(self):
        # Nesting, not uniformity, is what the prolongation needs: on a graded coarse grid refined
        # by 2 (midpoints), a global bilinear field still gives zero error, and adding x-shear
        # e = (g y, 0) gives ||e||_a^2 = A mu g^2.
        xs_c, ys_c = np.array([0, .2, .3, .7, 1.0]), np.array([0, .1, .4])
        xs_f = np.sort(np.concatenate([xs_c, 0.5 * (xs_c[1:] + xs_c[:-1])]))
        ys_f = np.sort(np.concatenate([ys_c, 0.5 * (ys_c[1:] + ys_c[:-1])]))
        g = 1e-4

        def make(name, xs, ys, shear):
            gx, gy = np.meshgrid(xs, ys, indexing="xy")
            x, y = gx.ravel(), gy.ravel()
            U = np.stack([1e-3 * x * y + shear * y, -2e-3 * y + 1e-3 * x], axis=1)
            p = write_run(self.path(name), 1.0, 0.4, xs.size - 1, ys.size - 1, U)
            with h5py.File(p, "r+") as f:
                f["mesh/coordinates"][...] = np.stack([x, y], axis=1)
                s = xs - xs[0]
                del f["contact/abscissa"]
                f.create_dataset("contact/abscissa", data=s)
            return p

        c = make("c.h5", xs_c, ys_c, 0.0)
        res = cmp.compare(c, make("f0.h5", xs_f, ys_f, 0.0))
        self.assertLess(res["errors"]["energy"], 1e-13)
        res = cmp.compare(c, make("f1.h5", xs_f, ys_f, g))
        self.assertAlmostEqual(res["absolute"]["energy"] / math.sqrt(0.4 * MU * g * g), 1.0, places=12)


class ContactFields(Base):
    def test_p0_cells_on_nested_levels(self):
        # Gamma_c = [0, 2]. Coarse nodes 0, 1, 2: cells [0,.5], [.5,1.5], [1.5,2] with c0..c2.
        # Fine nodes 0, .5, ..., 2: cells [0,.25], [.25,.75], [.75,1.25], [1.25,1.75], [1.75,2]
        # with f0..f4. Common refinement and the constant difference on each piece:
        c = np.array([3.0, 5.0, 1.0])
        f = np.array([4.0, 2.0, 6.0, 7.0, 0.5])
        pieces = [(.25, f[0] - c[0]), (.25, f[1] - c[0]), (.25, f[1] - c[1]), (.5, f[2] - c[1]),
                  (.25, f[3] - c[1]), (.25, f[3] - c[2]), (.25, f[4] - c[2])]
        l2 = math.sqrt(sum(L * d * d for L, d in pieces))
        mx = max(abs(d) for _, d in pieces)
        ref_l2 = math.sqrt(.25 * f[0] ** 2 + .5 * (f[1] ** 2 + f[2] ** 2 + f[3] ** 2) + .25 * f[4] ** 2)
        a = write_run(self.path("c.h5"), 2.0, 1.0, 2, 1, lambda x, y: (0 * x, 0 * y),
                      multiplier="P0", pressure=c, shear=-2 * c)
        b = write_run(self.path("f.h5"), 2.0, 1.0, 4, 2, lambda x, y: (0 * x, 1e-3 * y),
                      multiplier="P0", pressure=f, shear=-2 * f)
        res = cmp.compare(a, b)
        self.assertAlmostEqual(res["absolute"]["pressure_l2"], l2, places=13)
        self.assertAlmostEqual(res["errors"]["pressure_l2"], l2 / ref_l2, places=13)
        self.assertAlmostEqual(res["absolute"]["pressure_max"], mx, places=13)
        self.assertAlmostEqual(res["errors"]["pressure_max"], mx / max(f), places=13)
        self.assertAlmostEqual(res["absolute"]["shear_l2"], 2 * l2, places=13)
        # the cells are not nested: sampling at fine cell centres would give a different number
        naive = math.sqrt(sum(w * (fv - cv) ** 2 for w, fv, cv in
                              zip([.25, .5, .5, .5, .25], f, [c[0], c[0], c[1], c[1], c[2]])))
        self.assertGreater(abs(naive - l2), 0.1)

    def test_p1_nested_levels(self):
        # Nodal values of s^2 at s = 0, 1, 2 (coarse) and 0, .5, ..., 2 (fine): the difference of
        # the two interpolants is two hats of height -1/4 of width 1, so int d^2 = 2 (1/4)^2 / 3.
        sc, sf = np.linspace(0, 2, 3), np.linspace(0, 2, 5)
        a = write_run(self.path("c.h5"), 2.0, 1.0, 2, 1, lambda x, y: (0 * x, 0 * y),
                      pressure=sc ** 2)
        b = write_run(self.path("f.h5"), 2.0, 1.0, 4, 2, lambda x, y: (0 * x, 1e-3 * y),
                      pressure=sf ** 2)
        res = cmp.compare(a, b)
        self.assertAlmostEqual(res["absolute"]["pressure_l2"], math.sqrt(1.0 / 24.0), places=14)
        self.assertAlmostEqual(res["absolute"]["pressure_max"], 0.25, places=14)
        # ||s^2 interpolant||^2 on the fine nodes: sum over edges h/3 (a^2 + ab + b^2)
        ref = sum(0.5 / 3 * (p * p + p * q + q * q) for p, q in zip(sf[:-1] ** 2, sf[1:] ** 2))
        self.assertAlmostEqual(res["reference_norms"]["pressure_l2"], math.sqrt(ref), places=14)

    def test_p1_against_p0_needs_the_flag(self):
        # Same mesh, P1 p(s) = s on nodes 0, 1, 2 against P0 constants c on [0,.5], [.5,1.5],
        # [1.5,2]: int_a^b (s - c)^2 ds = ((b - c)^3 - (a - c)^3) / 3 on each cell.
        c = np.array([0.5, 1.0, 1.25])
        a = write_run(self.path("p0.h5"), 2.0, 1.0, 2, 1, lambda x, y: (0 * x, 0 * y),
                      multiplier="P0", pressure=c)
        b = write_run(self.path("p1.h5"), 2.0, 1.0, 2, 1, lambda x, y: (0 * x, 0 * y),
                      multiplier="P1", pressure=np.array([0.0, 1.0, 2.0]))
        with self.assertRaisesRegex(cmp.CompareError, "multiplier kinds differ"):
            cmp.compare(a, b)
        res = cmp.compare(a, b, allow_mixed_multipliers=True)
        cells = [(0, .5, c[0]), (.5, 1.5, c[1]), (1.5, 2, c[2])]
        l2 = math.sqrt(sum(((hi - cv) ** 3 - (lo - cv) ** 3) / 3 for lo, hi, cv in cells))
        self.assertAlmostEqual(res["absolute"]["pressure_l2"], l2, places=14)
        self.assertAlmostEqual(res["absolute"]["pressure_max"], 0.75, places=14)  # at s = 2
        self.assertTrue(any("P0" in w and "P1" in w for w in res["warnings"]))


class Refusals(Base):
    def u(self, x, y):
        return (1e-3 * x, -1e-3 * y)

    def refused(self, a, b, pattern):
        with self.assertRaisesRegex(cmp.CompareError, pattern):
            cmp.compare(a, b)
        out = subprocess.run([sys.executable, "-B", os.path.join(POSTPROC, "compare.py"), a, b],
                             capture_output=True, text=True)
        self.assertEqual(out.returncode, 2)
        self.assertEqual(out.stdout, "")
        self.assertEqual(len(out.stderr.strip().splitlines()), 1, out.stderr)
        self.assertTrue(out.stderr.startswith("compare.py: refused: "), out.stderr)

    def test_refusals(self):
        base = write_run(self.path("base.h5"), 1.0, 0.5, 4, 2, self.u)
        cases = [
            (write_run(self.path("dom.h5"), 1.0, 0.6, 8, 4, self.u), "different domains"),
            (write_run(self.path("shift.h5"), 1.0, 0.5, 8, 4, self.u, x0=0.1), "different domains"),
            (write_run(self.path("ratio.h5"), 1.0, 0.5, 8, 2, self.u), "nx:ny ratios"),
            (write_run(self.path("nonint.h5"), 1.0, 0.5, 6, 3, self.u), "not an integer"),
            (write_run(self.path("mat.h5"), 1.0, 0.5, 8, 4, self.u, young=2.1e5), "material differs"),
            (write_run(self.path("nu.h5"), 1.0, 0.5, 8, 4, self.u, poisson=0.25), "material differs"),
            (write_run(self.path("p0.h5"), 1.0, 0.5, 8, 4, self.u, multiplier="P0"),
             "multiplier kinds differ"),
            (write_run(self.path("top.h5"), 1.0, 0.5, 8, 4, self.u, contact_edge="top"),
             "contact boundaries differ"),
            (write_run(self.path("noc.h5"), 1.0, 0.5, 8, 4, self.u, with_contact=False),
             "contact boundaries differ"),
            (self.path("missing.h5"), "no such file"),
        ]
        shuffled = fem_q1.structured_connectivity(8, 4)[:, [1, 2, 3, 0]] + 1
        cases.append((write_run(self.path("unstr.h5"), 1.0, 0.5, 8, 4, self.u,
                                connectivity=shuffled), "not the structured"))
        for other, pattern in cases:
            with self.subTest(other=os.path.basename(other)):
                self.refused(base, other, pattern)
                if os.path.exists(other):
                    self.refused(other, base, pattern)

    def test_non_nested_grid_lines(self):
        # Same domain, nx 4 -> 8, but the fine grid is graded: coarse lines are not fine lines.
        base = write_run(self.path("base.h5"), 1.0, 0.5, 4, 2, self.u)
        other = write_run(self.path("graded.h5"), 1.0, 0.5, 8, 4, self.u)
        with h5py.File(other, "r+") as f:
            X = f["mesh/coordinates"][()]
            X[:, 0] = X[:, 0] ** 1.5
            f["mesh/coordinates"][...] = X
        self.refused(base, other, "not nested")


class CommandLine(Base):
    def test_json_and_symmetry(self):
        G = np.array([[1e-3, 0], [0, -1e-3]])
        a = write_run(self.path("a.h5"), 1.0, 0.5, 4, 2, lambda x, y: G @ np.array([x, y]),
                      pressure=np.linspace(1, 2, 5))
        b = write_run(self.path("b.h5"), 1.0, 0.5, 8, 4, lambda x, y: 1.1 * G @ np.array([x, y]),
                      pressure=np.linspace(1, 3, 9))
        out = self.path("out.json")
        run = subprocess.run([sys.executable, "-B", os.path.join(POSTPROC, "compare.py"), a, b,
                              "--json", out], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("displacement energy norm", run.stdout)
        with open(out) as fh:
            res = json.load(fh, parse_constant=lambda c: self.fail("non-JSON constant " + c))
        self.assertEqual(res["reference"], "b")
        self.assertAlmostEqual(res["errors"]["energy"], 0.1 / 1.1, places=12)  # e = 0.1 G x
        swapped = cmp.compare(b, a)
        self.assertEqual(swapped["reference"], "a")
        for k in cmp.ERROR_KEYS:
            self.assertAlmostEqual(swapped["errors"][k], res["errors"][k], places=14)


    def cli(self, *args):
        return subprocess.run([sys.executable, "-B", os.path.join(POSTPROC, "compare.py")] + list(args),
                              capture_output=True, text=True)

    def one_line_refusal(self, run, pattern):
        self.assertEqual(run.returncode, 2, run.stderr)
        self.assertEqual(run.stdout, "")          # refused before comparing: no table
        self.assertEqual(len(run.stderr.strip().splitlines()), 1, run.stderr)
        self.assertRegex(run.stderr, pattern)

    def pair(self):
        a = write_run(self.path("a.h5"), 1.0, 0.5, 4, 2, lambda x, y: (1e-3 * x, -1e-3 * y))
        b = write_run(self.path("b.h5"), 1.0, 0.5, 8, 4, lambda x, y: (1.1e-3 * x, -1e-3 * y))
        return a, b

    def test_json_never_replaces_an_input(self):
        # the old code wrote the JSON over a.h5 (exit 0), with or without --force
        a, b = self.pair()
        for extra in ([], ["--force"]):
            for target in (a, b, os.path.join(self.dir, ".", "b.h5")):
                self.one_line_refusal(self.cli(a, b, "--json", target, *extra), "is an input")
        self.assertTrue(h5py.is_hdf5(a) and h5py.is_hdf5(b))

    def test_json_existing_file_needs_force(self):
        a, b = self.pair()
        out = self.path("out.json")
        with open(out, "w") as fh:
            fh.write("the user's notes\n")
        self.one_line_refusal(self.cli(a, b, "--json", out), "exists .*--force")
        with open(out) as fh:
            self.assertEqual(fh.read(), "the user's notes\n")
        run = self.cli(a, b, "--json", out, "--force")
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(out) as fh:
            self.assertEqual(json.load(fh)["reference"], "b")
        self.assertEqual(sorted(os.listdir(self.dir)), ["a.h5", "b.h5", "out.json"])  # no temporary left

    def test_json_missing_folder_is_refused_before_comparing(self):
        # the old code compared, printed the table, then died in open() with a traceback
        a, b = self.pair()
        run = self.cli(a, b, "--json", os.path.join(self.dir, "no_such_dir", "x.json"))
        self.one_line_refusal(run, "does not exist")
        self.assertNotIn("Traceback", run.stderr)

    def test_unfinished_run_is_named(self):
        # a crashed run's OUT.h5.<pid>.partial: status 'running', no /final
        a, b = self.pair()
        part = self.path("b.h5.1234.partial")
        with h5py.File(b, "r") as src, h5py.File(part, "w") as f:
            src.copy("mesh", f)
            for k, v in src.attrs.items():
                f.attrs[k] = v
            f.attrs["status"] = "running"
            f.attrs["converged"] = 0
        self.one_line_refusal(self.cli(a, part), r"did not finish \(status 'running'\)")
        with self.assertRaisesRegex(cmp.CompareError, "did not finish"):
            cmp.compare(a, part)


@unittest.skipUnless(os.environ.get("CONTACT2D"), "set CONTACT2D=path/to/contact2d to run")
class RealRuns(Base):
    def test_patch_scene_levels_0_and_1(self):
        exe = os.environ["CONTACT2D"]
        deck = os.path.join(ROOT, "inputs", "patch_compression_p0.nml")
        files = []
        for k in (0, 1):
            p = self.path("patch_k%d.h5" % k)
            subprocess.run([exe, deck, "-q", "-o", p, "--set", "mesh:level=%d" % k], check=True,
                           capture_output=True)
            files.append(p)
        res = cmp.compare(files[0], files[0])
        self.assertEqual(res["absolute"]["energy"], 0.0)
        res = cmp.compare(files[0], files[1])
        self.assertEqual(res["refinement_ratio"], 2)
        # the exact solution is linear, so both levels carry it (to the solver tolerance)
        self.assertLess(res["errors"]["energy"], 1e-5)
        self.assertLess(res["errors"]["pressure_l2"], 1e-5)


if __name__ == "__main__":
    unittest.main()
