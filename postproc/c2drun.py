"""Run contact2d from Python scripts (studies, sweeps, benchmarks).

    from c2drun import find_exe, run, strip_group, parse_levels, out_dir
    res = run(find_exe(), "inputs/baillet_sassi_2002_p1.nml", "out.h5", {"mesh:level": 3})
    res.returncode, res.seconds, res.stderr
    parse_levels("0-2") == parse_levels("0,1,2") == [0, 1, 2]   # ValueError (one line) otherwise
    out_dir("study/x", "hertz_study.py")   # mkdir -p, or one line on stderr and exit 2

Only the standard library is needed.
"""
import os
import re
import subprocess
import sys
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


def parse_levels(text):
    """Mesh levels of a study's command line: 'a-b' (a range), 'a,b,c' or 'a'; sorted, distinct.
    ValueError with a one-line message otherwise."""
    t = str(text).replace(" ", "")
    try:
        if "-" in t:
            a, b = t.split("-")
            out = list(range(int(a), int(b) + 1))
        else:
            out = sorted({int(x) for x in t.split(",")})
    except ValueError:
        raise ValueError(f"'{text}' is not a list of mesh levels (e.g. 0-2, 0,1,2 or 2)") from None
    if not out:
        raise ValueError(f"'{text}' is an empty range of mesh levels (write the smaller level first)")
    if out[0] < 0:
        raise ValueError(f"'{text}': mesh levels are >= 0")
    return out


def levels_or_exit(text, option, prog):
    """parse_levels, or one line on stderr naming the option and exit status 2."""
    try:
        return parse_levels(text)
    except ValueError as exc:
        print(f"{prog}: refused: {option} {exc}", file=sys.stderr)
        sys.exit(2)


def out_dir(path, prog):
    """Create the study folder path (and its parents); one line on stderr and exit 2 if it cannot be."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        print(f"{prog}: refused: --out {p} exists and is not a folder", file=sys.stderr)
        sys.exit(2)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(f"{prog}: refused: --out {p}: {exc.strerror or exc}", file=sys.stderr)
        sys.exit(2)
    return p


def strip_group(deck_text, group):
    """Deck text without the namelist group &group ... / (e.g. to drop &contact)."""
    return re.sub(r"(?ims)^\s*&" + group + r"\b.*?^[^!\n]*?/\s*$", "", deck_text)
