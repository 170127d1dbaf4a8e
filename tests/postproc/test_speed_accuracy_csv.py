#!/usr/bin/python3
"""Consistency of the committed speed-accuracy table docs/figures/speed_accuracy.csv (made by
postproc/speed_accuracy.py, docs/performance.md "Speed against accuracy"); no runs.

    PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_speed_accuracy_csv.py [-v]

The header is the script's; the static route is the exact static solution on its own mesh
(error_same_mesh <= 1e-10); on every route the error against the fine reference decreases with the
mesh level (for the static route that is the discretisation error alone: its decrease is the
physics); every explicit route adds a solver error (error_same_mesh > 0).
"""
import csv
import sys
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/
from speed_accuracy import FIELDS  # noqa: E402

CSV = Path(__file__).resolve().parent.parent.parent / "docs" / "figures" / "speed_accuracy.csv"


class TestSpeedAccuracyCsv(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(CSV, newline="") as fh:
            cls.header = next(csv.reader(fh))
        with open(CSV, newline="") as fh:
            cls.rows = list(csv.DictReader(fh))

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
        static = [r for r in self.rows if r["route"] == "static"]
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
        explicit = [r for r in self.rows if r["route"].startswith("explicit")]
        self.assertTrue(explicit)
        for r in explicit:
            self.assertGreater(float(r["error_same_mesh"]), 0.0, r)


if __name__ == "__main__":
    unittest.main()
