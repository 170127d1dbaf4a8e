"""Regression 15: faults end cleanly and never lose data.

- SIGINT / SIGTERM mid-run: exit 130 / 143, one line on stderr, OUT.h5 in place with status
  'interrupted', the history up to the stop, /final and the sidecar; no temporary file or lock left.
  The same for the static engine (--static) between its increments.
- A --force run over an existing result that does not reach its end (SIGTERM, SIGINT to the static
  engine, a blow-up): the result and its sidecar are byte for byte intact, the run's complete file
  is kept as OUT.h5.<pid>.partial with its status, named on the one stderr line.
- kill -9 of a --force run over an existing result: the result is byte for byte intact, the
  killed run's OUT.h5.<pid>.partial is there and opens (what was flushed is readable); a later
  run takes over the stale lock and leaves only that partial file.
- PID reuse (a PID namespace, where the solver is PID 1 in every run): a later run takes another
  temporary name and leaves the earlier run's OUT.h5.1.partial and sidecar byte for byte; a link
  planted under the sidecar's temporary name is not followed.
- A file that appears under the output's name while a run writes (no --force): exit 2, one line,
  the run's complete file kept under its temporary name, the other file and no sidecar for it.
- Two runs on one output: while one writes, a second --force run is refused with one line and
  writes nothing; two runs started together leave one valid result.
- A write that fails (file size limit RLIMIT_FSIZE, the kernel's EFBIG, and a full tmpfs where
  the machine allows mounting one): exit 2, one line with the system's reason, the existing
  result intact, the partial file readable.
- Semantics: a load-unload deck converges (absolute floor), two snapshot times in one step
  give one snapshot, dt_factor = 1e29 (allowed) blows up with a summary instead of a formatting
  crash, an obstacle normal pointing away from the body is warned about.
"""
import glob
import hashlib
import os
import resource
import shutil
import signal
import subprocess
import tempfile
import time

import h5py
import numpy as np

import c2dtest

LONG = "baillet_sassi_2002_p0.nml"
# a run that lasts (never converges) but is cheap per step; the test stops it
LONG_ARGS = ["--set", "mesh:level=2", "--set", "solver:tol_residual=1e-300", "--set", "solver:t_end=1.0",
             "--set", "output:history_interval=1"]
UNIAXIAL = "uniaxial_compression.nml"
ENV = {**os.environ, "OMP_NUM_THREADS": "1"}


def sha(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def start(t, folder, deck, args, out="out.h5"):
    cmd = [t.exe, deck, "-o", out, "-q"] + list(args)
    print("-- start (cd %s && %s)" % (folder, " ".join(cmd)))
    return subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV)


def wait_for(pattern, timeout=120.0):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        found = glob.glob(pattern)
        if found:
            return found[0]
        time.sleep(0.05)
    return None


def finish(proc, timeout=300):
    out, err = proc.communicate(timeout=timeout)
    lines = [line for line in err.decode("utf-8", "replace").splitlines() if line.strip()]
    print("   exit %d; stderr: %s" % (proc.returncode, " | ".join(lines)))
    return proc.returncode, lines, out.decode("utf-8", "replace")


def leftovers(folder):
    return sorted(n for n in os.listdir(folder) if n.endswith(".partial") or n.endswith(".lock"))


# the static engine (--static) at level 2 with far more increments than a second holds
STATIC_ARGS = ["--static", "--set", "mesh:level=2", "--set", "solver:static_increments=1000000"]
PATCH = "patch_compression_p1.nml"
COMPARE_ARGS = ["--set", "solver:compare_static=.true.", "--set", "solver:static_increments=1000000"]


