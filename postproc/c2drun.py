"""Run contact2d from Python scripts (studies, sweeps, benchmarks).

    from c2drun import find_exe, run, strip_group
    res = run(find_exe(), "inputs/baillet_sassi_2002_p1.nml", "out.h5", {"mesh:level": 3})
    res.returncode, res.seconds, res.stderr

Only the standard library is needed.
"""
import os
import re
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def find_exe(explicit=None):
    """The contact2d executable: explicit path, $CONTACT2D, or build/bin/contact2d."""
    for cand in (explicit, os.environ.get("CONTACT2D"), ROOT / "build" / "bin" / "contact2d"):
        if cand and Path(cand).is_file():
            return str(Path(cand).resolve())
    raise SystemExit("contact2d executable not found: build it (.ci/bootstrap build) or pass --exe")


@dataclass
class Result:
    returncode: int
    seconds: float
    stdout: str
    stderr: str
    output: str


def _fmt(value):
    if isinstance(value, bool):
        return ".true." if value else ".false."
    if isinstance(value, str):
        return "'" + value + "'"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def run(exe, deck, output, sets=None, threads=None, reuse=False, timeout=None):
    """Run one deck; sets maps 'group:variable' to a Python value. With reuse=True an existing
    output file from an earlier, finished run is kept and the run skipped (returncode 0)."""
    output = str(output)
    if reuse and Path(output).is_file():
        return Result(0, 0.0, "", "", output)
    args = [exe, str(deck), "-q", "-o", output, "--force"]
    for key, value in (sets or {}).items():
        args += ["--set", f"{key}={_fmt(value)}"]
    env = dict(os.environ)
    if threads is not None:
        env["OMP_NUM_THREADS"] = str(threads)
    t0 = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True, env=env, timeout=timeout)
    return Result(proc.returncode, time.perf_counter() - t0, proc.stdout, proc.stderr, output)


def strip_group(deck_text, group):
    """Deck text without the namelist group &group ... / (e.g. to drop &contact)."""
    return re.sub(r"(?ims)^\s*&" + group + r"\b.*?^[^!\n]*?/\s*$", "", deck_text)
