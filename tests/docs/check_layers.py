#!/usr/bin/env python3
"""The source folders are layers: a module uses only modules of its own folder or of the folders
before it in LAYERS (docs/architecture.md, "Layers"). Fails, naming each upward use, when a
Fortran `use contact2d_...` crosses the order the wrong way, and when a source file (Fortran or
C) sits in a folder that is not a layer. The calls of the C files are not checked.

    check_layers.py SOURCE_DIR
"""
import re
import sys
from pathlib import Path

#: the folders of src/, lowest first (docs/architecture.md lists the same order)
LAYERS = ("common", "model", "input", "kernels", "contact", "solvers", "output", "app")

USE = re.compile(r"^\s*use\s*(?:,\s*(?:non_)?intrinsic\s*::\s*|::\s*)?(contact2d_\w+)", re.I | re.M)
MODULE = re.compile(r"^\s*module\s+(?!procedure\b)(contact2d_\w+)\s*$", re.I | re.M)


def layer_of(path, src):
    return path.relative_to(src).parts[0]


def main(argv):
    src = Path(argv[1]) / "src"
    problems = []
    owner = {}   # module name -> layer
    files = sorted(p for p in src.rglob("*.f90"))
    for p in files:
        layer = layer_of(p, src)
        if layer not in LAYERS:
            problems.append(f"{p.relative_to(src.parent)}: folder '{layer}' is not a layer {LAYERS}")
            continue
        for m in MODULE.findall(p.read_text()):
            owner[m.lower()] = layer
    for p in files:
        layer = layer_of(p, src)
        if layer not in LAYERS:
            continue
        for m in USE.findall(p.read_text()):
            used = owner.get(m.lower())
            if used is None:
                continue   # generated at configure time (build config) or a program
            if LAYERS.index(used) > LAYERS.index(layer):
                problems.append(f"{p.relative_to(src.parent)} ({layer}) uses {m} ({used}): an upward use")
    for p in sorted(src.rglob("*.c")):
        if layer_of(p, src) not in LAYERS:
            problems.append(f"{p.relative_to(src.parent)}: folder '{layer_of(p, src)}' is not a layer {LAYERS}")
    for line in problems:
        print("layers: " + line)
    print(f"layers: {len(files)} Fortran files in {len(LAYERS)} layers, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
