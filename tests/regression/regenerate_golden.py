#!/usr/bin/env python3
"""Write the golden end states (tests/regression/golden/) from the current program. On purpose only.

    /usr/bin/python3 tests/regression/regenerate_golden.py --exe build/bin/contact2d [--force]

Runs every case of golden_cases.CASES with OMP_NUM_THREADS=1 in a temporary folder and stores
the final displacement (golden.npz) and the scalars, the commands and the build identity
(golden.json). Refuses to replace existing golden files without --force: regenerating is
legitimate only when a change is meant to alter the arithmetic (tests/README.md, "Golden end
states"), never to make test_golden pass after a refactoring that should have kept the bits.
"""
import argparse
import io
import json
import os
import subprocess
import sys
import tempfile
import zipfile

import numpy as np

import golden_cases as gc


def write_npz(fh, arrays):
    """np.savez_compressed with fixed zip timestamps and order: the same arrays give the same
    bytes, so regenerating without a change of the results leaves git with nothing to commit."""
    with zipfile.ZipFile(fh, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name in sorted(arrays):
            info = zipfile.ZipInfo(name + ".npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            with zf.open(info, "w", force_zip64=True) as out:
                np.lib.format.write_array(out, np.ascontiguousarray(arrays[name]), allow_pickle=False)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True, help="the contact2d executable (a Release build)")
    ap.add_argument("--inputs", default=os.path.join(gc.HERE, os.pardir, os.pardir, "inputs"),
                    help="the inputs/ folder (default: the repository's)")
    ap.add_argument("--force", action="store_true", help="replace existing golden files")
    args = ap.parse_args()
    existing = [p for p in (gc.NPZ, gc.JSON) if os.path.exists(p)]
    if existing and not args.force:
        sys.exit("regenerate_golden: %s exist(s); regenerating is for a change meant to alter the "
                 "arithmetic (tests/README.md); add --force to replace" % ", ".join(existing))
    exe = os.path.abspath(args.exe)
    inputs = os.path.abspath(args.inputs)
    arrays = {}
    meta = {"build": gc.build_identity(exe), "omp_num_threads": 1, "cases": {}}
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    with tempfile.TemporaryDirectory(prefix="golden.") as tmp:
        for name, deck, extra, _threads in gc.CASES:
            out = os.path.join(tmp, name + ".h5")
            cmd = [exe, os.path.join(inputs, deck), "-o", out, "-q"] + extra
            print("-- " + " ".join(cmd[1:]), flush=True)
            subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
            u, scalars = gc.end_state(out)
            arrays[name] = u
            meta["cases"][name] = {"deck": deck, "args": extra, **scalars}
    os.makedirs(gc.GOLDEN_DIR, exist_ok=True)
    # written whole to temporary names, then renamed: an interrupted run leaves the old pair
    buf = io.BytesIO()
    write_npz(buf, arrays)
    for path, data in ((gc.NPZ, buf.getvalue()),
                       (gc.JSON, (json.dumps(meta, indent=1, sort_keys=True) + "\n").encode())):
        with open(path + ".tmp", "wb") as fh:
            fh.write(data)
    for path in (gc.NPZ, gc.JSON):
        os.replace(path + ".tmp", path)
    print("wrote %s (%d bytes) and %s" % (gc.NPZ, os.path.getsize(gc.NPZ), gc.JSON))


if __name__ == "__main__":
    main()
