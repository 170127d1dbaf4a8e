#!/usr/bin/env python3
"""block_on_moving_plane (P1 or P0): a pressed block dragged by a rigid plane that moves along x.

Block [0, L] x [0, H] = [0, 1] x [0, 0.5] mm on the plane y = 0, Coulomb mu = 0.3; the top is held
in x and pressed down by 1e-3 mm over [0, 2e-6] s; the plane's velocity ramps smoothly from 0 to
V = 1000 mm/s over [2e-6, 3e-6] s and is then held (docs/geometry.md "Moving obstacles").
Facts:
- The plane's displacement is the exact integral of its velocity curve: 0 up to 2e-6 s,
  V T (s^2/2 - sin^2(pi s)/(2 pi^2)) during the ramp (s the ramp's fraction, T its length),
  V (t - 2.5e-6) after it (history obstacle_displacement_x, at the sample's own time).
- Once the plane has moved well beyond the shear the block needs to carry mu F_n (about
  mu (F_n/L) H / G), every node slides relative to the plane: the total tangential force is
  mu times the total normal force of the same step, to round-off; friction drags the block along
  the plane's motion (the force on the body, -F_t t with t = +x, points along +V).
- When the block has come to rest in steady sliding (the run converges), the plane's power on the
  block, d(obstacle_work)/dt, is mu F_n V: all of it is dissipated by friction.
- Energy: E_kin0 + W_ext + W_obstacle = E_kin + E_strain + D_friction + D_damping + W_normal to
  round-off at every sample (the obstacle's work is the balance's input).
- The nodes stay on the moving plane: penetration at round-off.
- The slip velocity relative to the plane (history contact_slip_velocity, one row of ncontact
  values per sample) is -V at every node once the block rests on the sliding plane.
"""
import math

import numpy as np

import c2dtest

E, NU, L, H, MU_F, V = 7.0e4, 0.3, 1.0, 0.5, 0.3, 1000.0
G = E / (2 * (1 + NU))
T1, T2 = 2.0e-6, 3.0e-6


def plane_displacement(t):
    """The exact integral of the velocity curve 0 (to T1), smooth ramp to V (to T2), held."""
    s = np.clip((t - T1) / (T2 - T1), 0.0, 1.0)
    ramp = V * (T2 - T1) * (0.5 * s * s - np.sin(np.pi * s) ** 2 / (2 * np.pi ** 2))
    return np.where(t <= T2, ramp, V * 0.5 * (T2 - T1) + V * (t - T2))


def body(t):
    mult = t.args.multiplier
    deck = t.deck("block_on_moving_plane_%s.nml" % mult.lower())
    run = t.run(deck, "--set", "output:history_interval=1", name="run")
    t.expect_exit(run, 0)
    t.expect_output(run)
    with run.open() as f:
        a = f.attrs
        t.check_equal(run, "converged (steady sliding reached)", 1, int(a["converged"]))
        t.check_equal(run, "/contact geometry attribute", "current", c2dtest.attr_str(f["contact"].attrs["geometry"]))
        hist = {k: f["history/" + k][()] for k in (
            "time", "tangential_force_total", "normal_force_total", "obstacle_work", "obstacle_displacement_x",
            "obstacle_displacement_y", "energy_balance_error", "penetration_max", "friction_dissipation")}
        slip_data = f["history/contact_slip_velocity"]
        nc = int(slip_data.attrs["ncontact"])
        slip_flat = slip_data[()]
        ncontact = f["contact/nodes"].shape[0]
    time, ft, fn = hist["time"], hist["tangential_force_total"], hist["normal_force_total"]

    # -- the plane's displacement: the closed-form integral of its velocity curve ---------------
    t.check_close(run, "obstacle_displacement_x = integral of the velocity curve [mm]", plane_displacement(time),
                  hist["obstacle_displacement_x"], rtol=1e-12, atol=1e-18,
                  reason="closed form of the smooth ramp's integral; round-off")
    t.check_equal(run, "obstacle_displacement_y (no vertical motion)", 0.0, float(np.abs(hist["obstacle_displacement_y"]).max()))

    # -- gross slip: total F_t = mu total F_n ------------------------------------------------------
    d_slide = 2.5 * MU_F * (fn[-1] / L) * H / G
    window = plane_displacement(time) >= d_slide
    nwin = int(np.count_nonzero(window))
    t.info(run, "sliding window", "plane moved >= %.3e mm: t >= %.4e s, %d samples" % (d_slide, time[window][0], nwin))
    t.check_ge(run, "samples in the sliding window", nwin, 20, reason="enough samples for the check to mean something")
    t.check_close(run, "|tangential_force_total| = mu normal_force_total while sliding", MU_F * fn[window],
                  np.abs(ft[window]), rtol=1e-8,
                  reason="every node at its limit mu F_n,i of the same step; 1e-8 (measured 1e-16)")
    t.check_le(run, "tangential_force_total while sliding (force on the body -F_t t along +V: F_t < 0) [N]",
               ft[window], 0.0, reason="friction drags the block along the plane's motion")

    # -- steady sliding: the plane's power goes into friction ------------------------------------
    k = max(len(time) - 5, 0)
    power = (hist["obstacle_work"][-1] - hist["obstacle_work"][k]) / (time[-1] - time[k])
    t.check_close(run, "d(obstacle_work)/dt at the end = mu F_n V [mW]", MU_F * fn[-1] * V, power, rtol=1e-6,
                  reason="the block at rest on the sliding plane: power of the friction force mu F_n at speed V "
                  "(measured 2e-11)")

    # -- the slip velocity along the interface (a space-time map: one row per sample) -----------
    t.check_equal(run, "contact_slip_velocity: ncontact columns, one row per sample", (ncontact, len(time) * ncontact),
                  (nc, slip_flat.size))
    slip = slip_flat.reshape(len(time), nc)
    t.check_close(run, "final contact_slip_velocity = -V at every node [mm/s]", np.full(nc, -V), slip[-1], rtol=1e-6,
                  reason="the block at rest on the plane moving at +V: each node slips at -V relative to it "
                  "(up to the block's residual motion; measured 3e-9)")

    # -- energy balance and penetration -----------------------------------------------------------
    t.check_le(run, "energy_balance_error at every sample", hist["energy_balance_error"], 1e-12,
               reason="the obstacle's work in the balance: round-off (measured <= 1.4e-15)")
    t.check_le(run, "penetration_max at every sample [mm]", hist["penetration_max"], 1e-12 * 1e-3,
               reason="nodes projected onto the plane at t_(n+1): round-off of the 1e-3 mm indentation")


if __name__ == "__main__":
    c2dtest.Test("block_on_moving_plane: mu F_n during gross slip, plane displacement, energy, penetration",
                 extra_args=[(("--multiplier",), {"choices": ["P1", "P0"], "required": True})]).main(body)
