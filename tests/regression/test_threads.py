#!/usr/bin/env python3
"""OpenMP runs give the same bits as serial runs.

The paper scene at level 4 (10 241 nodes, above the 4096-node threshold where the kernels go
parallel), P1 and P0 with Tresca, run with OMP_NUM_THREADS=1 and 2: every history series, the
final fields and the contact fields must be bitwise identical. Stick/slip decisions amplify
round-off, so this only holds because every sum has a fixed order (node gathers, per-block
partial sums added in block order).
"""
import numpy as np

import c2dtest


def body(t):
    for m in ("p1", "p0"):
        deck = t.deck("baillet_sassi_2002_%s.nml" % m)
        runs = {}
        for threads in (1, 2):
            r = t.run(deck, "--set", "mesh:level=4", name="%s_t%d" % (m, threads),
                      env={"OMP_NUM_THREADS": str(threads)}, timeout=900)
            t.expect_exit(r, 0)
            runs[threads] = r
        with runs[1].open() as a, runs[2].open() as b:
            t.check_equal(runs[2], "steps (%s)" % m, int(a.attrs["steps"]), int(b.attrs["steps"]))
            names = ["final/displacement", "final/velocity", "final/stress", "final/contact/normal_force",
                     "final/contact/tangential_force", "final/contact/status"]
            names += ["history/" + k for k in a["history"].keys()]
            differ = [n for n in names if not np.array_equal(a[n][()], b[n][()])]
            t.check(runs[2], "datasets bitwise identical, 1 vs 2 threads (%s, %d compared)" % (m, len(names)),
                    not differ, "none differ", ", ".join(differ) if differ else "none differ")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
