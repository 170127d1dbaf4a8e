#!/usr/bin/python3
"""Consistency of the committed speed-accuracy table docs/figures/speed_accuracy.csv (made by
postproc/speed_accuracy.py, docs/performance.md "Speed against accuracy"); no runs.

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_speed_accuracy_csv.py [-v]

The header is the package's (contact2d.chart.FIELDS); the static routes (paper scene and Hertz) are
the exact static solution on their own mesh (error_same_mesh <= 1e-10); on every route the error
against the fine reference (Hertz: against the analytic pressure) decreases with the mesh level (for
the static route that is the discretisation error alone: its decrease is the physics); every
explicit route adds a solver error (error_same_mesh > 0). The Hertz panel is there (its static
route at two levels at least, its explicit routes P1 at the levels of the static one). CalculiX's
rows, when there are any, are penalty solutions: their distance to the static solution on the same
mesh falls as 1/slope (the penalised problem differs from the constrained one by O(1/slope)).
"""
import csv
import re
import sys
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/
from contact2d.chart import FIELDS, HERTZ  # noqa: E402

CSV = Path(__file__).resolve().parent.parent.parent / "docs" / "figures" / "speed_accuracy.csv"


class TestSpeedAccuracyCsv(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(CSV, newline="") as fh:
            cls.header = next(csv.reader(fh))
        with open(CSV, newline="") as fh:
            cls.rows = list(csv.DictReader(fh))

    def route(self, name):
        return [r for r in self.rows if r["route"] == name]

    def test_header(self):
        self.assertEqual(tuple(self.header), FIELDS)
        self.assertTrue(self.rows)

    def test_values(self):
        for r in self.rows:
            self.assertGreater(int(r["level"]), -1)
            self.assertGreater(int(r["elements"]), 0)
            self.assertGreater(float(r["wall_seconds"]), 0.0, r)
            self.assertGreaterEqual(float(r["error_reference"]), 0.0, r)

    def test_static_route_is_exact_on_its_mesh(self):
        for name in ("static", HERTZ + "static"):
            static = self.route(name)
            with self.subTest(route=name):
                self.assertTrue(static)
                for r in static:
                    self.assertLessEqual(float(r["error_same_mesh"]), 1e-10, r)

    def test_reference_error_decreases_with_level(self):
        for route in sorted({r["route"] for r in self.rows}):
            for m in sorted({r["multiplier"] for r in self.rows}):
                rs = sorted((r for r in self.rows if r["route"] == route and r["multiplier"] == m),
                            key=lambda r: int(r["level"]))
                with self.subTest(route=route, multiplier=m):
                    self.assertEqual(len({r["level"] for r in rs}), len(rs))     # one run per level
                    errs = [float(r["error_reference"]) for r in rs]
                    self.assertTrue(all(b < a for a, b in zip(errs, errs[1:])), errs)

    def test_explicit_routes_add_a_solver_error(self):
        explicit = [r for r in self.rows if r["route"].startswith(("explicit", HERTZ + "explicit"))]
        self.assertTrue(explicit)
        for r in explicit:
            self.assertGreater(float(r["error_same_mesh"]), 0.0, r)

    def test_hertz_panel(self):
        static = self.route(HERTZ + "static")
        levels = {int(r["level"]) for r in static}
        self.assertGreaterEqual(len(levels), 2)                 # a line: at least two levels
        self.assertEqual({r["multiplier"] for r in static}, {"P1"})
        elements = {int(r["level"]): int(r["elements"]) for r in static}
        for name in (HERTZ + "explicit", HERTZ + "explicit_tol1e-3", HERTZ + "explicit_mass2"):
            rs = self.route(name)
            with self.subTest(route=name):
                self.assertGreaterEqual(len(rs), 2)
                for r in rs:                                    # the same meshes as the static route
                    self.assertEqual(elements[int(r["level"])], int(r["elements"]), r)

    def test_calculix_error_falls_as_one_over_the_penalty(self):
        slopes = {}
        for r in self.rows:
            m = re.fullmatch(HERTZ + r"calculix_(\d+(?:\.\d+)?e\d+)", r["route"])
            if m:
                self.assertEqual(r["multiplier"], "penalty", r)
                slopes.setdefault(float(m.group(1)), {})[int(r["level"])] = float(r["error_same_mesh"])
        if len(slopes) < 2:
            self.skipTest("fewer than two CalculiX penalty slopes in the table (ccx was not installed)")
        ks = sorted(slopes)
        for lo, hi in zip(ks, ks[1:]):
            for level in sorted(set(slopes[lo]) & set(slopes[hi])):
                with self.subTest(slopes=(lo, hi), level=level):
                    ratio = slopes[lo][level] / slopes[hi][level]
                    # first order in 1/slope; +-30 %: the .dat's 7 digits and higher-order terms
                    self.assertGreater(ratio, 0.7 * hi / lo)
                    self.assertLess(ratio, 1.3 * hi / lo)


if __name__ == "__main__":
    unittest.main()
