#!/usr/bin/env python3
"""Several processes (mpirun -np N) give the bits of one process.

The explicit engine shares the built-in mesh's grid rows among the ranks in blocks of whole
rows: every row's energy sums are formed by one rank as in the serial run and added in the
serial order, and the rest of the step is done alike on every rank from the same numbers, so
the file rank 0 writes must equal the serial run's bit for bit (docs/mpi.md). Checked on the
paper scene, P1 and P0, with 1, 2, 3 and 4 ranks (and 2 ranks of 2 OpenMP threads): a fixed
number of steps at the deck's level and the converged end state at level 2 (every dataset and
attribute but the timings); Gmsh meshes (chunks of block rows per rank) likewise, the Hertz
indenter (frictionless) and the Mindlin cylinder (Coulomb) with 1 to 4 ranks. Contracts: a Gmsh
mesh of fewer chunks than ranks, the static engine and a mesh with fewer than two grid rows per
rank stop under mpirun with one line, exit 1, no file; a write that fails
on rank 0 alone (a full tmpfs, where one can be mounted) ends the run with one line and exit 2,
no hang; SIGTERM sent to rank 1 alone stops every rank at the same step (exit 143, one line,
the file holds status 'interrupted'), it does not hang.
"""
import os
import signal
import subprocess
import tempfile
import time

import h5py
import numpy as np

import c2dtest

# attributes that hold timings or the machine, not results (as tools/h5same.py)
SKIP_ATTR = ("wall", "time_", "timing", "seconds", "clock", "date", "host", "version", "pid", "build",
             "threads", "command", "elapsed", "rate")
ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMP_NUM_THREADS": "1",
       "OMPI_MCA_rmaps_base_oversubscribe": "1"}


