#!/usr/bin/env python3
"""coulomb_sliding (P1 or P0): a block pressed, then sheared until it slides, Coulomb friction.

Block [0, L] x [0, H] = [0, 1] x [0, 0.5] mm on the line y = 0, Coulomb coefficient mu = 0.3.
Stage 1 (to 2e-6 s): top pressed by 1e-3 mm, u_x = 0; stage 2 (to 6e-6 s): top moved
u_x = +5e-3 mm. Facts (docs/friction.md sections 1 and 4):
- Each node's tangential limit in a step is mu F_n,i of the same step (P1: Lambda_n,i; P0:
  F_n = D^T mu_n). While the block slides, every node carries its limit, so the total
  tangential force equals mu times the total normal force of the same step, to round-off,
  although the normal force itself shifts as the block tilts; |F_t| <= mu F_n at every sample.
- A stuck node gets no tangential increment (history stick_increment_max is round-off).
- At the end every node is at its limit: |F_t,i| = mu F_n,i; for P0 the limit is checked against
  mu (D mu_n)_i built here from the output pressure field and the abscissae (SPEC 3's D).
- Friction work of stage 2 = sum over time of mu sum_i F_n,i |d slip_i|. From 16 snapshots
  (end of stage 1, 14 during stage 2, the final state) with the trapezoidal rule in time; the
  quadrature error is what the tolerance covers (it is measured and printed).
- The discrete energy balance closes (<= 1e-12 at every sample).
The sliding window: top moved by at least 2.5 mu (F_n/L) H / G (uniform-shear estimate of the
shear the block needs to carry mu F_n, with margin for the free sides and the tilting).
Runs at mesh:level=1 (the deck) and level=2.
"""
import math

import numpy as np

import c2dtest

E, NU, L, H, MU_F = 7.0e4, 0.3, 1.0, 0.5, 0.3
G = E / (2 * (1 + NU))
U_TOTAL = 5.0e-3
T1, T2 = 2.0e-6, 6.0e-6
LEVELS = (1, 2)
MIN_WINDOW_SAMPLES = 20
SNAPSHOTS = [T1] + list(np.linspace(T1 + (T2 - T1) / 14, T2, 14))


def ramp(tau):
    tau = np.clip(tau, 0.0, 1.0)
    return tau - np.sin(2 * np.pi * tau) / (2 * np.pi)


def load_curve(t, values, times):
    out = np.zeros_like(t)
    prev_v, prev_t = 0.0, 0.0
    for v, tk in zip(values, times):
        inside = t > prev_t
        out = np.where(inside, prev_v + (v - prev_v) * ramp((t - prev_t) / (tk - prev_t)), out)
        prev_v, prev_t = v, tk
    return out