def check_interrupt(t, sig, code, static=False):
    """An explicit run stops at the end of its step, the static engine before its next increment."""
    name = ("static_sig%d" if static else "sig%d") % sig
    folder = t.subdir(name)
    proc = start(t, folder, t.deck(LONG), STATIC_ARGS if static else LONG_ARGS)
    partial = wait_for(os.path.join(folder, "out.h5.*.partial"))
    t.require(partial is not None, name + ": " + "the run started writing its partial file")
    time.sleep(1.0)
    proc.send_signal(sig)
    rc, err, _ = finish(proc)
    t.check_equal(name, "exit code", code, rc)
    t.check_equal(name, "lines on stderr", 1, len(err))
    t.check(name, "the line says interrupted", bool(err) and "interrupted by" in err[0], "interrupted by ...",
            err[0] if err else "")
    t.check_equal(name, "no temporary or lock file left", [], leftovers(folder))
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "status", "interrupted", c2dtest.attr_str(f.attrs["status"]))
        steps = int(f.attrs["steps"])
        t.check(name, "stopped mid-run (steps or increments)", 0 < steps < 10 ** 6, "0 < steps < 1e6", steps)
        hist = f["history/step"][:]
        t.check_equal(name, "history flushed up to the stop (last sample = steps)", steps, int(hist[-1]))
        t.check(name, "/final/displacement present and finite", np.isfinite(f["final/displacement"][:]).all(),
                True, True)
    t.check(name, "sidecar written", os.path.exists(os.path.join(folder, "out.xmf")), True,
            os.path.exists(os.path.join(folder, "out.xmf")))


def check_force_unfinished(t, name, deck, args, sig, code, status):
    """--force over a good result by a run that does not reach its end (a signal, a blow-up): the
    good result and its sidecar stay byte for byte, the run's file is kept, complete and readable,
    at its temporary name with its status, and the one stderr line names it and the kept result."""
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, t.deck(UNIAXIAL), []))
    t.require(rc == 0, name + ": the first result exists")
    before = {n: sha(os.path.join(folder, n)) for n in ("out.h5", "out.xmf")}
    proc = start(t, folder, t.deck(deck), args + ["--force"])
    if sig is not None:
        t.require(wait_for(os.path.join(folder, "out.h5.%d.partial" % proc.pid)) is not None,
                  name + ": the --force run started writing")
        time.sleep(1.0)
        proc.send_signal(sig)
    rc, err, _ = finish(proc)
    err = [line for line in err if ": warning: " not in line]   # dt above the limit is warned about
    partial = "out.h5.%d.partial" % proc.pid
    t.check_equal(name, "exit code", code, rc)
    t.check_equal(name, "lines on stderr (besides warnings)", 1, len(err))
    t.check(name, "the line names the kept file and the kept result",
            bool(err) and partial in err[0] and "the existing out.h5 is kept" in err[0],
            partial + " ... the existing out.h5 is kept", err[0] if err else "")
    for n in before:
        t.check_equal(name, "existing %s unchanged (sha256)" % n, before[n], sha(os.path.join(folder, n)))
    t.check_equal(name, "only the run's file left beside the result", [partial], leftovers(folder))
    with h5py.File(os.path.join(folder, partial), "r") as f:
        t.check_equal(name, "the kept file's status", status, c2dtest.attr_str(f.attrs["status"]))
        t.check(name, "the kept file is complete (/final/displacement finite)",
                np.isfinite(f["final/displacement"][:]).all(), True, True)
    os.remove(os.path.join(folder, partial))


def check_interrupt_comparison(t, sig, code):
    """A signal during solver:compare_static, after the steps: the run's own file is finished and
    published as it would have been (status from the steps), without the comparison's attributes."""
    name = "compare_sig%d" % sig
    folder = t.subdir(name)
    proc = start(t, folder, t.deck(PATCH), COMPARE_ARGS)
    partial = wait_for(os.path.join(folder, "out.h5.*.partial"))
    t.require(partial is not None, name + ": " + "the run started writing its partial file")
    time.sleep(1.0)   # the patch's 230 steps take milliseconds; 10^6 static increments take seconds
    proc.send_signal(sig)
    rc, err, _ = finish(proc)
    t.check_equal(name, "exit code", code, rc)
    t.check_equal(name, "lines on stderr", 1, len(err))
    t.check(name, "the line says interrupted after the steps", bool(err) and "after the steps" in err[0],
            "interrupted by ... after the steps", err[0] if err else "")
    t.check_equal(name, "no temporary or lock file left", [], leftovers(folder))
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "status (the steps converged)", "converged", c2dtest.attr_str(f.attrs["status"]))
        t.check_equal(name, "no static_distance_energy", False, "static_distance_energy" in f.attrs)
        t.check_equal(name, "history flushed up to the end", int(f.attrs["steps"]), int(f["history/step"][-1]))
    t.check(name, "sidecar written", os.path.exists(os.path.join(folder, "out.xmf")), True,
            os.path.exists(os.path.join(folder, "out.xmf")))


