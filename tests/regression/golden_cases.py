"""The golden end states: which decks, how they are run, what is stored, how a build is named.

Shared by `test_golden.py` (the check) and `golden/regenerate.py` (the only writer of
`golden/golden.npz` and `golden/golden.json`). A golden file guards a refactoring against change:
its numbers are the program's own output, stored on purpose, and say nothing about physics
(tests/README.md, "Golden end states").
"""
import os
import platform
import re
import subprocess

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
GOLDEN_DIR = os.path.join(HERE, "golden")
NPZ = os.path.join(GOLDEN_DIR, "golden.npz")
JSON = os.path.join(GOLDEN_DIR, "golden.json")

# name, deck, extra arguments, OMP threads of the test's run. Every run of the generator uses one
# thread; the level-4 paper deck (10 241 nodes, above the 4096-node threshold where the kernels go
# parallel) is checked with two threads against that one-thread reference: same bits.
CASES = [
    ("baillet_sassi_2002_p1_level3", "baillet_sassi_2002_p1.nml", ["--set", "mesh:level=3"], 1),
    ("baillet_sassi_2002_p0_level3", "baillet_sassi_2002_p0.nml", ["--set", "mesh:level=3"], 1),
    ("patch_compression_p1", "patch_compression_p1.nml", [], 1),
    ("patch_compression_p0", "patch_compression_p0.nml", [], 1),
    ("tresca_sliding_p1", "tresca_sliding_p1.nml", [], 1),
    ("coulomb_sliding_p1", "coulomb_sliding_p1.nml", [], 1),
    ("coulomb_sliding_p0", "coulomb_sliding_p0.nml", [], 1),
    ("hertz_cylinder_p1", "hertz_cylinder_p1.nml", [], 1),
    ("impact_bar_p1", "impact_bar_p1.nml", [], 1),
    ("lame_cavity_p1", "lame_cavity_p1.nml", [], 1),
    ("baillet_sassi_2002_p1_level4_2threads", "baillet_sassi_2002_p1.nml", ["--set", "mesh:level=4"], 2),
]

# scalars stored beside the displacement: root attributes, and the total contact forces of the
# end state (sums of /final/contact/normal_force and tangential_force)
INT_ATTRS = ("steps", "node_count", "element_count")
REAL_ATTRS = ("dt", "final_time")


def end_state(h5path):
    """The stored quantities of one output file: (displacement array, scalars dict)."""
    with h5py.File(h5path, "r") as f:
        u = f["final/displacement"][()]
        s = {k: int(f.attrs[k]) for k in INT_ATTRS}
        s.update({k: float(f.attrs[k]) for k in REAL_ATTRS})
        status = f.attrs["status"]
        s["status"] = status.decode() if isinstance(status, bytes) else str(status)
        s["normal_force_total"] = float(np.sum(f["final/contact/normal_force"][()]))
        s["tangential_force_total"] = float(np.sum(f["final/contact/tangential_force"][()]))
    return u, s


def build_identity(exe):
    """What decides the round-off of a run: the build's flags and SIMD lanes (`--version`), and,
    when the flags contain -march=native, the instruction set the compiler picks on this CPU.

    Two builds with the same identity do the same arithmetic in the same order; others may differ
    at round-off (fused multiply-adds, 8 or 4 lanes, vectorised reductions)."""
    out = subprocess.run([exe, "--version"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         check=True).stdout.decode()
    built = next((line for line in out.splitlines() if line.startswith("built with")), out.strip())
    ident = {"build": built, "machine": platform.machine()}
    if "-march=native" in built:
        ident["native_arch"] = native_arch()
    return ident


def native_arch():
    """What gfortran's -march=native resolves to on this CPU: -march, -mtune and the enabled
    vector ISA options (AVX, AVX2, AVX-512*, FMA), e.g. `znver3 tune znver3: avx avx2 ... fma`.
    (gfortran 12 names a Zen 4 `znver3` and adds the AVX-512 options, so -march alone is not
    enough.)"""
    try:
        out = subprocess.run(["gfortran", "-march=native", "-Q", "--help=target"], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL).stdout.decode()
    except OSError:
        return "unknown (gfortran not found)"
    march = re.search(r"^\s*-march=\s*(\S+)", out, re.M)
    mtune = re.search(r"^\s*-mtune=\s*(\S+)", out, re.M)
    isa = sorted(m.group(1) for m in re.finditer(r"^\s*-m((?:avx|fma)\S*)\s+\[enabled\]", out, re.M))
    return "%s tune %s: %s" % (march.group(1) if march else "?", mtune.group(1) if mtune else "?",
                               " ".join(isa))