def items(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out["D:" + name] = obj[()]
            for k, v in obj.attrs.items():
                out["A:" + name + "@" + k] = v
        for k, v in f.attrs.items():
            out["A:/@" + k] = v
        f.visititems(visit)
    return {k: v for k, v in out.items() if not (k.startswith("A:") and any(s in k.split("@")[-1] for s in SKIP_ATTR))}


def bitwise(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "f" or b.dtype.kind == "f":
        return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
    try:
        return bool(np.array_equal(a, b))
    except Exception:
        return str(a) == str(b)


def mpirun(t, n, deck, args, name, timeout=600, threads=1):
    cwd = t.subdir(name)
    cmd = [t.args.mpirun, "-q", "--oversubscribe", "-np", str(n), t.exe, deck, "-o", "out.h5", "-q"] + list(args)
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, timeout=timeout,
                           env={**os.environ, **ENV, "OMP_NUM_THREADS": str(threads)})
    except subprocess.TimeoutExpired:
        t.abort("run timed out after %g s (a hang?): %s" % (timeout, " ".join(cmd)))
    run = c2dtest.Run(cmd, cwd, p.returncode, p.stdout.decode("utf-8", "replace"),
                      p.stderr.decode("utf-8", "replace"), time.monotonic() - t0, os.path.join(cwd, "out.h5"))
    print("-- run  %s\n   exit %d after %.2f s" % (run.command_line(), run.returncode, run.seconds))
    return run


def same_as_serial(t, deck, args, tag, runs=((1, 1), (2, 1), (3, 1), (4, 1))):
    serial = t.run(deck, *args, name=tag + "_serial", env={"OMP_NUM_THREADS": "1"})
    t.expect_exit(serial, 0)
    base = items(serial.h5)
    for n, threads in runs:
        r = mpirun(t, n, deck, args, "%s_np%d_t%d" % (tag, n, threads), threads=threads)
        t.expect_exit(r, 0)
        t.expect_output(r)
        new = items(r.h5)
        differ = sorted(k for k in set(base) | set(new) if k not in base or k not in new or not bitwise(base[k], new[k]))
        t.check(r, "%s, %d ranks x %d threads: every HDF5 item bit for bit as one process (%d compared)"
                % (tag, n, threads, len(base)), not differ, "none differ", ", ".join(differ[:8]) if differ else "none differ")


def rank_pid(marker, rank):
    """The pid of the rank `rank` of the run whose command line holds marker (from /proc)."""
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                cmd = f.read().decode("utf-8", "replace")
            with open("/proc/%s/environ" % pid, "rb") as f:
                env = f.read().decode("utf-8", "replace").split("\0")
        except OSError:
            continue
        if marker in cmd and "OMPI_COMM_WORLD_RANK=%d" % rank in env:
            return int(pid)
    return None


def body(t):
    for m in ("p1", "p0"):
        deck = t.deck("baillet_sassi_2002_%s.nml" % m)
        # (2 ranks x 2 threads: the deck's level has 10 241 nodes, above the threads' threshold)
        same_as_serial(t, deck, ["--set", "solver:max_steps=600"], m + "_600_steps",
                       runs=((1, 1), (2, 1), (3, 1), (4, 1), (2, 2)))
        same_as_serial(t, deck, ["--set", "mesh:level=2"], m + "_end_state_level2")

    # Gmsh meshes: contiguous ranges of whole chunks of block rows per rank, so the chunk sums
    # are the serial ones added in the serial order; frictionless (Hertz) and Coulomb (Mindlin)
    same_as_serial(t, t.deck("hertz_indenter_p1.nml"), ["--set", "mesh:level=1", "--set", "solver:max_steps=400"],
                   "gmsh_hertz_400_steps", runs=((1, 1), (2, 1), (3, 1), (4, 1), (2, 2)))
    same_as_serial(t, t.deck("mindlin_cylinder_p1.nml"), ["--set", "solver:max_steps=400"], "gmsh_mindlin_400_steps")

    # what the ranks cannot share: one line naming the reason, exit 1, nothing written
    p1 = t.deck("baillet_sassi_2002_p1.nml")
    # (the level-0 Gmsh rectangle: 14 x 4 = 56 nodes, one chunk of block rows)
    for name, n, deck, args, word in (("gmsh_too_small", 2, t.deck("gmsh_rectangle_p1.nml"), ["--set", "mesh:level=0"],
                                       "56 nodes"),
                                      ("static_refused", 2, p1, ["--static"], "one process"),
                                      ("rows_refused", 3, p1, ["--set", "mesh:level=0"], "4 grid rows")):
        r = mpirun(t, n, deck, args, name)
        t.expect_exit(r, 1, stop=False)
        lines = r.stderr_lines()
        t.check(r, "one stderr line, the error naming '%s'" % word,
                len(lines) == 1 and lines[0].startswith(c2dtest.ERROR_PREFIX) and word in lines[0],
                "1 line 'contact2d: error: ... %s ...'" % word, " | ".join(lines))
        t.check(r, "nothing written", not [f for f in os.listdir(r.cwd) if f.startswith("out.") or f.startswith(".out.")],
                "no file", ", ".join(os.listdir(r.cwd)))

    # a failure of rank 0 alone (only rank 0 writes: a full disk, a small tmpfs, makes its write
    # fail) stops the run with its one line and exit 2; the other rank must not be left waiting
    # (MPI_Finalize waits for every rank: it hung there). A file size limit would not do: MPI's
    # own shared-memory files would hit it.
    mnt = tempfile.mkdtemp(prefix="c2d_tmpfs_", dir=t.workdir)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", mnt],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if mounted.returncode != 0:
        print("SKIP write_fails_rank0: cannot mount a tmpfs here (%s)" % mounted.stdout.decode("utf-8", "replace").strip())
    else:
        try:
            snaps = ",".join("%g" % (k * 2.5e-7) for k in range(1, 17))
            cmd = [t.args.mpirun, "-q", "--oversubscribe", "-np", "2", t.exe, p1, "-o", "out.h5", "-q",
                   "--set", "mesh:level=3", "--set", "output:snapshot_times=" + snaps]
            p = subprocess.Popen(cmd, cwd=mnt, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env={**os.environ, **ENV})
            try:
                out, err = p.communicate(timeout=120)
            except subprocess.TimeoutExpired:
                p.kill()
                p.communicate()
                t.abort("a write failure on rank 0 did not end the run within 120 s (a hang)")
            run = c2dtest.Run(cmd, mnt, p.returncode, out.decode(), err.decode(), 0.0, os.path.join(mnt, "out.h5"))
            t.expect_exit(run, 2, stop=False)
            lines = run.stderr_lines()
            t.check(run, "one stderr line with the system's reason", len(lines) == 1 and "No space left" in lines[0],
                    "1 line '... No space left on device ...'", " | ".join(lines))
        finally:
            subprocess.run(["umount", mnt])

    # SIGTERM to rank 1 only: every rank stops at the same step (the signal is agreed in the step's
    # gather), rank 0 writes the interrupted state; a rank that stopped alone would hang the others
    cwd = t.subdir("sigterm_rank1")
    deck = t.deck("baillet_sassi_2002_p1.nml")
    cmd = [t.args.mpirun, "-q", "--oversubscribe", "-np", "2", t.exe, deck, "-o", "sig.h5", "-q",
           "--set", "mesh:level=5", "--set", "solver:max_steps=1000000"]
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env={**os.environ, **ENV})
    pid = None
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and p.poll() is None:
        # the steps have begun once the temporary file exists (the handler is installed then)
        if any(f.startswith("sig.h5.") for f in os.listdir(cwd)):
            time.sleep(1.0)
            pid = rank_pid("sig.h5", 1)
            break
        time.sleep(0.2)
    t.require(pid is not None, "rank 1 of the run was not found")
    os.kill(pid, signal.SIGTERM)
    try:
        out, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        t.abort("the run did not end within 120 s of SIGTERM to rank 1 (a hang)")
    run = c2dtest.Run(cmd, cwd, p.returncode, out.decode(), err.decode(), 0.0, os.path.join(cwd, "sig.h5"))
    t.expect_exit(run, 128 + signal.SIGTERM, stop=False)
    lines = run.stderr_lines()
    t.check(run, "one stderr line, 'interrupted by SIGTERM'", len(lines) == 1 and "interrupted by SIGTERM" in lines[0],
            "1 line", " | ".join(lines))
    t.expect_output(run)
    with run.open() as f:
        status = c2dtest.attr_str(f.attrs["status"])
    t.check_equal(run, "status of the file rank 0 wrote", "interrupted", status)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0], extra_args=[(("--mpirun",), {"required": True, "help": "mpirun"})]).main(body)
