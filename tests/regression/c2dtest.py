"""Helpers for the contact2d regression tests (standard library, numpy and h5py only).

A test script does:

    import c2dtest
    t = c2dtest.Test("what this test checks")          # parses --exe --inputs --workdir
    run = t.run(t.deck("uniaxial_compression.nml"), "--set", "mesh:level=1", name="a")
    t.expect_exit(run, 0)
    with run.open() as f:
        t.check_close(run, "u_x", expected, actual, rtol=1e-8, reason="...")
    t.finish()                                         # exit status 1 if any check failed

Every check prints one line, PASS or FAIL, with file, quantity, expected, actual and tolerance
and the one-line reason for the tolerance, so `ctest -V` shows every figure a test measured.
A failed check does not stop the test (the other figures still get printed); `require` does, for
checks whose failure makes the rest meaningless (no output file, wrong exit code...).
"""
import argparse
import os
import shlex
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

# the project's reader (postproc/contact2d/h5.py, on PYTHONPATH by ctest): its deck parser
try:
    from contact2d.h5 import parse_effective_deck
except ImportError as _exc:   # run by hand without PYTHONPATH: one line saying what to set
    raise SystemExit("c2dtest: cannot import the package contact2d (%s): run the test through ctest, or set "
                     "PYTHONPATH=<repository>/postproc" % _exc)

__all__ = ["Test", "Run", "parse_effective_deck", "q1_plane_strain", "exact_dt_limit"]

ERROR_PREFIX = "contact2d: error:"


class Abort(Exception):
    """Raised by Test.require: stop the test here (finish() reports it)."""


class Run:
    """One finished run of the program: command, exit code, stdout, stderr, output path."""

    def __init__(self, cmd, cwd, returncode, stdout, stderr, seconds, h5):
        self.cmd = cmd
        self.cwd = cwd
        self.returncode = returncode
        self.stdout = stdout
        self.stderr = stderr
        self.seconds = seconds
        self.h5 = h5          # absolute path of the expected HDF5 output (may not exist)

    @property
    def name(self):
        """Short label used in check lines: the output file relative to the work dir."""
        return os.path.relpath(self.h5, os.path.dirname(self.cwd))

    @property
    def xmf(self):
        root, _ = os.path.splitext(self.h5)
        return root + ".xmf"

    def stderr_lines(self):
        return [line for line in self.stderr.splitlines() if line.strip()]

    def error_lines(self):
        return [line for line in self.stderr_lines() if line.startswith(ERROR_PREFIX)]

    def open(self):
        """The output file, read-only (use as a context manager)."""
        return h5py.File(self.h5, "r")

    def command_line(self):
        return "(cd " + shlex.quote(self.cwd) + " && " + " ".join(shlex.quote(c) for c in self.cmd) + ")"


