#!/usr/bin/python3
"""Tests of the study scripts' command lines (postproc/hertz_study.py, paper_study.py, ...), of the
package's run wrapper (contact2d.runner) and of the products of every study script (contact2d.outfile).

    CONTACT2D=build/bin/contact2d PYTHONPATH=postproc /usr/bin/python3 tests/postproc/test_study_scripts.py [-v]

What a study writes and what it reuses: tracked docs only when asked, runs reused only when they
are finished runs of the same settings, tables and figures replaced only with --force, one line
(not a traceback) for a bad option. The tests
that run contact2d need CONTACT2D (set by ctest) and are skipped without it; the hertz_study ones
need Gmsh too. Scripts that write into the source tree are run from a copy of postproc/ in a
temporary tree, so the repository's docs are never touched.
"""
import hashlib
import re
import os
import re
import shutil
import subprocess
import sys
import unittest

from tmpcase import TempDirCase  # noqa: E402 (tests/postproc)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
POSTPROC = os.path.join(ROOT, "postproc")   # the study scripts
sys.dont_write_bytecode = True  # leave no __pycache__ in postproc/

EXE = os.environ.get("CONTACT2D")
DOCS = ("docs/geometry_study.md", "docs/figures/hertz_pressure.png", "docs/figures/hertz_convergence.png")


def digest(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


class Base(TempDirCase):
    def script(self, name, *args, root=ROOT):
        return subprocess.run([sys.executable, "-B", os.path.join(root, "postproc", name)] + list(args),
                              capture_output=True, text=True, timeout=900)

    def one_line(self, proc, pattern, status=2):
        self.assertEqual(proc.returncode, status, proc.stderr)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)
        self.assertRegex(proc.stderr, pattern)