def body(t):
    mult = t.args.multiplier
    scene = "coulomb_sliding_%s" % mult.lower()
    deck = t.deck(scene + ".nml")
    snaps = ", ".join("%.10g" % s for s in SNAPSHOTS)
    for level in LEVELS:
        print()
        run = t.run(deck, "--set", "mesh:level=%d" % level, "--set", "output:history_interval=1",
                    "--set", "output:snapshot_times=" + snaps, name="level%d" % level)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with run.open() as f:
            a = f.attrs
            eff = c2dtest.parse_effective_deck(c2dtest.attr_str(a["effective_deck"]))
            c = eff["contact"]
            t.check_equal(run, "deck (young, poisson, lx, ly, friction, friction_coefficient, multiplier)",
                          (E, NU, L, H, "coulomb", MU_F, mult),
                          (float(eff["material"]["young"]), float(eff["material"]["poisson"]),
                           float(eff["mesh"]["lx"]), float(eff["mesh"]["ly"]), c["friction"],
                           float(c["friction_coefficient"]), c["multiplier"]))
            top_x = [d for d in eff["dirichlet"] if d["edge"] == "top" and d["component"] == "x"]
            t.require(len(top_x) == 1, "the deck has one &dirichlet group for u_x on the top")
            values = [float(v) for v in top_x[0]["values"]]
            times = [float(v) for v in top_x[0]["times"]]
            t.check_equal(run, "top u_x load curve (values, times)", ([0.0, U_TOTAL], [T1, T2]), (values, times))
            t.check_equal(run, "converged", 1, int(a["converged"]))
            t.check_equal(run, "/contact friction attributes", ("coulomb", MU_F),
                          (c2dtest.attr_str(f["contact"].attrs["friction"]),
                           float(f["contact"].attrs["friction_coefficient"])))
            hist = {k: f["history/" + k][()] for k in ("time", "tangential_force_total", "normal_force_total",
                                                       "stick_increment_max", "friction_dissipation",
                                                       "energy_balance_error")}
            nodes = f["contact/nodes"][()] - 1
            s_abs = f["contact/abscissa"][()]
            u_end = f["final/displacement"][()]
            fn_end = f["final/contact/normal_force"][()]
            ft_end = f["final/contact/tangential_force"][()]
            p_end = f["final/contact/pressure"][()]
            groups = sorted(f["fields"].values(), key=lambda g: float(g.attrs["time"])) if "fields" in f else []
            snap = [(float(g.attrs["time"]), int(g.attrs["step"]), g["displacement"][()][nodes, 0],
                     g["contact_normal_force"][()]) for g in groups]
            dt = float(a["dt"])
            t_final = float(hist["time"][-1])

        time, ftot, fntot = hist["time"], hist["tangential_force_total"], hist["normal_force_total"]
        t.info(run, "history samples", time.size)
        t.info(run, "final total F_n, F_t [N]", "%.6f, %.6f" % (fntot[-1], ftot[-1]))

        # -- total tangential force while sliding = mu F_n of the same step ---------------------
        u_slide = 2.5 * MU_F * (fntot[-1] / L) * H / G
        u_top = load_curve(time, values, times)
        window = u_top >= u_slide
        nwin = int(np.count_nonzero(window))
        t.info(run, "sliding window", "t >= %.4e s (top u_x >= %.4e mm), %d samples"
               % (time[window][0] if nwin else math.nan, u_slide, nwin))
        t.check_ge(run, "samples in the sliding window", nwin, MIN_WINDOW_SAMPLES,
                   reason="many samples are needed for the check to mean something")
        t.check(run, "final sample in the sliding window", bool(window[-1]), "True", bool(window[-1]))
        if nwin:
            t.info(run, "total F_n over the window [N]", "%.6f .. %.6f" % (fntot[window].min(), fntot[window].max()))
            t.check_close(run, "tangential_force_total = mu normal_force_total while sliding",
                          MU_F * fntot[window], ftot[window], rtol=1e-12,
                          reason="every node at mu F_n,i of the same step: equal up to the round-off of the sums")
        t.check_le(run, "|tangential_force_total| - mu normal_force_total at every sample [N]",
                   np.abs(ftot) - MU_F * fntot, 1e-12 * MU_F * float(fntot.max()),
                   reason="|F_t,i| <= mu F_n,i at each node; 1e-12 for the round-off of the sums")

        # -- stuck nodes do not move tangentially --------------------------------------------------
        t.check_le(run, "stick_increment_max at every sample [mm]", hist["stick_increment_max"], 1e-12 * U_TOTAL,
                   reason="a stuck node gets no tangential increment: round-off, 1e-12 of the 5e-3 mm stroke")

        # -- per node at the end: every node at mu F_n,i --------------------------------------------
        if mult == "P0":
            fn_check = c2dtest.dual_coupling(s_abs) @ p_end     # F_n = D^T mu_n (D symmetric)
            t.check_close(run, "final F_n,i = (D mu_n)_i from the pressure field", fn_check, fn_end, rtol=1e-12,
                          reason="SPEC 3: P0 nodal normal force D^T mu_n; round-off")
        else:
            fn_check = fn_end
        t.check_close(run, "final |F_t,i| = mu F_n,i at every contact node", MU_F * fn_check, np.abs(ft_end),
                      rtol=1e-10, reason="the block has slid: every node at its Coulomb limit, 1e-10")

        # -- friction work of stage 2 ----------------------------------------------------------------
        t.check_equal(run, "number of /fields snapshots", len(SNAPSHOTS), len(snap))
        t.require(len(snap) == len(SNAPSHOTS), "one snapshot per requested time")
        t.check_close(run, "snapshot times", SNAPSHOTS, [s[0] for s in snap], atol=dt * (1 + 1e-9),
                      reason="the first step at or after each requested time: within one dt")
        pts = snap + [(t_final, -1, u_end[nodes, 0], fn_end)]
        predicted = 0.0
        for (ta, _, ua, fa), (tb, _, ub, fb) in zip(pts[:-1], pts[1:]):
            predicted += MU_F * float(np.sum(0.5 * (fa + fb) * np.abs(ub - ua)))
        dfric = hist["friction_dissipation"]
        d_start = float(np.interp(snap[0][0], time, dfric))
        d_stage2 = float(dfric[-1]) - d_start
        slip = u_end[nodes, 0] - snap[0][2]
        t.check_ge(run, "stage-2 slip of every contact node [mm] (the block slides forward)", slip, 0.0)
        t.info(run, "stage-2 friction work: history, mu sum F_n |slip| (trapezoid over snapshots) [mJ]",
               "%.9e, %.9e (relative difference %.2e)" % (d_stage2, predicted, abs(d_stage2 - predicted) / predicted))
        t.check_close(run, "stage-2 friction dissipation vs mu sum_t sum_i F_n,i |d slip_i|", predicted, d_stage2,
                      rtol=1e-3, reason="trapezoid in time over 15 intervals of a smoothly varying F_n,i; measured "
                      "3e-5 to 2.6e-4 (docs/friction.md section 4)")

        # -- energy balance --------------------------------------------------------------------------
        t.check_le(run, "energy_balance_error at every sample", hist["energy_balance_error"], 1e-12,
                   reason="as for Tresca: round-off (measured <= 8e-15)")


if __name__ == "__main__":
    c2dtest.Test("coulomb_sliding: total friction force mu F_n, no stuck-node motion, friction work",
                 extra_args=[(("--multiplier",), {"choices": ["P1", "P0"], "required": True})]).main(body)
