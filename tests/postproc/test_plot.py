#!/usr/bin/python3
"""Tests of the reader API (contact2d.open_run) and of the plot command (contact2d.plot) on real runs.

    CONTACT2D=build/bin/contact2d PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_plot.py [-v]

The patch scene (inputs/patch_compression_p1.nml, level 0) is run once with the build's contact2d:
a block pressed flat on the obstacle, closed at every contact node (SPEC section 7). Facts: the
reader gives every dataset's unit as docs/output.md states it, histories of one length, the gap
g_i - u_i.n_i zero at every node of the closed patch (to the LCP's round-off, as
regression_patch_compression checks the penetration); the plot command writes the two PNGs, refuses
a second time (one line, exit 2, the PNGs byte for byte kept), replaces them with --force only, and
refuses a missing or non-HDF5 file in one line, writing nothing.
"""
import hashlib
import os
import subprocess
import sys
import tempfile
import unittest

from tmpcase import TempDirCase

sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/contact2d/
from contact2d import RunFileError, open_run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PLOT = os.path.join(ROOT, "postproc", "plot.py")
EXE = os.environ.get("CONTACT2D")
DELTA = 1.0e-3          # the patch deck's top displacement [mm]
PNG = b"\x89PNG\r\n\x1a\n"


def digest(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def contact2d(deck, h5, *sets):
    args = [EXE, os.path.join(ROOT, "inputs", deck), "-q", "-o", h5]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, capture_output=True, env=dict(os.environ, OMP_NUM_THREADS="1"))


@unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
class PlotRun(TempDirCase):
    @classmethod
    def setUpClass(cls):
        cls._runs = tempfile.TemporaryDirectory()
        cls.h5 = os.path.join(cls._runs.name, "patch.h5")
        contact2d("patch_compression_p1.nml", cls.h5, "mesh:level=0", "output:xdmf=.false.")

    @classmethod
    def tearDownClass(cls):
        cls._runs.cleanup()

    def plot(self, *args, module=False):
        cmd = [sys.executable, "-B"] + (["-m", "contact2d", "plot"] if module else [PLOT]) + list(args)
        return subprocess.run(cmd, capture_output=True, text=True, timeout=300)

    def one_line(self, proc, pattern):
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)
        self.assertRegex(proc.stderr, pattern)

    def test_reader_units_histories_gap(self):
        with open_run(self.h5) as run:
            self.assertEqual(run.status, "converged")
            self.assertEqual(run.attr("multiplier"), "P1")
            for path, unit in (("mesh/coordinates", "mm"), ("final/displacement", "mm"),
                               ("final/contact/pressure", "MPa"), ("final/contact/normal_force", "N/mm"),
                               ("contact/abscissa", "mm"), ("history/time", "s"),
                               ("history/kinetic_energy", "mJ"), ("history/normal_force_total", "N/mm")):
                self.assertEqual(run.units(path), unit, path)
            self.assertEqual(run.attr_units("dt"), "s")
            hist = run.histories()
            self.assertIn("residual", hist)
            self.assertEqual({len(v) for v in hist.values()}, {len(run.history("time"))})
            # the patch is closed everywhere (status 2 at every node: frictionless contact)
            self.assertTrue((run.contact("status") == 2).all())
            gap = run.contact_gap()
            self.assertEqual(gap.shape, run.abscissa.shape)
            self.assertLessEqual(abs(gap).max(), 1e-12 * DELTA, "complementarity: closed nodes have no gap")

    def test_open_run_refuses_in_one_line(self):
        with self.assertRaisesRegex(RunFileError, "no such file"):
            open_run(self.path("none.h5"))
        text = self.path("text.h5")
        with open(text, "w") as fh:
            fh.write("not HDF5\n")
        with self.assertRaisesRegex(RunFileError, "not a readable HDF5 file"):
            open_run(text)

    def test_writes_then_refuses_then_force(self):
        prefix = self.path("fig")
        p = self.plot(self.h5, "-o", prefix)
        self.assertEqual(p.returncode, 0, p.stderr)
        pngs = [prefix + "_contact.png", prefix + "_history.png"]
        self.assertEqual(p.stdout.split(), pngs)
        for png in pngs:
            with open(png, "rb") as fh:
                self.assertEqual(fh.read(8), PNG, png)
        kept = {png: digest(png) for png in pngs}
        # a second call: refused before drawing, both files byte for byte as they were
        for module in (False, True):
            self.one_line(self.plot(self.h5, "-o", prefix, module=module),
                          r"plot(\.py)?: refused: .*fig_contact\.png exists \(pass --force")
        self.assertEqual({png: digest(png) for png in pngs}, kept)
        self.assertEqual(sorted(os.listdir(self.dir)), ["fig_contact.png", "fig_history.png"])
        # only the history figure there: still refused, nothing else written
        os.unlink(pngs[0])
        self.one_line(self.plot(self.h5, "-o", prefix), r"refused: .*fig_history\.png exists")
        self.assertEqual(os.listdir(self.dir), ["fig_history.png"])
        p = self.plot(self.h5, "-o", prefix, "--force", module=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["fig_contact.png", "fig_history.png"])

    def test_default_prefix_is_beside_the_run(self):
        h5 = self.path("run.h5")
        with open(self.h5, "rb") as src, open(h5, "wb") as dst:
            dst.write(src.read())
        before = digest(h5)
        p = self.plot(h5)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["run.h5", "run_contact.png", "run_history.png"])
        self.assertEqual(digest(h5), before)

    def test_bad_or_missing_file(self):
        self.one_line(self.plot(self.path("none.h5"), "-o", self.path("x")), r"^plot\.py: error: .*none\.h5: no such file$")
        text = self.path("text.h5")
        with open(text, "w") as fh:
            fh.write("the user's notes\n")
        self.one_line(self.plot(text, module=True), r"^contact2d plot: error: .*text\.h5: not a readable HDF5 file")
        self.one_line(self.plot(self.dir), r"is a directory")
        with open(text) as fh:
            self.assertEqual(fh.read(), "the user's notes\n")
        self.assertEqual(os.listdir(self.dir), ["text.h5"])

    def test_run_without_contact_has_histories_only(self):
        h5 = self.path("uni.h5")
        contact2d("uniaxial_compression.nml", h5, "output:xdmf=.false.")
        p = self.plot(h5)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["uni.h5", "uni_history.png"])


if __name__ == "__main__":
    unittest.main()
