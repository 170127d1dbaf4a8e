"""The set-up command .ci/bootstrap: what it builds for each action, and that it says what it does.

.ci/bootstrap is copied into an empty stand-in repository (it works from its own location), with
stand-ins for dpkg-query (every package installed), cmake, ctest and the program on PATH that
record their arguments; the stand-in `cmake --build` prints 100 lines of make-style progress and
creates bin/contact2d. Checked (a fresh-machine fault: `run` was silent for 6 minutes on a fresh machine while
it built every unit-test executable before a 1.1 s run):
- `build` and `run` build only the program's targets (--target contact2d contact2d-solver), `test`
  builds everything (no --target) and runs ctest;
- a line per stage (checking packages, configuring, building, running) and the build's progress
  condensed to one line per 10 % (at most 11 lines for 100 progress lines), each with the step it
  is at; the build's full output in build.build.log;
- `run` writes runs/<deck stem>.h5 and a second run the next free name, -2.h5 (nothing overwritten);
- a failing build stops with a non-zero status and shows the end of the log.
Exit status 0 when every check holds, 1 otherwise (the failed checks listed).
"""
import os
import shutil
import stat
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
BOOTSTRAP = os.path.join(HERE, "..", "..", ".ci", "bootstrap")

FAKE_CMAKE = r"""#!/usr/bin/env bash
echo "cmake $*" >> "$FAKE_LOG"
if [ "$1" = --build ]; then
  for i in $(seq 1 100); do
    echo "[$(printf '%3d' $i)%] Building Fortran object CMakeFiles/lib.dir/src/area/file_$i.f90.o"
  done
  [ -n "${FAKE_BUILD_FAILS:-}" ] && { echo "Error: fake compile error in file_100.f90"; exit 2; }
  mkdir -p "$2/bin"
  printf '#!/usr/bin/env bash\necho "contact2d $*" >> "$FAKE_LOG"\nfor ((i = 1; i <= $#; i++)); do\n  if [ "${!i}" = -o ]; then j=$((i + 1)); echo h5 > "${!j}"; fi\ndone\n' > "$2/bin/contact2d"
  chmod +x "$2/bin/contact2d"
fi
exit 0
"""
FAKE_CTEST = """#!/usr/bin/env bash
echo "ctest $*" >> "$FAKE_LOG"
"""
FAKE_DPKG = """#!/usr/bin/env bash
printf 'install ok installed'
"""

problems = []


def check(ok, what, detail=""):
    print("%s %s%s" % ("PASS" if ok else "FAIL", what, (": " + detail) if detail and not ok else ""))
    if not ok:
        problems.append(what)


def write_exe(path, text):
    with open(path, "w") as f:
        f.write(text)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        repo = os.path.join(tmp, "repo")
        os.makedirs(os.path.join(repo, ".ci"))
        os.makedirs(os.path.join(repo, "inputs"))
        shutil.copy(BOOTSTRAP, os.path.join(repo, ".ci", "bootstrap"))
        open(os.path.join(repo, "inputs", "baillet_sassi_2002_p1.nml"), "w").close()
        fake = os.path.join(tmp, "bin")
        os.makedirs(fake)
        write_exe(os.path.join(fake, "cmake"), FAKE_CMAKE)
        write_exe(os.path.join(fake, "ctest"), FAKE_CTEST)
        write_exe(os.path.join(fake, "dpkg-query"), FAKE_DPKG)
        log = os.path.join(tmp, "calls.log")
        env = {**os.environ, "PATH": fake + os.pathsep + os.environ["PATH"], "FAKE_LOG": log, "JOBS": "2"}
        for k in ("BUILD_TYPE", "BUILD_DIR", "CMAKE_ARGS"):
            env.pop(k, None)

        def bootstrap(action, **extra):
            if os.path.exists(log):
                os.remove(log)
            proc = subprocess.run([os.path.join(repo, ".ci", "bootstrap"), action], cwd=tmp,
                                  env={**env, **extra}, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  universal_newlines=True, timeout=120)
            calls = open(log).read().splitlines() if os.path.exists(log) else []
            print("-- .ci/bootstrap %s: exit %d\n%s" % (action, proc.returncode, proc.stdout))
            return proc, calls

        for action in ("build", "run", "test"):
            proc, calls = bootstrap(action)
            check(proc.returncode == 0, "%s: exit 0" % action, str(proc.returncode))
            builds = [c for c in calls if c.startswith("cmake --build")]
            check(len(builds) == 1, "%s: one cmake --build" % action, str(builds))
            want = " --target all" if action == "test" else " --target contact2d contact2d-solver"
            check(len(builds) == 1 and builds[0].endswith(want), "%s: builds%s" % (action, want), str(builds))
            out = proc.stdout.splitlines()
            for stage in ("checking Debian packages", "configuring the Release build", "building "):
                check(any(line.startswith("bootstrap: " + stage) for line in out),
                      "%s: a line 'bootstrap: %s...'" % (action, stage))
            progress = [line for line in out if line.startswith("bootstrap:  ") and " % " in line]
            check(1 <= len(progress) <= 11, "%s: the build's 100 progress lines condensed to 1..11" % action,
                  "%d lines" % len(progress))
            check(all("file_" in line for line in progress), "%s: each progress line names its step" % action)
            with open(os.path.join(repo, "build.build.log")) as f:
                check(f.read().count("Building Fortran object") == 100,
                      "%s: the full build output in build.build.log" % action)
            if action == "run":
                check(any(c.startswith("contact2d inputs/baillet_sassi_2002_p1.nml -o runs/baillet_sassi_2002_p1.h5")
                          for c in calls), "run: the default deck to runs/baillet_sassi_2002_p1.h5", str(calls))
                check(any(line.startswith("bootstrap: running inputs/baillet_sassi_2002_p1.nml") for line in out),
                      "run: a line before the run")
            if action == "test":
                check(any(c.startswith("ctest --test-dir build") for c in calls), "test: runs ctest", str(calls))
        proc, calls = bootstrap("run")
        check(any(c.endswith("-o runs/baillet_sassi_2002_p1-2.h5") for c in calls),
              "a second run writes runs/baillet_sassi_2002_p1-2.h5", str(calls))
        proc, calls = bootstrap("build", FAKE_BUILD_FAILS="1")
        check(proc.returncode != 0, "a failing build: non-zero exit", str(proc.returncode))
        check("fake compile error" in proc.stdout, "a failing build: the end of the log is shown")
    print("ci bootstrap test: %s" % ("FAILED: " + "; ".join(problems) if problems else "OK"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