class Test:
    """Command line, work directory, program runs and checks of one regression test."""

    def __init__(self, description, extra_args=None):
        parser = argparse.ArgumentParser(description=description)
        parser.add_argument("--exe", required=True, help="the contact2d executable")
        parser.add_argument("--inputs", required=True, help="the inputs/ directory of the decks")
        parser.add_argument("--workdir", required=True, help="per-test scratch directory (recreated)")
        for args, kwargs in (extra_args or []):
            parser.add_argument(*args, **kwargs)
        self.args = parser.parse_args()
        self.exe = os.path.abspath(self.args.exe)
        self.inputs = os.path.abspath(self.args.inputs)
        self.workdir = os.path.abspath(self.args.workdir)
        self.here = os.path.dirname(os.path.abspath(__file__))
        self.failures = []
        self.npass = 0
        self.t0 = time.monotonic()
        # stale outputs of an earlier run must never be mistaken for this run's
        if os.path.isdir(self.workdir):
            shutil.rmtree(self.workdir)
        os.makedirs(self.workdir)
        print("== " + description)
        print("   exe     " + self.exe)
        print("   workdir " + self.workdir)
        sys.stdout.flush()

    # ---- files and runs --------------------------------------------------------------------

    def deck(self, name):
        """Path of a shipped deck in inputs/."""
        return os.path.join(self.inputs, name)

    def subdir(self, name):
        """A fresh, empty directory under the work dir."""
        path = os.path.join(self.workdir, name)
        if os.path.exists(path):
            shutil.rmtree(path)
        os.makedirs(path)
        return path

    def run(self, deck, *args, name=None, cwd=None, output="out.h5", timeout=600, quiet=True, env=None):
        """Run the program on deck with extra args, in cwd (default: a fresh subdir `name`).

        output: file name given with -o (relative to cwd), or None to let the program choose
        (<deck stem>.h5 in cwd). Stale outputs are deleted first unless cwd is given (then the
        caller owns the directory's contents).
        """
        if cwd is None:
            cwd = self.subdir(name or "run")
        cmd = [self.exe, deck]
        if output is not None:
            cmd += ["-o", output]
        cmd += list(args)
        if quiet:
            cmd.append("-q")
        if output is None:
            h5 = os.path.join(cwd, os.path.splitext(os.path.basename(deck))[0] + ".h5")
        else:
            h5 = os.path.join(cwd, output)
        t0 = time.monotonic()
        try:
            proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  timeout=timeout, env=None if env is None else {**os.environ, **env})
        except subprocess.TimeoutExpired:
            self.abort("run timed out after %g s: %s" % (timeout, " ".join(cmd)))
        seconds = time.monotonic() - t0
        run = Run(cmd, cwd, proc.returncode, proc.stdout.decode("utf-8", "replace"),
                  proc.stderr.decode("utf-8", "replace"), seconds, h5)
        print("-- run  %s" % run.command_line())
        print("   exit %d after %.2f s" % (run.returncode, seconds))
        for line in run.stderr_lines():
            # Debug builds print gfortran's array-temporary warnings; show everything else
            if "array temporary" in line or line.startswith("At line "):
                continue
            print("   stderr: " + line)
        sys.stdout.flush()
        return run

    # ---- reporting -------------------------------------------------------------------------

    def _report(self, ok, where, quantity, expected, actual, tolerance, reason):
        line = "%s %s: %s: expected %s, actual %s" % ("PASS" if ok else "FAIL", where, quantity,
                                                       expected, actual)
        if tolerance:
            line += ", tolerance " + tolerance
        if reason:
            line += "  [" + reason + "]"
        print(line)
        sys.stdout.flush()
        if ok:
            self.npass += 1
        else:
            self.failures.append(line)
        return ok

    @staticmethod
    def _where(where):
        return where.name if isinstance(where, Run) else str(where)

    def info(self, where, quantity, value):
        """Print a measured figure that is not checked (context for the reader)."""
        print("INFO %s: %s = %s" % (self._where(where), quantity, value))
        sys.stdout.flush()

    def check(self, where, quantity, ok, expected, actual, tolerance="", reason=""):
        """Generic check: ok is the verdict, the rest is what gets printed."""
        return self._report(bool(ok), self._where(where), quantity, expected, actual, tolerance, reason)

    def check_equal(self, where, quantity, expected, actual, reason=""):
        return self._report(expected == actual, self._where(where), quantity, repr(expected),
                            repr(actual), "exact", reason)

    def check_lines_equal(self, where, quantity, expected, actual, reason=""):
        """Two texts (lists of lines) equal; prints the line count or the first difference."""
        expected, actual = list(expected), list(actual)
        if expected == actual:
            return self._report(True, self._where(where), quantity, "%d lines" % len(expected),
                                "%d identical lines" % len(actual), "exact", reason)
        k = next((i for i, (e, a) in enumerate(zip(expected, actual)) if e != a), min(len(expected), len(actual)))
        e = repr(expected[k]) if k < len(expected) else "(end, %d lines)" % len(expected)
        a = repr(actual[k]) if k < len(actual) else "(end, %d lines)" % len(actual)
        return self._report(False, self._where(where), quantity + " (first difference, line %d)" % (k + 1), e, a,
                            "exact", reason)

    def check_close(self, where, quantity, expected, actual, rtol=0.0, atol=0.0, scale=None, reason=""):
        """max |actual - expected| <= atol + rtol * scale, scale = max |expected| by default.

        Works for scalars and arrays (max-norm); prints the worst entry.
        """
        exp = np.asarray(expected, dtype=float)
        act = np.asarray(actual, dtype=float)
        if exp.shape != act.shape and exp.size != 1:
            return self._report(False, self._where(where), quantity, "shape %s" % (exp.shape,),
                                "shape %s" % (act.shape,), "", reason)
        exp = np.broadcast_to(exp, act.shape)
        if scale is None:
            scale = float(np.max(np.abs(exp))) if exp.size else 0.0
        limit = atol + rtol * scale
        if act.size == 0:
            return self._report(False, self._where(where), quantity, "values", "an empty array", "", reason)
        err = np.abs(act - exp)
        finite = bool(np.all(np.isfinite(act)))
        k = int(np.nanargmax(np.where(np.isfinite(err), err, np.inf))) if finite else int(
            np.argmax(~np.isfinite(act).ravel()))
        worst = float(err.ravel()[k])
        ok = finite and worst <= limit
        if act.size == 1:
            e_txt, a_txt = "%.17g" % exp.ravel()[0], "%.17g" % act.ravel()[0]
        else:
            idx = np.unravel_index(k, act.shape)
            e_txt = "%.17g (worst entry %s of %d)" % (exp[idx], list(int(i) for i in idx), act.size)
            a_txt = "%.17g" % act[idx]
        tol = "|diff| %.3e <= %.3e" % (worst, limit)
        if rtol:
            tol += " (rtol %.1e x %.6g" % (rtol, scale) + (" + atol %.1e)" % atol if atol else ")")
        else:
            tol += " (atol)"
        return self._report(ok, self._where(where), quantity, e_txt, a_txt, tol, reason)

    def check_le(self, where, quantity, actual, limit, reason=""):
        """max(actual) <= limit (arrays: every entry; NaN fails)."""
        act = np.asarray(actual, dtype=float)
        if act.size == 0:
            return self._report(False, self._where(where), quantity, "<= %.6g" % limit, "an empty array",
                                "", reason)
        worst = float(np.max(act)) if np.all(np.isfinite(act)) else float("nan")
        ok = np.isfinite(worst) and worst <= limit
        what = "max " if act.size > 1 else ""
        return self._report(ok, self._where(where), quantity, "<= %.6g" % limit,
                            "%s%.6g" % (what, worst) + (" over %d values" % act.size if act.size > 1 else ""),
                            "", reason)

    def check_ge(self, where, quantity, actual, limit, reason=""):
        """min(actual) >= limit (arrays: every entry; NaN fails)."""
        act = np.asarray(actual, dtype=float)
        if act.size == 0:
            return self._report(False, self._where(where), quantity, ">= %.6g" % limit, "an empty array",
                                "", reason)
        worst = float(np.min(act)) if np.all(np.isfinite(act)) else float("nan")
        ok = np.isfinite(worst) and worst >= limit
        what = "min " if act.size > 1 else ""
        return self._report(ok, self._where(where), quantity, ">= %.6g" % limit,
                            "%s%.6g" % (what, worst) + (" over %d values" % act.size if act.size > 1 else ""),
                            "", reason)

    def require(self, ok, message):
        """Stop the test now if not ok (later checks would be meaningless)."""
        if not ok:
            self.abort(message)

    def abort(self, message):
        line = "FAIL (stopping) " + message
        print(line)
        self.failures.append(line)
        raise Abort(message)

    # ---- common program-level checks -------------------------------------------------------

    def expect_exit(self, run, code, stop=True):
        """The exit code; on a mismatch print stdout/stderr tails and (by default) stop."""
        ok = self.check_equal(run, "exit code", code, run.returncode)
        if not ok:
            print("   --- stdout (last 15 lines) ---")
            print("\n".join("   " + l for l in run.stdout.splitlines()[-15:]))
            print("   --- stderr ---")
            print("\n".join("   " + l for l in run.stderr.splitlines()[-15:]))
            if stop:
                self.abort("%s: exit code %d, expected %d" % (run.command_line(), run.returncode, code))
        return ok

    def expect_output(self, run):
        """The HDF5 file exists and opens."""
        exists = os.path.isfile(run.h5)
        self.check(run, "output file exists", exists, "a file", "present" if exists else "missing")
        if not exists:
            self.abort("no output file " + run.h5)
        try:
            with run.open() as f:
                nkeys = len(f.keys())
        except (OSError, KeyError) as exc:
            self.check(run, "output file opens with h5py", False, "opens", repr(exc))
            self.abort("cannot open " + run.h5)
        self.check(run, "output file opens with h5py", True, "opens", "opens (%d root groups)" % nkeys)

    # ---- end ---------------------------------------------------------------------------------

    def finish(self):
        print("== %d checks passed, %d failed (%.2f s)" % (self.npass, len(self.failures),
                                                          time.monotonic() - self.t0))
        if self.failures:
            print("failed checks:")
            for line in self.failures:
                print("  " + line)
            sys.exit(1)
        sys.exit(0)

    def main(self, body):
        """Run body(self), turning Abort and unexpected exceptions into a failed test."""
        try:
            body(self)
        except Abort:
            pass
        except Exception:  # a test bug or an unreadable file: report it, fail the test
            import traceback
            traceback.print_exc(file=sys.stdout)
            self.failures.append("unexpected exception (see traceback above)")
        self.finish()


