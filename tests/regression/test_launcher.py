"""Regression: the launcher `contact2d` sets libgomp's short spin before the solver
loads, unless the user chose a wait or a binding, and starts `contact2d-solver` once, with the
same arguments and process id.

libgomp reads GOMP_SPINCOUNT when it is loaded and prints what it read under
OMP_DISPLAY_ENV=verbose, so the solver's own report is the evidence: one report (the launcher
does not load libgomp, the solver is loaded once) with GOMP_SPINCOUNT = '2000' by default, and
the user's value or libgomp's default when the user set OMP_WAIT_POLICY, GOMP_SPINCOUNT,
OMP_PROC_BIND, OMP_PLACES or GOMP_CPU_AFFINITY. A launcher copied away from its solver refuses
with one line naming the solver it looked for.
"""
import os
import re
import shutil
import subprocess

import c2dtest

SPIN = "2000"   # the launcher's documented spin count (docs/performance.md, README)
USER_VARS = ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "OMP_PROC_BIND", "OMP_PLACES", "GOMP_CPU_AFFINITY")


def launch(exe, args, extra_env, cwd):
    env = {k: v for k, v in os.environ.items() if k not in USER_VARS}
    env.update({"OMP_DISPLAY_ENV": "verbose", "OMP_NUM_THREADS": "2"})
    env.update(extra_env)
    proc = subprocess.run([exe] + args, cwd=cwd, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=60)
    err = proc.stderr.decode("utf-8", "replace")
    spins = re.findall(r"GOMP_SPINCOUNT = '([^']*)'", err)
    return proc.returncode, proc.stdout.decode("utf-8", "replace"), err, spins


def body(t):
    cwd = t.subdir("runs")
    code, out, err, spins = launch(t.exe, ["--version"], {}, cwd)
    t.check_equal("default", "exit status", 0, code)
    t.check("default", "version line", out.startswith("contact2d "), "contact2d <version>", repr(out[:40]))
    t.check_equal("default", "libgomp reports (solver loaded once, launcher without OpenMP)", 1,
                  err.count("OPENMP DISPLAY ENVIRONMENT BEGIN"))
    t.check_equal("default", "GOMP_SPINCOUNT the solver's libgomp read", [SPIN], spins)

    user = {"OMP_WAIT_POLICY": "passive", "GOMP_SPINCOUNT": "12345", "OMP_PROC_BIND": "false",
            "OMP_PLACES": "threads", "GOMP_CPU_AFFINITY": "0-1"}
    for name, value in user.items():
        code, out, err, spins = launch(t.exe, ["--version"], {name: value}, cwd)
        where = "%s=%s" % (name, value)
        t.check_equal(where, "exit status", 0, code)
        t.check("%s=%s" % (name, value), "GOMP_SPINCOUNT left to the user / libgomp",
                len(spins) == 1 and spins[0] != SPIN, "one report, not '%s'" % SPIN, spins)
        if name == "GOMP_SPINCOUNT":
            t.check_equal(where, "the user's GOMP_SPINCOUNT", [value], spins)

    # arguments reach the solver byte for byte (blanks inside and at the end)
    odd = "no such  deck .nml "
    code, out, err, spins = launch(t.exe, [odd], {"OMP_DISPLAY_ENV": "false"}, cwd)
    t.check_equal("odd argument", "exit status", 1, code)
    t.check("odd argument", "the solver names the argument exactly", "'%s'" % odd in err,
            repr(odd), err.strip())

    # a launcher away from its solver: one line naming the solver it looked for, exit 1
    alone = t.subdir("alone")
    shutil.copy2(t.exe, os.path.join(alone, "contact2d"))
    code, out, err, spins = launch(os.path.join(alone, "contact2d"), ["--version"], {"OMP_DISPLAY_ENV": "false"}, alone)
    lines = [line for line in err.splitlines() if line.strip()]
    t.check_equal("alone", "exit status", 1, code)
    t.check("alone", "one error line naming the missing solver",
            len(lines) == 1 and lines[0].startswith("contact2d: error:")
            and os.path.join(alone, "contact2d-solver") in lines[0],
            "one line naming %s" % os.path.join(alone, "contact2d-solver"), lines)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