def disk_full_sweep(t):
    """A --force run over a good result on a tmpfs with less and less room (4 KiB steps, from
    more than the run needs to none), explicit and --static: whichever write fails (history,
    /final, the status, the sidecar), the run either succeeds with a complete result or exits 2
    with one line naming ENOSPC and leaves the old result and its sidecar as they were; a
    partial file it keeps never claims a status it did not finish ('running' unless /final is
    whole)."""
    name = "disk_full_sweep"
    mnt = tempfile.mkdtemp(prefix="c2d_tmpfs_", dir=t.workdir)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=512k", "tmpfs", mnt],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if mounted.returncode != 0:
        print("SKIP %s: cannot mount a tmpfs here (%s)" % (name, mounted.stdout.decode("utf-8", "replace").strip()))
        return
    finals = ("displacement", "velocity", "stress", "reaction")
    try:
        for engine, extra in (("explicit", []), ("static", ["--static"])):
            deck = os.path.join(mnt, "deck.nml")
            shutil.copy(t.deck("baillet_sassi_2002_p1.nml"), deck)
            args = ["--set", "mesh:level=2"] + extra
            rc, err, _ = finish(start(t, mnt, "deck.nml", args))
            t.require(rc == 0, "%s %s: the first result exists" % (name, engine))
            good = {n: sha(os.path.join(mnt, n)) for n in ("out.h5", "out.xmf")}
            need = os.path.getsize(os.path.join(mnt, "out.h5")) + os.path.getsize(os.path.join(mnt, "out.xmf"))
            outcomes = {"ok": 0, "enospc": 0}
            free0 = shutil.disk_usage(mnt).free
            for room in range(need + 16384, -1, -4096):
                with open(os.path.join(mnt, "fill"), "wb") as fh:
                    fh.write(b"\0" * max(0, free0 - room))
                proc = start(t, mnt, "deck.nml", args + ["--force"])
                rc, err, _ = finish(proc)
                where = "%s %s room %d" % (name, engine, room)
                if rc == 0:
                    outcomes["ok"] += 1
                    with h5py.File(os.path.join(mnt, "out.h5"), "r") as f:
                        whole = c2dtest.attr_str(f.attrs["status"]) == "converged" and \
                            all(k in f["final"] for k in finals)
                    xmf = open(os.path.join(mnt, "out.xmf"), "rb").read()
                    if not (whole and xmf.rstrip().endswith(b"</Xdmf>")):
                        t.check(where, "exit 0: a complete result and sidecar", False, True, (whole, len(xmf)))
                    good = {n: sha(os.path.join(mnt, n)) for n in ("out.h5", "out.xmf")}
                else:
                    outcomes["enospc"] += 1
                    if not (rc == 2 and len(err) == 1 and "No space left on device" in err[0]):
                        t.check(where, "exit 2, one line naming ENOSPC", False, True, (rc, err))
                    now = {n: sha(os.path.join(mnt, n)) for n in ("out.h5", "out.xmf")}
                    if now != good:
                        t.check(where, "the old result and sidecar unchanged", False, True, True)
                    partial = os.path.join(mnt, "out.h5.%d.partial" % proc.pid)
                    if err and "creating the file" in err[0] and os.path.exists(partial):
                        # docs/output.md: an output that cannot even be created leaves no file
                        t.check(where, "an output that could not be created leaves no file", False, "no file",
                                "%s (%d bytes)" % (os.path.basename(partial), os.path.getsize(partial)))
                    if os.path.exists(partial):
                        try:
                            with h5py.File(partial, "r") as f:
                                st = c2dtest.attr_str(f.attrs["status"])
                                whole = "final" in f and all(k in f["final"] for k in finals)
                            if st != "running" and not whole:
                                t.check(where, "a kept partial says 'running' unless /final is whole", False,
                                        "running", st)
                        except (OSError, KeyError):
                            pass   # a failed metadata flush can leave it unreadable (HDF5 has no journal)
                        os.remove(partial)
                os.remove(os.path.join(mnt, "fill"))
                for n in os.listdir(mnt):
                    if n.endswith(".partial") or n.endswith(".lock"):
                        t.check(where, "no file left but a named partial", False, [], n)
                        os.remove(os.path.join(mnt, n))
            t.info(name, engine + " runs that succeeded / failed with ENOSPC", outcomes)
            t.check(name, engine + ": the sweep reached both outcomes", outcomes["ok"] > 0 and outcomes["enospc"] > 0,
                    True, outcomes)
            for n in os.listdir(mnt):
                os.remove(os.path.join(mnt, n))
    finally:
        subprocess.run(["umount", mnt])