# ---- input files ---------------------------------------------------------------------------------

def write_grid_msh(path, nx, ny):
    """A MSH 2.2 file of the unit square in nx x ny quads, physical curves 'bottom' and 'top'."""
    def nid(i, j):
        return j * (nx + 1) + i + 1
    els = ["1 2 1 1 %d %d" % (nid(i, 0), nid(i + 1, 0)) for i in range(nx)]
    els += ["1 2 2 3 %d %d" % (nid(i + 1, ny), nid(i, ny)) for i in range(nx)]
    els += ["3 2 3 1 %d %d %d %d" % (nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1))
            for j in range(ny) for i in range(nx)]
    with open(path, "w") as f:
        f.write('$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 1 "bottom"\n1 2 "top"\n'
                '2 3 "square"\n$EndPhysicalNames\n$Nodes\n%d\n' % ((nx + 1) * (ny + 1)))
        for j in range(ny + 1):
            for i in range(nx + 1):
                f.write("%d %r %r 0\n" % (nid(i, j), i / nx, j / ny))
        f.write("$EndNodes\n$Elements\n%d\n" % len(els))
        f.write("".join("%d %s\n" % (k + 1, e) for k, e in enumerate(els)))
        f.write("$EndElements\n")


# ---- independent reference computations (numpy) ------------------------------------------------

