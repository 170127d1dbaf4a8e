"""Run contact2d from Python scripts (studies, sweeps, benchmarks).

    from contact2d.runner import find_exe, run, strip_group, parse_levels, out_dir
    res = run(find_exe(), "inputs/baillet_sassi_2002_p1.nml", "out.h5", {"mesh:level": 3})
    res.returncode, res.seconds, res.stderr
    parse_levels("0-2") == parse_levels("0,1,2") == [0, 1, 2]   # ValueError (one line) otherwise
    out_dir("study/x", "hertz_study.py")   # mkdir -p, or one line on stderr and exit 2

run(..., reuse=True) keeps an existing output only when reuse_problem() finds nothing against it:
a finished contact2d run (status in FINISHED, per method) of the same deck text, by the same
method, whose effective deck holds every value of `sets` (the &output group excepted: it does not
change the results); otherwise the run is redone and one line says why. reference_problem() is
the same question for a GetFEM reference (contact2d.getfem_reference, contact2d.getfem_coulomb) of a
contact2d output, and keep_reference() asks it for --reuse and says why a reference is remade.

Only the standard library is needed, and h5py (contact2d.h5) for reuse.
"""
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent   # postproc/contact2d/runner.py: the repository


def find_exe(explicit=None):
    """The contact2d executable: explicit path, $CONTACT2D, or build/bin/contact2d."""
    for cand in (explicit, os.environ.get("CONTACT2D"), ROOT / "build" / "bin" / "contact2d"):
        if cand and Path(cand).is_file():
            return str(Path(cand).resolve())
    raise SystemExit("contact2d executable not found: build it (.ci/bootstrap build) or pass --exe")


FINISHED = {"explicit": ("converged", "not converged", "dynamic", "no convergence test"),
            "static": ("converged",)}


@dataclass
class Result:
    returncode: int
    seconds: float
    stdout: str
    stderr: str
    output: str
    reused: bool = False


def _fmt(value):
    if isinstance(value, (list, tuple)):
        return ", ".join(_fmt(v) for v in value)
    if isinstance(value, bool):
        return ".true." if value else ".false."
    if isinstance(value, str):
        return "'" + value + "'"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _same_value(want, have):
    if isinstance(want, (list, tuple)) or isinstance(have, list):
        want = want if isinstance(want, (list, tuple)) else [want]
        have = have if isinstance(have, list) else [have]
        return len(want) == len(have) and all(_same_value(a, b) for a, b in zip(want, have))
    if isinstance(want, bool) or isinstance(have, bool):
        return want is have
    if isinstance(want, str) or isinstance(have, str):
        return str(want).strip().lower() == str(have).strip().lower()
    a, b = float(want), float(have)
    return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))


def _root_attrs(path, needs=()):
    """An HDF5 file's root attributes as text, or None when it cannot be read or lacks a dataset of
    `needs` (written last: a file cut short has not got it)."""
    from .h5 import Run   # h5py only where a file is read
    try:
        with Run(path) as run:
            if not all(run.has(name) for name in needs):
                return None
            return {k: str(run.attr(k)) for k in run.attrs}
    except OSError:
        return None


def reuse_problem(output, deck, sets=None, method="explicit", statuses=None):
    """None when output is a finished run that run(deck, output, sets) would make again, else why not
    (a few words). statuses: the accepted final statuses (default FINISHED[method])."""
    from .h5 import parse_effective_deck   # h5py only where a file is read

    attrs = _root_attrs(output)
    if attrs is None:
        return "not a readable HDF5 file"
    if attrs.get("program", "") != "contact2d":
        return "not a contact2d output file"
    status = attrs.get("status", "?")
    if status not in (statuses or FINISHED[method]):
        return f"status '{status}'"
    if attrs.get("method", "?") != method:
        return f"method '{attrs.get('method', '?')}', not '{method}'"
    try:
        deck_text = Path(deck).read_text()
    except OSError:
        deck_text = None
    if deck_text is None or attrs.get("deck", "") != deck_text:
        return f"made from another text of {Path(deck).name}"
    eff = parse_effective_deck(attrs.get("effective_deck", ""))
    for key, want in (sets or {}).items():
        group, _, var = key.partition(":")
        if group.lower() == "output":
            continue
        name, _, index = group.lower().partition("#")
        g = eff.get(name)
        if isinstance(g, list):        # dirichlet#2, traction (the index may be left out for one)
            i = int(index or 1) - 1
            g = g[i] if 0 <= i < len(g) else None
        have = g.get(var.lower()) if isinstance(g, dict) else None
        if have is None or not _same_value(want, have):
            return f"{key} = {have if have is not None else '?'}, not {_fmt(want)}"
    return None


def reference_problem(ref, source, program="getfem_reference", **want):
    """None when ref is a complete, converged `program` reference of the problem of the contact2d
    output `source` (the same effective deck) whose root attributes hold `want` (e.g.
    friction='tresca'), else why not (a few words)."""
    attrs = _root_attrs(ref, needs=("final/displacement",))
    if attrs is None:
        return "not a complete HDF5 reference file"
    if attrs.get("program") != program:
        return f"program '{attrs.get('program', '?')}', not '{program}'"
    if attrs.get("status") != "converged":
        return f"status '{attrs.get('status', '?')}'"
    src = _root_attrs(source) or {}
    if attrs.get("effective_deck") != src.get("effective_deck", "?"):
        return f"made for another problem than {source}"
    for key, value in want.items():
        if attrs.get(key) != str(value):
            return f"{key} '{attrs.get(key, '?')}', not '{value}'"
    return None


def keep_reference(ref, source, reuse, program="getfem_reference", **want):
    """With reuse, True when reference_problem() accepts ref; otherwise False (ref is to be made),
    with one line saying why when ref exists."""
    if not reuse:
        return False
    why = reference_problem(ref, source, program, **want)
    if why is not None and Path(ref).exists():
        print(f"recomputing {ref}: {why}", flush=True)
    return why is None


def run(exe, deck, output, sets=None, threads=None, reuse=False, timeout=None, static=False):
    """Run one deck; sets maps 'group:variable' to a Python value; static adds --static. With
    reuse=True an existing output that reuse_problem() accepts is kept and the run skipped
    (returncode 0, reused True); any other existing file is rerun, with one line saying why."""
    output = str(output)
    if reuse and Path(output).is_file():
        why = reuse_problem(output, deck, sets, method="static" if static else "explicit")
        if why is None:
            return Result(0, 0.0, "", "", output, reused=True)
        print(f"rerunning {output}: {why}", flush=True)
    args = [exe, str(deck), "-q", "-o", output, "--force"] + (["--static"] if static else [])
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


def out_dir(path, prog, option="--out"):
    """Create the study folder path (and its parents) given as `option`; one line on stderr and exit 2
    if it cannot be."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        print(f"{prog}: refused: {option} {p} exists and is not a folder", file=sys.stderr)
        sys.exit(2)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        print(f"{prog}: refused: {option} {p}: {exc.strerror or exc}", file=sys.stderr)
        sys.exit(2)
    return p


def strip_group(deck_text, group):
    """Deck text without the namelist group &group ... / (e.g. to drop &contact)."""
    return re.sub(r"(?ims)^\s*&" + group + r"\b.*?^[^!\n]*?/\s*$", "", deck_text)


if __name__ == "__main__":
    print("contact2d.runner is a module, not a script (docs/postproc.md): it is used by "
          "the study scripts (postproc/*_study.py, bench_*.py, ...)", file=sys.stderr)
    sys.exit(2)