NAMESPACE = ["unshare", "--pid", "--fork", "--mount-proc", "--kill-child"]


def pid_reuse(t):
    """PID reuse: in a PID namespace (a container) the solver is PID 1 in every run, so a run's
    temporary name OUT.h5.1.partial is an earlier run's. A run killed by SIGKILL leaves
    out.h5.1.partial (with, planted here, an earlier sidecar out.xmf.1.partial); the next run
    in a namespace must take another temporary name, succeed, and leave both files byte for
    byte (it did not create them, so it never removes them). A symbolic link planted under the
    sidecar's temporary name is never followed (the user's file it points to keeps its bytes)."""
    probe = subprocess.run(NAMESPACE + ["true"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if probe.returncode != 0:
        print("SKIP pid_reuse: cannot make a PID namespace here (%s)" % probe.stdout.decode("utf-8", "replace").strip())
        return

    def in_namespace(folder, deck, args):
        cmd = NAMESPACE + [t.exe, deck, "-o", "out.h5", "-q"] + list(args)
        print("-- start (cd %s && %s)" % (folder, " ".join(cmd)))
        return subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV,
                                start_new_session=True)

    name = "pid_reuse"
    folder = t.subdir(name)
    first = in_namespace(folder, t.deck(LONG), LONG_ARGS)
    partial = wait_for(os.path.join(folder, "out.h5.1.partial"))
    t.require(partial is not None, name + ": the first run (PID 1 in its namespace) writes out.h5.1.partial")
    time.sleep(1.0)
    os.killpg(first.pid, signal.SIGKILL)   # the solver and unshare: kill -9, nothing cleans up
    first.communicate()
    with open(os.path.join(folder, "out.xmf.1.partial"), "w") as fh:
        fh.write("<Xdmf>an earlier run's sidecar</Xdmf>\n")
    kept = {n: sha(os.path.join(folder, n)) for n in ("out.h5.1.partial", "out.xmf.1.partial")}
    rc, err, _ = finish(in_namespace(folder, t.deck(UNIAXIAL), []))
    t.check_equal(name, "the second run (PID 1 again) exit code", 0, rc)
    t.check_equal(name, "stderr lines", 0, len(err))
    for n in kept:
        t.check_equal(name, "the earlier run's %s unchanged (sha256)" % n, kept[n],
                      sha(os.path.join(folder, n)) if os.path.exists(os.path.join(folder, n)) else "missing")
    if os.path.exists(os.path.join(folder, "out.h5")):
        with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
            t.check_equal(name, "the second run's result in place", "converged", c2dtest.attr_str(f.attrs["status"]))
    else:
        t.check(name, "the second run's result in place", False, "out.h5", "missing")
    t.check_equal(name, "left beside the result: the earlier files only (no lock, no temporary of its own)",
                  sorted(kept), leftovers(folder))

    name = "pid_reuse_sidecar_link"
    folder = t.subdir(name)
    with open(os.path.join(folder, "precious.txt"), "w") as fh:
        fh.write("the user's data\n")
    before = sha(os.path.join(folder, "precious.txt"))
    os.symlink("precious.txt", os.path.join(folder, "out.xmf.1.partial"))
    rc, err, _ = finish(in_namespace(folder, t.deck(UNIAXIAL), []))
    t.check_equal(name, "exit code", 0, rc)
    t.check_equal(name, "precious.txt behind the planted link unchanged (sha256)", before,
                  sha(os.path.join(folder, "precious.txt")))
    t.check_equal(name, "the planted link left as it is", "precious.txt",
                  os.readlink(os.path.join(folder, "out.xmf.1.partial"))
                  if os.path.islink(os.path.join(folder, "out.xmf.1.partial")) else "not a link")
    t.check_equal(name, "out.xmf is the run's own regular file", True,
                  os.path.isfile(os.path.join(folder, "out.xmf")) and not os.path.islink(os.path.join(folder, "out.xmf")))
    t.check_equal(name, "left beside the result: the planted link only", ["out.xmf.1.partial"], leftovers(folder))


def publish_refused(t):
    """A file named like the output appears while a run writes (another program, a user; no
    --force): the run's move into place, which never replaces a file, fails. The run exits 2 with
    one line naming its temporary file; that file is kept, complete (the line says "the complete
    result stays in" it), the other file keeps its bytes, and the sidecar moved just before is
    taken back (it would describe the other file). Explicit and static engines."""
    for engine, args in (("explicit", ["--set", "mesh:level=2", "--set", "solver:tol_residual=1e-300",
                                       "--set", "solver:t_end=1.0", "--set", "solver:max_steps=200000"]),
                         ("static", ["--static", "--set", "mesh:level=2", "--set", "solver:static_increments=20000"])):
        name = "publish_refused_" + engine
        folder = t.subdir(name)
        proc = start(t, folder, t.deck(LONG), args)
        partial = wait_for(os.path.join(folder, "out.h5.%d.partial" % proc.pid))
        t.require(partial is not None, name + ": the run writes its partial file")
        with open(os.path.join(folder, "out.h5"), "w") as fh:
            fh.write("another program's file\n")
        theirs = sha(os.path.join(folder, "out.h5"))
        rc, err, _ = finish(proc)
        t.require(proc.poll() is not None, name + ": the run ended")
        t.check_equal(name, "exit code", 2, rc)
        t.check(name, "one line: File exists, the result stays in the partial file",
                len(err) == 1 and "File exists" in err[0] and "stays in " + os.path.basename(partial) in err[0],
                "one line '... File exists; the complete result stays in %s'" % os.path.basename(partial), err)
        t.check_equal(name, "the other out.h5 unchanged (sha256)", theirs, sha(os.path.join(folder, "out.h5")))
        t.check_equal(name, "no sidecar out.xmf describing the other file", False,
                      os.path.lexists(os.path.join(folder, "out.xmf")))
        t.check_equal(name, "left: the named partial file only (no lock)", [os.path.basename(partial)],
                      leftovers(folder))
        if os.path.exists(partial):
            with h5py.File(partial, "r") as f:
                t.check(name, "the kept file is complete (status set, /final/displacement finite)",
                        c2dtest.attr_str(f.attrs["status"]) != "running" and
                        np.isfinite(f["final/displacement"][:]).all(), "complete",
                        c2dtest.attr_str(f.attrs["status"]))


def body(t):
    quick = [t.deck(UNIAXIAL)]
    # ---- interrupts -------------------------------------------------------------------------
    check_interrupt(t, signal.SIGINT, 130)
    check_interrupt(t, signal.SIGTERM, 143)
    check_interrupt(t, signal.SIGINT, 130, static=True)
    check_interrupt(t, signal.SIGTERM, 143, static=True)
    check_interrupt_comparison(t, signal.SIGINT, 130)
    check_interrupt_comparison(t, signal.SIGTERM, 143)
    # ---- --force over a result by a run that does not reach its end: the result is kept -------
    check_force_unfinished(t, "force_sigterm", LONG, LONG_ARGS, signal.SIGTERM, 143, "interrupted")
    check_force_unfinished(t, "force_static_sigint", LONG, STATIC_ARGS, signal.SIGINT, 130, "interrupted")
    check_force_unfinished(t, "force_blow_up", "baillet_sassi_2002_p1.nml",
                           ["--set", "mesh:level=2", "--set", "solver:dt_factor=1.6",
                            "--set", "solver:allow_unstable=.true."], None, 2, "blow-up")

    # ---- kill -9 of a --force run over an existing result -----------------------------------
    name = "kill9"
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, quick[0], []))
    t.require(rc == 0, name + ": " + "the first result exists")
    h_before = sha(os.path.join(folder, "out.h5"))
    x_before = sha(os.path.join(folder, "out.xmf"))
    proc = start(t, folder, t.deck(LONG), LONG_ARGS + ["--force"])
    partial = wait_for(os.path.join(folder, "out.h5.%d.partial" % proc.pid))
    t.require(partial is not None, name + ": " + "the --force run started writing")
    time.sleep(2.5)   # past the first timed history flush (2 s)
    proc.kill()
    proc.wait()
    t.check_equal(name, "existing out.h5 unchanged (sha256)", h_before, sha(os.path.join(folder, "out.h5")))
    t.check_equal(name, "existing out.xmf unchanged (sha256)", x_before, sha(os.path.join(folder, "out.xmf")))
    t.check(name, "the killed run's partial file is kept", os.path.exists(partial), True, os.path.exists(partial))
    try:
        with h5py.File(partial, "r") as f:
            status = c2dtest.attr_str(f.attrs["status"])
            ncoord = f["mesh/coordinates"].shape[0]
            nhist = f["history/time"].shape[0]
        t.check_equal(name, "partial file status", "running", status)
        t.check(name, "partial file holds the mesh and flushed history", ncoord > 0 and nhist > 0,
                "> 0", (ncoord, nhist))
    except OSError as e:
        t.check(name, "partial file opens", False, "readable", str(e))
    # a later run to the same output is not blocked by the dead run (its flock died with it)
    rc, err, _ = finish(start(t, folder, quick[0], ["--force"]))
    t.check_equal(name, "a later --force run succeeds", 0, rc)
    # the killed run's stale lock (its process id) was taken over and removed; its partial kept
    t.check_equal(name, "after the later run: only the killed run's partial file left",
                  [os.path.basename(partial)], leftovers(folder))
    pid_reuse(t)
    publish_refused(t)

    # ---- --force onto a result another process holds open ------------------------------------
    name = "force_while_open"
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, quick[0], []))
    with h5py.File(os.path.join(folder, "out.h5"), "r") as held:
        u_old = held["final/displacement"][:]
        rc, err, _ = finish(start(t, folder, quick[0], ["--force", "--set", "dirichlet#3:values=-2e-3"]))
        t.check_equal(name, "--force run exit code", 0, rc)
        t.check(name, "the open handle still reads the old, intact file",
                np.array_equal(held["final/displacement"][:], u_old), True, True)
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_close(name, "new result in place: u_y at the top = -2e-3", -2e-3,
                      f["final/displacement"][:, 1].min(), rtol=1e-8, reason="the prescribed value")

    # ---- two runs aimed at one output -------------------------------------------------------
    name = "concurrent"
    folder = t.subdir(name)
    a = start(t, folder, t.deck(LONG), LONG_ARGS + ["--force"])
    t.require(wait_for(os.path.join(folder, "out.h5.%d.partial" % a.pid)) is not None, name + ": run A writes")
    before = sorted(os.listdir(folder))
    rc, err, _ = finish(start(t, folder, quick[0], ["--force"]))
    t.check_equal(name, "run B exit code", 1, rc)
    t.check(name, "run B refused with one line naming the lock", len(err) == 1 and "another run" in err[0],
            "one line '... being written by another run ...'", err)
    t.check_equal(name, "run B created nothing", before, sorted(os.listdir(folder)))
    a.send_signal(signal.SIGINT)
    rc, err, _ = finish(a)
    t.check_equal(name, "run A exit code (interrupted)", 130, rc)
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "the result is run A's, complete", "interrupted", c2dtest.attr_str(f.attrs["status"]))
    # started together: one valid result, every run either succeeded or was refused by the lock
    name = "concurrent_start"
    folder = t.subdir(name)
    procs = [start(t, folder, quick[0], ["--force"]) for _ in range(3)]
    results = [finish(p) for p in procs]
    ok = all(rc == 0 or (rc == 1 and len(err) == 1 and "another run" in err[0]) for rc, err, _ in results)
    t.check(name, "each run exit 0, or 1 refused by the lock", ok, True, [r[0] for r in results])
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "one valid result", "converged", c2dtest.attr_str(f.attrs["status"]))
    t.check_equal(name, "no temporary or lock file left", [], leftovers(folder))

    # ---- two outputs that share a sidecar name (run.h5, run.dat: run.xmf) --------------------
    name = "shared_sidecar"
    folder = t.subdir(name)
    a = start(t, folder, t.deck(LONG), LONG_ARGS, out="same.h5")
    t.require(wait_for(os.path.join(folder, "same.h5.%d.partial" % a.pid)) is not None, name + ": run A writes")
    before = sorted(os.listdir(folder))
    rc, err, _ = finish(start(t, folder, quick[0], ["--force"], out="same.dat"))
    t.check_equal(name, "run B (same.dat, sidecar same.xmf) exit code", 1, rc)
    t.check(name, "run B refused: the sidecar is being written", len(err) == 1 and "same.xmf" in err[0]
            and "another run" in err[0], "one line '... same.xmf ... another run ...'", err)
    t.check_equal(name, "run B created nothing", before, sorted(os.listdir(folder)))
    a.send_signal(signal.SIGINT)
    rc, err, _ = finish(a)
    t.check_equal(name, "run A exit code (interrupted)", 130, rc)
    x_before = sha(os.path.join(folder, "same.xmf"))
    rc, err, _ = finish(start(t, folder, quick[0], ["--force"], out="same.dat"))
    t.check_equal(name, "--force onto another output's sidecar: exit code", 1, rc)
    t.check(name, "refused, naming the file the sidecar describes", len(err) == 1 and "describes 'same.h5'" in err[0],
            "one line '... describes 'same.h5' ...'", err)
    t.check_equal(name, "same.xmf unchanged (sha256)", x_before, sha(os.path.join(folder, "same.xmf")))
    t.check_equal(name, "no temporary or lock file left", [], leftovers(folder))
    # --force without a sidecar: the old sidecar would describe the replaced file; it goes
    rc, err, _ = finish(start(t, folder, quick[0], ["--force", "--set", "output:xdmf=.false."], out="same.h5"))
    t.check_equal(name, "--force with xdmf off: exit code", 0, rc)
    t.check_equal(name, "the replaced result's sidecar removed", False, os.path.exists(os.path.join(folder, "same.xmf")))
    # a FIFO where the old sidecar would be is never opened (a read would block forever) nor removed
    os.mkfifo(os.path.join(folder, "same.xmf"))
    rc, err, _ = finish(start(t, folder, quick[0], ["--force", "--set", "output:xdmf=.false."], out="same.h5"),
                        timeout=60)
    t.check_equal(name, "--force with xdmf off beside a FIFO named like the sidecar: exit code", 0, rc)
    t.check_equal(name, "the FIFO left alone", True, os.path.exists(os.path.join(folder, "same.xmf")))
    os.remove(os.path.join(folder, "same.xmf"))
    # a symbolic link named like the old sidecar (to the user's own sidecar of same.h5, kept
    # elsewhere) is the user's: the run removes only a regular sidecar file, never a link
    os.mkdir(os.path.join(folder, "mine"))
    with open(os.path.join(folder, "mine", "same.xmf"), "w") as fh:
        fh.write('<DataItem Dimensions="1" Format="HDF">same.h5:/mesh/coordinates</DataItem>\n')
    mine = sha(os.path.join(folder, "mine", "same.xmf"))
    os.symlink(os.path.join("mine", "same.xmf"), os.path.join(folder, "same.xmf"))
    rc, err, _ = finish(start(t, folder, quick[0], ["--force", "--set", "output:xdmf=.false."], out="same.h5"))
    t.check_equal(name, "--force with xdmf off beside a link named like the sidecar: exit code", 0, rc)
    t.check_equal(name, "the link same.xmf left alone", os.path.join("mine", "same.xmf"),
                  os.readlink(os.path.join(folder, "same.xmf")) if os.path.islink(os.path.join(folder, "same.xmf"))
                  else "removed")
    t.check_equal(name, "the file it points to unchanged (sha256)", mine, sha(os.path.join(folder, "mine", "same.xmf")))
    t.check_equal(name, "no temporary or lock file left", [], leftovers(folder))

    # ---- a write that fails: file size limit (EFBIG) ----------------------------------------
    name = "write_fails"
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, quick[0], []))
    h_before = sha(os.path.join(folder, "out.h5"))
    snaps = ",".join("%g" % (k * 2.5e-7) for k in range(1, 17))
    args = ["--set", "mesh:level=3", "--set", "output:snapshot_times=" + snaps, "--force"]

    def fsize_limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)   # write() then fails with EFBIG
        resource.setrlimit(resource.RLIMIT_FSIZE, (300_000, 300_000))

    cmd = [t.exe, quick[0], "-o", "out.h5", "-q"] + args
    print("-- run (cd %s && %s) with RLIMIT_FSIZE = 300 kB" % (folder, " ".join(cmd)))
    proc = subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV,
                            preexec_fn=fsize_limit)
    rc, err, _ = finish(proc)
    t.check_equal(name, "exit code", 2, rc)
    t.check(name, "one line with the system's reason", len(err) == 1 and "File too large" in err[0],
            "one line '... File too large ...'", err)
    t.check_equal(name, "existing out.h5 unchanged (sha256)", h_before, sha(os.path.join(folder, "out.h5")))
    partial = os.path.join(folder, "out.h5.%d.partial" % proc.pid)
    t.check(name, "the partial file is named in the message", bool(err) and os.path.basename(partial) in err[0],
            os.path.basename(partial), err)
    try:
        with h5py.File(partial, "r") as f:
            nsnap = len(f["fields"]) if "fields" in f else 0
            t.check(name, "partial file readable with the mesh", f["mesh/coordinates"].shape[0] > 0, True, True)
            t.info(name, "snapshots on disk before the failure", nsnap)
    except OSError as e:
        t.check(name, "partial file opens", False, "readable", str(e))
    t.check_equal(name, "no lock file left", [], [n for n in leftovers(folder) if n.endswith(".lock")])

    # ---- a full disk: a small tmpfs, where the machine allows mounting one -------------------
    name = "disk_full"
    mnt = tempfile.mkdtemp(prefix="c2d_tmpfs_", dir=t.workdir)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", mnt],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if mounted.returncode != 0:
        print("SKIP disk_full: cannot mount a tmpfs here (%s)" %
              mounted.stdout.decode("utf-8", "replace").strip())
    else:
        try:
            shutil.copy(quick[0], os.path.join(mnt, "deck.nml"))
            rc, err, _ = finish(start(t, mnt, "deck.nml", args))
            t.check_equal(name, "exit code", 2, rc)
            t.check(name, "one line: No space left on device", len(err) == 1 and "No space left on device" in err[0],
                    "one line '... No space left on device ...'", err)
        finally:
            subprocess.run(["umount", mnt])
    disk_full_sweep(t)

    # ---- semantics ---------------------------------------------------------------------------
    name = "load_unload"
    folder = t.subdir(name)
    deck = os.path.join(t.here, "decks", "load_unload.nml")
    rc, err, out = finish(start(t, folder, deck, []))
    t.check_equal(name, "exit code", 0, rc)
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "converged (stress-free end state)", 1, int(f.attrs["converged"]))
        umax = float(np.abs(f["final/displacement"][:]).max())
        t.check_le(name, "max |u| at the end / peak 1e-3 mm", umax / 1e-3, 1e-6,
                   reason="the load is removed: the unique elastic equilibrium is u = 0")

    # the summary says why an unconverged run stopped
    for why, args in (("max_steps", ["--set", "solver:max_steps=100"]), ("t_end", ["--set", "solver:t_end=2.1e-6"])):
        name = "not_converged_" + why
        folder = t.subdir(name)
        rc, err, out = finish(start(t, folder, t.deck(PATCH), args))
        t.check_equal(name, "exit code", 0, rc)
        line = [l for l in out.splitlines() if l.strip().startswith("converged")]
        t.check(name, "the summary names the limit reached", bool(line) and ("NO: not converged, solver:%s = " % why)
                in line[0] and line[0].split("(")[0].rstrip().endswith("reached"), "NO: not converged, solver:%s = ... reached" % why, line)

    name = "snapshots_one_step"
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, quick[0], ["--set", "output:snapshot_times=1e-12,2e-12,5e-7"]))
    t.check_equal(name, "exit code", 0, rc)
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        groups = sorted(f["fields"].keys(), key=int)
        dt = float(f.attrs["dt"])
    t.check_equal(name, "snapshot groups (times 1e-12 and 2e-12 share step 1)",
                  ["1", str(int(np.ceil(5e-7 / dt - 1e-9)))], groups)

    name = "dt_factor_huge"
    folder = t.subdir(name)
    # t_end far off: the default (10 x the ramp, 2e-5 s) is reached by the first step (t = 1.8e21 s),
    # and the run ends there, before the energy runs away at step 2
    rc, err, out = finish(start(t, folder, quick[0], ["--set", "solver:dt_factor=1e29",
                                                      "--set", "solver:allow_unstable=.true.",
                                                      "--set", "solver:t_end=1e30"]))
    t.check_equal(name, "exit code (blow-up)", 2, rc)
    t.check(name, "summary printed (no formatting crash)", "dt / dt_critical" in out and "End of record" not in out
            + " ".join(err), True, False)
    with h5py.File(os.path.join(folder, "out.h5"), "r") as f:
        t.check_equal(name, "status", "blow-up", c2dtest.attr_str(f.attrs["status"]))

    name = "obstacle_normal_away"
    folder = t.subdir(name)
    rc, err, _ = finish(start(t, folder, t.deck("patch_compression_p1.nml"),
                              ["--set", "contact:obstacle_normal=0,-1", "--set", "solver:max_steps=20"]))
    t.check_equal(name, "exit code", 0, rc)
    t.check(name, "warning names obstacle_normal", any("warning" in e and "obstacle_normal" in e and "away" in e
                                                       for e in err), True, err)


if __name__ == "__main__":
    c2dtest.Test("faults: interrupts, kill -9, concurrent runs, write failures, semantics").main(body)