def attr_str(value):
    """An HDF5 string attribute as a Python str (h5py may return bytes or numpy strings)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return attr_str(value[()])
    return str(value)


def q1_plane_strain(coords, conn, young, poisson, density):
    """Global Q1 plane-strain stiffness K (dense, 2 dofs per node: x then y) and the row-sum
    lumped mass vector m (per dof), 2x2 Gauss, from first principles.

    coords (nnode, 2); conn (nel, 4) 0-based, counter-clockwise.
    """
    nnode = coords.shape[0]
    ndof = 2 * nnode
    lam_fac = young / ((1 + poisson) * (1 - 2 * poisson))
    dmat = lam_fac * np.array([[1 - poisson, poisson, 0.0],
                               [poisson, 1 - poisson, 0.0],
                               [0.0, 0.0, (1 - 2 * poisson) / 2]])
    xi_a = np.array([-1.0, 1.0, 1.0, -1.0])
    eta_a = np.array([-1.0, -1.0, 1.0, 1.0])
    g = 1 / np.sqrt(3.0)
    gauss = [(-g, -g), (g, -g), (g, g), (-g, g)]
    K = np.zeros((ndof, ndof))
    m = np.zeros(ndof)
    for nodes in conn:
        xe = coords[nodes]
        ke = np.zeros((8, 8))
        me = np.zeros(4)
        for xi, eta in gauss:
            n = 0.25 * (1 + xi * xi_a) * (1 + eta * eta_a)
            dn = 0.25 * np.array([xi_a * (1 + eta * eta_a), eta_a * (1 + xi * xi_a)])  # (2, 4)
            jac = dn @ xe                                                           # (2, 2)
            det = np.linalg.det(jac)
            dxy = np.linalg.solve(jac, dn)                                          # (2, 4)
            b = np.zeros((3, 8))
            b[0, 0::2] = dxy[0]
            b[1, 1::2] = dxy[1]
            b[2, 0::2] = dxy[1]
            b[2, 1::2] = dxy[0]
            ke += b.T @ dmat @ b * det
            me += density * n * det
        dofs = np.ravel(np.column_stack([2 * nodes, 2 * nodes + 1]))
        K[np.ix_(dofs, dofs)] += ke
        m[2 * nodes] += me
        m[2 * nodes + 1] += me
    return K, m


def exact_dt_limit(coords, conn, young, poisson, density, free):
    """The true central-difference stability limit 2 / omega_max of the free dofs:
    omega_max^2 = largest eigenvalue of M^-1/2 K_ff M^-1/2 (dense numpy eigensolver)."""
    K, m = q1_plane_strain(coords, conn, young, poisson, density)
    f = np.flatnonzero(free)
    s = 1 / np.sqrt(m[f])
    a = K[np.ix_(f, f)] * s[:, None] * s[None, :]
    omega2 = float(np.linalg.eigvalsh(a)[-1])
    return 2 / np.sqrt(omega2), np.sqrt(omega2)


def select_edge_nodes(coords, edge, lx, ly, xmin=-np.inf, xmax=np.inf, ymin=-np.inf, ymax=np.inf):
    """Nodes on one side of the bounding box within a coordinate range (tolerance 1e-9 of the size)."""
    tol = 1e-9 * max(lx, ly)
    x, y = coords[:, 0], coords[:, 1]
    on = {"bottom": np.abs(y) <= tol, "top": np.abs(y - ly) <= tol,
          "left": np.abs(x) <= tol, "right": np.abs(x - lx) <= tol}[edge]
    inside = (x >= xmin - tol) & (x <= xmax + tol) & (y >= ymin - tol) & (y <= ymax + tol)
    return np.flatnonzero(on & inside)


def free_dofs_from_deck(coords, deck):
    """Boolean mask of the dofs no &dirichlet group prescribes (x then y per node)."""
    lx, ly = float(deck["mesh"]["lx"]), float(deck["mesh"]["ly"])
    free = np.ones(2 * coords.shape[0], dtype=bool)
    for d in deck["dirichlet"]:
        rng = {k: float(d[k]) for k in ("xmin", "xmax", "ymin", "ymax") if k in d}
        nodes = select_edge_nodes(coords, d["edge"], lx, ly, **rng)
        comp = {"x": 0, "y": 1}[d["component"]]
        free[2 * nodes + comp] = False
    return free


def dual_coupling(abscissa):
    """The P0 coupling matrix D of SPEC section 3 (tridiagonal, from the contact abscissae):
    D_ii = 3 (h_{i-1} + h_i) / 8, D_{i,i+1} = D_{i+1,i} = h_i / 8 (missing half-edges at the ends)."""
    s = np.asarray(abscissa, dtype=float)
    h = np.diff(s)
    n = s.size
    D = np.zeros((n, n))
    for i in range(n - 1):
        D[i, i] += 3 * h[i] / 8
        D[i + 1, i + 1] += 3 * h[i] / 8
        D[i, i + 1] = D[i + 1, i] = h[i] / 8
    return D


def nodal_weights(abscissa):
    """w_i = (h_{i-1} + h_i) / 2 (one half-edge at the two ends)."""
    h = np.diff(np.asarray(abscissa, dtype=float))
    w = np.zeros(h.size + 1)
    w[:-1] += h / 2
    w[1:] += h / 2
    return w
