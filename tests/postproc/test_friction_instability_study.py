#!/usr/bin/python3
"""The stick-slip study's command (postproc/friction_instability_study.py) on the smallest case.

    CONTACT2D=build/bin/contact2d PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_friction_instability_study.py [-v]

Runs inputs/friction_instability_p1.nml at level 0 with dt factors 1 and 0.5 (the build's contact2d,
CONTACT2D; skipped without it). Contract: exit 0, the CSV has one row per level and dt factor with
the wave speeds of the deck's material (c_R/c_s the root of Rayleigh's equation, c_p/c_s =
sqrt(2 (1 - nu)/(1 - 2 nu))) and a detachment front found (its sweep across the interface takes a
positive time), the figure is a PNG; a second run without --force is refused in one line (exit 2),
both products byte for byte kept; a bad --dt-factors or --levels is one line, exit 2, nothing run.
"""
import csv
import hashlib
import math
import os
import subprocess
import sys
import unittest

from tmpcase import TempDirCase

from contact2d.slip_fronts import rayleigh_ratio

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STUDY = os.path.join(ROOT, "postproc", "friction_instability_study.py")
EXE = os.environ.get("CONTACT2D")
PNG = b"\x89PNG\r\n\x1a\n"


def digest(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


class Study(TempDirCase):
    def study(self, *args):
        return subprocess.run([sys.executable, "-B", STUDY] + list(args), capture_output=True, text=True,
                              timeout=600)

    def one_line(self, proc, pattern):
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)
        self.assertRegex(proc.stderr, pattern)

    def test_bad_options_one_line(self):
        for opt, val in (("--dt-factors", "1,x"), ("--dt-factors", "2"), ("--dt-factors", "0"), ("--levels", "2-1")):
            self.one_line(self.study(opt, val, "--out", self.path("o"), "--exe", EXE or "/bin/false"),
                          "refused: " + opt)
            self.assertFalse(os.path.exists(self.path("o", "friction_instability.csv")))

    @unittest.skipUnless(EXE, "needs CONTACT2D")
    def test_level0_writes_table_and_figure(self):
        out = self.path("o")
        p = self.study("--exe", EXE, "--levels", "0", "--dt-factors", "1,0.5", "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        csv_path, png = os.path.join(out, "friction_instability.csv"), os.path.join(out, "friction_instability.png")
        with open(csv_path) as fh:
            rows = list(csv.DictReader(fh))
        self.assertEqual([(int(r["level"]), float(r["dt_factor"])) for r in rows], [(0, 1.0), (0, 0.5)])
        nu = 0.3
        for r in rows:
            self.assertAlmostEqual(float(r["c_R_over_c_s"]), rayleigh_ratio(nu), delta=1e-12)
            self.assertAlmostEqual(float(r["c_p_over_c_s"]), math.sqrt(2 * (1 - nu) / (1 - 2 * nu)), delta=1e-12)
            self.assertEqual(int(r["ncontact"]), 33)          # 32 2^0 elements along the bottom
            self.assertGreater(float(r["sweep_us"]), 0.0)
        with open(png, "rb") as fh:
            self.assertEqual(fh.read(8), PNG)
        before = (digest(csv_path), digest(png))
        again = self.study("--exe", EXE, "--levels", "0", "--out", out)
        self.one_line(again, "exists")
        self.assertEqual((digest(csv_path), digest(png)), before)


if __name__ == "__main__":
    unittest.main()