class HertzStudy(Base):
    def test_help_describes_every_option(self):
        out = self.script("hertz_study.py", "--help").stdout
        for opt, text in (("--levels", "Hertz mesh levels"), ("--lame-levels", "Lame mesh levels"),
                          ("--out", "folder of the runs"), ("--exe", "contact2d executable"),
                          ("--reuse", "finished run"), ("--update-docs", "docs/geometry_study.md")):
            self.assertIn(opt, out)
            self.assertIn(text, " ".join(out.split()), opt)

    def test_bad_levels_are_one_line(self):
        for opt, val in (("--levels", "x"), ("--levels", "2-1"), ("--lame-levels", "1-")):
            self.one_line(self.script("hertz_study.py", opt, val, "--out", self.path("o")), "refused: " + opt)
        self.assertFalse(os.path.exists(self.path("o")))

    @unittest.skipUnless(EXE and shutil.which("gmsh"), "needs CONTACT2D and gmsh")
    def test_docs_written_only_with_update_docs(self):
        # a copy of the tree: postproc/ copied, inputs/ linked, the three tracked docs copied
        root = self.path("tree")
        shutil.copytree(POSTPROC, os.path.join(root, "postproc"),
                        ignore=shutil.ignore_patterns("__pycache__"))
        os.symlink(os.path.join(ROOT, "inputs"), os.path.join(root, "inputs"))
        for d in DOCS:
            os.makedirs(os.path.dirname(os.path.join(root, d)), exist_ok=True)
            shutil.copy(os.path.join(ROOT, d), os.path.join(root, d))
        before = {d: digest(os.path.join(root, d)) for d in DOCS}
        out = self.path("out")
        # the old code wrote the docs whatever --out was
        p = self.script("hertz_study.py", "--exe", EXE, "--levels", "0", "--lame-levels", "0-1", "--out", out,
                        root=root)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertEqual({d: digest(os.path.join(root, d)) for d in DOCS}, before)
        for name in ("geometry_study.md", "hertz_pressure.png", "hertz_convergence.png"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        # '0,1' (ValueError in the old code) and a single Lame level other than 0 (KeyError ('p1', 0))
        p = self.script("hertz_study.py", "--exe", EXE, "--levels", "0,1", "--lame-levels", "1-1", "--out", out,
                        "--reuse", "--update-docs", root=root)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        after = {d: digest(os.path.join(root, d)) for d in DOCS}
        for d in DOCS:
            self.assertNotEqual(after[d], before[d], d)
        with open(os.path.join(root, "docs", "geometry_study.md")) as fh:
            table = fh.read()
        self.assertIn("| hertz_indenter_p1 | 1 |", table)
        self.assertIn("| lame_cavity_p0 | 1 |", table)
        self.assertNotIn("| lame_cavity_p0 | 0 |", table)



@unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
class Reuse(Base):
    """contact2d.runner.run(reuse=True) and paper_study.py keep a file only when it is the run they
    would make."""

    def attrs(self, h5):
        import h5py
        from contact2d.h5 import parse_effective_deck
        with h5py.File(h5, "r") as f:
            a = dict(f.attrs)
        return a, parse_effective_deck(a["effective_deck"])

    def test_runner_reuses_only_the_same_finished_run(self):
        import h5py
        from contact2d import runner as c2drun
        deck = os.path.join(self.dir, "patch.nml")
        shutil.copy(os.path.join(ROOT, "inputs", "patch_compression_p1.nml"), deck)
        h5 = self.path("patch.h5")
        sets = {"mesh:level": 0, "solver:tol_residual": 1e-7, "output:xdmf": False}
        self.assertEqual(c2drun.run(EXE, deck, h5, sets).returncode, 0)
        res = c2drun.run(EXE, deck, h5, dict(sets, **{"output:xdmf": True}), reuse=True)
        self.assertTrue(res.reused)               # &output does not change the results
        # another tolerance: the old code kept the 1e-7 run
        res = c2drun.run(EXE, deck, h5, dict(sets, **{"solver:tol_residual": 1e-9}), reuse=True)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(self.attrs(h5)[1]["solver"]["tol_residual"], 1e-9)
        self.assertFalse(res.reused)
        sets["solver:tol_residual"] = 1e-9
        # an interrupted run (SIGINT): the old code kept it
        with h5py.File(h5, "r+") as f:
            f.attrs["status"] = "interrupted"
        res = c2drun.run(EXE, deck, h5, sets, reuse=True)
        self.assertEqual(self.attrs(h5)[0]["status"], "converged")
        self.assertFalse(res.reused)
        # a --static run of the same deck is not an explicit run
        self.assertEqual(c2drun.run(EXE, deck, h5, sets, static=True).returncode, 0)
        self.assertFalse(c2drun.run(EXE, deck, h5, sets, reuse=True).reused)
        self.assertEqual(self.attrs(h5)[0]["method"], "explicit")
        # the deck was edited since
        with open(deck, "a") as fh:
            fh.write("! edited\n")
        self.assertFalse(c2drun.run(EXE, deck, h5, sets, reuse=True).reused)
        self.assertTrue(c2drun.run(EXE, deck, h5, sets, reuse=True).reused)

    def test_paper_study_tol_and_static(self):
        out = self.path("paper")
        p = self.script("paper_study.py", "--exe", EXE, "--levels", "0-1", "--tol", "1e-4", "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        before = {name: digest(os.path.join(out, name)) for name in os.listdir(out)}
        # a second study into the same folder: refused before any run (the old code replaced the
        # tables and figures, and reran the runs, silently)
        self.one_line(self.script("paper_study.py", "--exe", EXE, "--levels", "0-1", "--out", out),
                      r"refused: .*convergence\.csv exists \(pass --force")
        self.assertEqual({name: digest(os.path.join(out, name)) for name in os.listdir(out)}, before)
        # the default --tol: the old code reused the 1e-4 runs silently
        p = self.script("paper_study.py", "--exe", EXE, "--levels", "0-1", "--out", out, "--force")
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertNotEqual(digest(os.path.join(out, "convergence.csv")), before["convergence.csv"])
        self.assertIn("rerunning", p.stdout)
        self.assertNotIn("reusing", p.stdout)
        for name in ("p1_k0.h5", "p1_k1.h5", "p0_k0.h5", "p0_k1.h5"):
            self.assertEqual(self.attrs(os.path.join(out, name))[1]["solver"]["tol_residual"], 1e-10, name)
        # a --static file under a run's name is rerun (the old code reused it: status 'converged')
        h5 = os.path.join(out, "p1_k0.h5")
        subprocess.run([EXE, os.path.join(ROOT, "inputs", "baillet_sassi_2002_p1.nml"), "--static", "-q",
                        "-o", h5, "--force", "--set", "mesh:level=0", "--set", "solver:tol_residual=1e-10"],
                       check=True, capture_output=True)
        self.assertEqual(self.attrs(h5)[0]["method"], "static")
        p = self.script("paper_study.py", "--exe", EXE, "--levels", "0-1", "--out", out, "--force")
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertIn("rerunning %s" % h5, p.stdout)
        self.assertIn("reusing %s" % os.path.join(out, "p0_k1.h5"), p.stdout)
        self.assertEqual(self.attrs(h5)[0]["method"], "explicit")

    def test_speed_accuracy_reuses_only_a_reference_of_the_same_problem(self):
        import h5py
        out = self.path("sa")
        args = ["--exe", EXE, "--levels", "0", "--reference-dir", self.path("none"), "--out", out, "--force",
                "--no-hertz"]
        p = self.script("speed_accuracy.py", *args)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        gf1, gf0 = (os.path.join(out, "getfem_%s_k0.h5" % m) for m in ("p1", "p0"))
        kept = digest(gf0)
        # the P0 reference under the P1 name: the old code reused any getfem_*.h5 that existed
        shutil.copy(gf0, gf1)
        p = self.script("speed_accuracy.py", *args, "--reuse")
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertIn("recomputing %s: made for another problem" % gf1, p.stdout)
        self.assertEqual(self.attrs(gf1)[0]["multiplier"], "P1")
        self.assertNotIn("recomputing %s" % gf0, p.stdout)
        self.assertEqual(digest(gf0), kept)      # a reference of the same problem is kept
        # a reference cut short, and one that did not converge
        with open(gf1, "r+b") as fh:
            fh.truncate(4096)
        with h5py.File(gf0, "r+") as f:
            f.attrs["status"] = "not converged"
        p = self.script("speed_accuracy.py", *args, "--reuse")
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertIn("recomputing %s: not a complete HDF5 reference file" % gf1, p.stdout)
        self.assertIn("recomputing %s: status 'not converged'" % gf0, p.stdout)
        self.assertEqual(self.attrs(gf0)[0]["status"], "converged")


    def test_coulomb_path_reuses_only_the_same_problem(self):
        # what coulomb_path_study.py does with --reuse, through the package it calls: a run kept by
        # contact2d.runner.run(reuse=True), a GetFEM Coulomb reference by runner.keep_reference
        import contextlib
        import io
        from contact2d import runner
        increments = 20
        deck = os.path.join(ROOT, "inputs", "coulomb_sliding_p1.nml")

        def staged(stroke):     # coulomb_path_study.path_sets("staged", stroke, f=1, level=0)
            return {"mesh:level": 0, "solver:tol_residual": 1e-11, "output:xdmf": False, "solver:t_end": 6e-5,
                    "dirichlet#1:times": [2e-6], "dirichlet#2:values": [0.0, stroke],
                    "dirichlet#2:times": [2e-6, 6e-6]}

        class cps:              # the study's two steps
            @staticmethod
            def contact2d(exe, mult, sets, h5, reuse):
                res = runner.run(exe, deck, h5, sets, threads=1, reuse=reuse)
                self.assertEqual(res.returncode, 0, res.stderr)

            @staticmethod
            def getfem(h5, ref, reuse):
                if runner.keep_reference(ref, h5, reuse, program="getfem_coulomb", friction="coulomb",
                                         increments=increments):
                    return 0
                return subprocess.run([sys.executable, os.path.join(POSTPROC, "getfem_coulomb.py"), h5, "-o", ref,
                                       "--force", "--increments", str(increments)], capture_output=True).returncode

        h5, ref = self.path("run.h5"), self.path("ref.h5")
        sliding, partial = staged(5.0e-3), staged(4.0e-4)
        cps.contact2d(EXE, "P1", sliding, h5, False)
        self.assertEqual(cps.getfem(h5, ref, False), 0)
        said = io.StringIO()
        with contextlib.redirect_stdout(said):
            # the partial-slip stroke under the sliding run's name: the old code kept the sliding run
            cps.contact2d(EXE, "P1", partial, h5, True)
            self.assertEqual(self.attrs(h5)[1]["dirichlet"][1]["values"], [0.0, 4e-4])
            kept = digest(h5)
            cps.contact2d(EXE, "P1", partial, h5, True)      # the same run: kept
            self.assertEqual(digest(h5), kept)
            # the sliding run's reference: the old code kept any converged file
            self.assertEqual(cps.getfem(h5, ref, True), 0)
            self.assertEqual(self.attrs(ref)[0]["effective_deck"], self.attrs(h5)[0]["effective_deck"])
            kept = digest(ref)
            self.assertEqual(cps.getfem(h5, ref, True), 0)   # the same problem: kept
            self.assertEqual(digest(ref), kept)
            # the same problem with other increments
            subprocess.run([sys.executable, os.path.join(POSTPROC, "getfem_coulomb.py"), h5, "-o", ref, "--force",
                            "--increments", "5"], check=True, capture_output=True)
            self.assertEqual(cps.getfem(h5, ref, True), 0)
            self.assertEqual(int(self.attrs(ref)[0]["increments"]), increments)
        said = said.getvalue()
        self.assertIn("rerunning %s: dirichlet#2:values" % h5, said)
        self.assertIn("recomputing %s: made for another problem" % ref, said)
        self.assertIn("recomputing %s: increments '5', not '20'" % ref, said)
        self.assertEqual(len(said.splitlines()), 3, said)


class PaperStudy(Base):
    def test_bad_levels(self):
        self.one_line(self.script("paper_study.py", "--levels", "0-x", "--out", self.path("o")), "refused: --levels")

    @unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
    def test_single_level(self):
        # the old code did the runs, then died in lsq_slope (TypeError)
        out = self.path("one")
        p = self.script("paper_study.py", "--exe", EXE, "--levels", "1", "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        self.assertIn("one level (1): no errors, rates", p.stdout)
        for name in ("convergence.csv", "fig1_vertical_displacement.png", "fig3_contact_stress.png", "p1_sign.csv"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        self.assertFalse(os.path.exists(os.path.join(out, "rates.csv")))



class OutFolder(Base):
    """Every study script makes its folders with contact2d.runner.out_dir: one line, not a traceback."""
    CASES = (("paper_study.py", [], "--out"), ("hertz_study.py", [], "--out"), ("impact_study.py", [], "--out"),
             ("impact_study.py", ["--out", "{dir}"], "--figures"), ("stability_study.py", ["penalty"], "--out"), ("coulomb_path_study.py", [], "--out"),
             ("speed_accuracy.py", [], "--out"), ("stability_sweep.py", [], "--out"), ("bench_speed.py", [], "--out"),
             ("bench_static.py", [], "--out"))

    def test_folder_that_is_a_file(self):
        # the old code: FileExistsError (or NotADirectoryError) traceback
        f = self.path("taken")
        with open(f, "w") as fh:
            fh.write("the user's file\n")
        for script, args, option in self.CASES:
            with self.subTest(script=script, option=option):
                p = self.script(script, "--exe", "/bin/false", option, f, *[a.format(dir=self.dir) for a in args])
                self.one_line(p, r"^%s: refused: %s .*taken exists and is not a folder" % (script, option))
        with open(f) as fh:
            self.assertEqual(fh.read(), "the user's file\n")

    def test_speed_accuracy_levels(self):
        # the old code parsed --levels itself: ValueError ('x') and IndexError ('2-1') tracebacks
        for levels in ("x", "2-1"):
            with self.subTest(levels=levels):
                p = self.script("speed_accuracy.py", "--exe", "/bin/false", "--levels", levels, "--out", self.path("o"))
                self.one_line(p, r"^speed_accuracy\.py: refused: --levels '%s'" % levels)
        self.assertFalse(os.path.exists(self.path("o")))

    def test_speed_accuracy_penalties(self):
        # CalculiX's penalty slopes: a slope must be a finite positive number (pressure = slope x
        # penetration); refused before any run, nothing written
        for penalties in ("x", "0", "1e8,-1e9", "inf", "1e8,1e9,1e10,1e11,1e12"):
            with self.subTest(penalties=penalties):
                p = self.script("speed_accuracy.py", "--exe", "/bin/false", "--penalties", penalties,
                                "--out", self.path("o"))
                self.one_line(p, r"^speed_accuracy\.py: refused: --penalties '%s'" % re.escape(penalties))
        self.assertFalse(os.path.exists(self.path("o")))


class BenchStaticThreads(Base):
    """bench_static.py --threads: the static runs on several OpenMP thread counts (the BLAS of the
    factorisation follows them, docs/static.md "Threads")."""

    def test_bad_thread_counts_refused(self):
        # the old script had no --threads: argparse's usage and error (two lines)
        for threads in ("x", "0", "1,", "-2"):
            with self.subTest(threads=threads):
                p = self.script("bench_static.py", "--exe", "/bin/false", "--threads=" + threads, "--out", self.path("o"))
                self.one_line(p, r"^bench_static\.py: refused: --threads '%s'" % re.escape(threads))
        self.assertFalse(os.path.exists(self.path("o")))

    @unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
    def test_two_thread_counts_same_solution(self):
        # one discrete problem, one factorisation: 2 threads change only the order of the BLAS's sums,
        # so the end state agrees with one thread's to round-off (or bitwise)
        p = self.script("bench_static.py", "--exe", EXE, "--levels", "1", "--repeats", "1", "--explicit-repeats", "0",
                        "--threads", "1,2", "--out", self.path("b"))
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        rows = [line.split() for line in p.stdout.splitlines() if line.split()[:2] in (["1", "1"], ["2", "1"])]
        self.assertEqual([r[0] for r in rows], ["1", "2"], p.stdout)
        self.assertEqual(rows[0][-1], "bitwise")
        self.assertTrue(rows[1][-1] == "bitwise" or float(rows[1][-1]) < 1e-11, rows[1])
        self.assertEqual(os.listdir(self.path("b")), [])            # its runs removed once read


class BenchScaling(Base):
    """bench_scaling.py: strong and weak scaling over MPI ranks x OpenMP threads (docs/mpi.md)."""

    def test_bad_counts_refused(self):
        for opt, val in (("--ranks", "x"), ("--ranks", "0"), ("--threads", "1,"), ("--threads", "-2")):
            with self.subTest(opt=opt, val=val):
                p = self.script("bench_scaling.py", "--exe", "/bin/false", opt + "=" + val, "--out", self.path("o"))
                self.one_line(p, r"^bench_scaling\.py: refused: %s '%s'" % (opt, re.escape(val)))
        self.assertFalse(os.path.exists(self.path("o")))

    @unittest.skipUnless(EXE and shutil.which("mpirun"), "needs CONTACT2D and mpirun")
    def test_tiny_tables(self):
        # level 1 (26 x 6 elements), 20 steps, 1 and 2 ranks of 1 thread: both tables, a row per
        # case with a positive time and rate; the 1 x 1 row is the reference (speed-up 1); the weak
        # mesh of 2 ranks has twice the grid rows, so twice the elements of 1 rank's
        out = self.path("s")
        p = self.script("bench_scaling.py", "--exe", EXE, "--ranks", "1,2", "--threads", "1", "--level", "1",
                        "--steps", "20", "--repeats", "1", "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        for kind in ("strong", "weak"):
            self.assertIn(kind + " scaling", p.stdout)
        rows = [line.split() for line in p.stdout.splitlines() if re.match(r"^\s+[12]\s+1\s+[0-9.]", line)]
        self.assertEqual([r[0] for r in rows], ["1", "2", "1", "2"], p.stdout)
        for r in rows:
            self.assertGreater(float(r[2]), 0)      # steps [s]
            self.assertGreater(float(r[3]), 0)      # element-steps / s
        self.assertEqual(rows[0][4], "1.00")
        import h5py
        with h5py.File(os.path.join(out, "weak_1_1.h5"), "r") as f1, h5py.File(os.path.join(out, "weak_2_1.h5"), "r") as f2:
            self.assertEqual(2 * int(f1.attrs["element_count"]), int(f2.attrs["element_count"]))
        # its table is not replaced without --force: one line, the file kept
        before = digest(os.path.join(out, "scaling.json"))
        p = self.script("bench_scaling.py", "--exe", EXE, "--level", "1", "--steps", "20", "--repeats", "1", "--out", out)
        self.one_line(p, r"^bench_scaling\.py: refused: .*scaling\.json exists")
        self.assertEqual(before, digest(os.path.join(out, "scaling.json")))


class Products(Base):
    """Every study script refuses, before any run, a table or figure of its own already there (the
    benchmarks: bench.json, and bench_static.py the runs it would write and remove)."""
    CASES = (("paper_study.py", ["--levels", "0-1"], "convergence.png"),
             ("paper_study.py", ["--levels", "1"], "p1_sign.csv"),
             ("hertz_study.py", [], "geometry_study.md"),
             ("impact_study.py", ["--figures", "{out}"], "impact_study.csv"),
             ("impact_study.py", ["--figures", "{out}"], "impact_energy.png"),
             ("stability_study.py", ["penalty"], "penalty.png"),
             ("stability_study.py", ["all"], "longrun.csv"),
             ("coulomb_path_study.py", [], "coulomb_path.png"),
             ("speed_accuracy.py", ["--no-getfem"], "speed_accuracy.csv"),
             ("stability_sweep.py", ["--methods", "elastic", "--ratios", "0.5:0.5:0.1"], "stability.csv"),
             ("stability_sweep.py", ["--methods", "elastic", "--ratios", "0.5:0.5:0.1"], "stability.png"),
             ("bench_speed.py", ["--sections", "speed", "--levels", "0", "--no-getfem"], "bench.json"),
             ("bench_static.py", ["--levels", "0"], "static_k0.h5"),
             ("bench_static.py", ["--levels", "0"], "explicit_k0.h5"))

    def test_existing_product_needs_force(self):
        # the old scripts ran (here a contact2d that fails at once) and replaced them silently
        for script, args, name in self.CASES:
            with self.subTest(script=script, product=name):
                out = self.path(script + "_" + name)
                os.mkdir(out)
                with open(os.path.join(out, name), "w") as fh:
                    fh.write("the user's file\n")
                p = self.script(script, "--exe", "/bin/false", "--out", out, *[a.format(out=out) for a in args])
                self.one_line(p, r"^%s: refused: .*%s exists \(pass --force" % (script, name))
                self.assertEqual(os.listdir(out), [name])          # nothing run, nothing written
                with open(os.path.join(out, name)) as fh:
                    self.assertEqual(fh.read(), "the user's file\n")

    @unittest.skipUnless(EXE, "set CONTACT2D=path/to/contact2d to run")
    def test_product_that_appears_meanwhile(self):
        # a contact2d that puts a file under the product's name beside its output, then runs: the old
        # studies died with an OutputRefused traceback
        for script, args, name in (("paper_study.py", ["--levels", "0"], "convergence.csv"),
                                   ("paper_study.py", ["--levels", "0"], "fig3_contact_stress.png"),
                                   ("speed_accuracy.py", ["--levels", "0", "--no-getfem", "--no-hertz",
                                                          "--reference-dir", self.path("none")], "speed_accuracy.png"),
                                   ("stability_sweep.py", ["--methods", "elastic", "--ratios", "0.5:0.5:0.1",
                                                           "--level", "0", "--time", "3e-6"], "stability.png")):
            with self.subTest(script=script, product=name):
                out = self.path(script + "_" + name)
                exe = self.path("contact2d_" + name)
                with open(exe, "w") as fh:
                    fh.write('#!/bin/sh\nfor a; do [ "$prev" = -o ] && echo "the user\'s file" > "${a%%/*}/%s"; '
                             'prev=$a; done\nexec "%s" "$@"\n' % (name, EXE))
                os.chmod(exe, 0o755)
                p = self.script(script, "--exe", exe, "--out", out, *args)
                self.one_line(p, r"^%s: refused: .*%s appeared while this command ran; not replaced$"
                              % (script, name))
                with open(os.path.join(out, name)) as fh:
                    self.assertEqual(fh.read(), "the user's file\n")

    def test_help_names_force(self):
        for script in sorted({c[0] for c in self.CASES}):
            with self.subTest(script=script):
                self.assertIn("--force", self.script(script, "--help").stdout)

    def test_save_figure_keeps_the_format(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from contact2d.outfile import OutputRefused, save_figure
        fig = plt.figure()
        png = self.path("f.png")
        save_figure(fig, png)
        with open(png, "rb") as fh:
            self.assertEqual(fh.read(8), b"\x89PNG\r\n\x1a\n")
        with self.assertRaises(OutputRefused):
            save_figure(fig, png)
        save_figure(fig, self.path("f.pdf"), force=True)
        self.assertEqual(sorted(os.listdir(self.dir)), ["f.pdf", "f.png"])
        plt.close(fig)


class Modules(Base):
    def test_modules_say_so(self):
        # the old modules printed nothing and exited 0 for --help (or any argument)
        for name in ("h5", "runner", "cattaneo_mindlin", "fem_q1", "hertz", "impact", "lame", "outfile"):
            for args in (["--help"], []):
                with self.subTest(module=name, args=args):
                    p = subprocess.run([sys.executable, "-B", "-m", "contact2d." + name] + args,
                                       capture_output=True, text=True, timeout=60)
                    self.one_line(p, r"^contact2d\.%s is a module, not a script \(docs/postproc\.md\)" % name)
                    self.assertEqual(p.stdout, "")


if __name__ == "__main__":
    unittest.main()
