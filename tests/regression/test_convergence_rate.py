#!/usr/bin/env python3
"""Convergence of the paper scene: postproc/paper_study.py at levels 0..4 (reference 4).

- The unbiased energy-norm rate (least squares over the three finest successive differences)
  is >= 0.45 for P1 and for P0: the scene's mixed-condition corners limit the H^2 rate 3/4 of
  the paper's Theorem 1 to about 1/2 (SPEC section 9).
- P0 pressures are never negative (mu >= 0 by the LCP); the recovered P1 pressure may be.
"""
import csv
import os
import subprocess
import sys

import c2dtest


def body(t):
    study = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "postproc",
                         "paper_study.py")
    out = t.subdir("study")
    cmd = [sys.executable, os.path.normpath(study), "--exe", t.exe, "--levels", "0-4", "--out", out]
    print("-- run  " + " ".join(cmd))
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=1500)
    print(proc.stdout[-3000:])
    t.require(proc.returncode == 0, "paper_study.py failed: " + proc.stderr[-2000:])
    with open(os.path.join(out, "rates.csv")) as fh:
        rates = list(csv.DictReader(fh))
    for m in ("P1", "P0"):
        r = [x for x in rates if x["multiplier"] == m and x["measure"] == "energy"
             and x["way"] == "successive differences" and x["levels"] == "three finest"][0]
        t.check_ge(os.path.join(out, "rates.csv"), "%s energy-norm rate, successive differences, 3 finest" % m,
                   float(r["rate"]), 0.45, reason="the corners of the contact zone predict about 1/2")
    with open(os.path.join(out, "p1_sign.csv")) as fh:
        sign = list(csv.DictReader(fh))
    p0_min = min(float(x["min_pressure"]) for x in sign if x["multiplier"] == "P0")
    t.check_ge(os.path.join(out, "p1_sign.csv"), "smallest P0 pressure over all levels", p0_min, 0.0,
               reason="mu >= 0 exactly: the LCP solution is clipped by construction, never negative")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
