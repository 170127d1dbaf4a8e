#!/usr/bin/env python3
"""Two equal elastic bars on a line, one at v0 hitting the other at rest, against 1D wave theory.

inputs/bar_impact_two_bodies_p1.nml (node to segment, P1, contact:master): bars 'a' and 'b' of
length L, u_y = 0 at every node, so each is a 1D bar with the P-wave modulus
M = E (1 - nu)/((1 + nu)(1 - 2 nu)) and c = sqrt(M/rho); 'a' moves at v0 (&body velocity) and
meets 'b' after the gap g0. d'Alembert with equal impedances: contact from t0 = g0/v0 for
2L/c at the stress rho c v0/2, then the velocities exchange ('a' at rest, 'b' at v0). Checked:
- the run is dynamic; the initial kinetic energy is 1/2 m_a v0^2 (round-off);
- contact starts within one step of t0 and lasts 2L/c within 1 % (start and end: the first
  and last history samples with a contact force; one step is 0.7 % of 2L/c here);
- the mean contact force over the contact = rho c v0 w/2 within 2 % (impulse over duration);
- after separation the bars' momenta (sum m v over each body) are 0 and m v0 within 3 % of
  m v0 (the forward increment stops the touching nodes inelastically: an O(h) loss, the
  normal contact work, 0.4 % of the energy here);
- the total momentum (sum m v^(n+1/2), v from two snapshots one step apart) equals m_a v0 to
  round-off (1e-10 relative) before, during and after the contact: the contact forces on the
  two bodies are equal and opposite (B^T lambda: +n at the slave node, -(1 - xi) n and -xi n
  at the master nodes);
- energy balance (initial kinetic energy and normal contact work included) <= 1e-10 at every
  step; no penetration beyond 1e-12 g0 at any step.
"""
import numpy as np

import c2dtest
from contact2d.h5 import Run

E, NU, RHO = 7.0e4, 0.3, 2.7e-9
L, W, G0, V0 = 1.0, 0.125, 1.0e-4, 1000.0


def body(t):
    deck = t.deck("bar_impact_two_bodies_p1.nml")
    c = np.sqrt(E * (1 - NU) / ((1 + NU) * (1 - 2 * NU)) / RHO)
    t0, duration, force = G0 / V0, 2 * L / c, 0.5 * RHO * c * V0 * W
    probe = t.run(deck, "--set", "solver:t_end=1e-8", name="probe")
    t.expect_exit(probe, 0)
    with Run(probe.h5) as r:
        tt = r.history("time")
        dt = float(tt[1] - tt[0])
    # snapshot pairs one step apart: before, in, and after the contact
    pairs = [5.0e-8, 2.0e-7, 3.0e-7, 4.0e-7, 5.5e-7]
    times = []
    for tp in pairs:
        k = round(tp / dt)
        times += [(k - 0.5) * dt, (k + 0.5) * dt]
    run = t.run(deck, "--set", "output:snapshot_times=" + ",".join("%.12e" % x for x in times), name="run")
    t.expect_exit(run, 0)
    t.expect_output(run)
    with run.open() as f:
        m = f["mesh/mass"][:]
        nb = f["mesh/node_body"][:]
        h = f["history"]
        time, fn = h["time"][:], h["normal_force_total"][:]
        balance, pen, kin = h["energy_balance_error"][:], h["penetration_max"][:], h["kinetic_energy"][:]
        vfin = f["final/velocity"][:]
        snaps = sorted(((int(k), f["fields"][k]["displacement"][:]) for k in f["fields"]), key=lambda s: s[0])
        dynamic = int(f.attrs["dynamic"])
    ma, mb = m[nb == 1].sum(), m[nb == 2].sum()
    t.check_equal(run, "dynamic", 1, dynamic, reason="&body velocity /= 0 with damping = 'none'")
    t.check_close(run, "initial kinetic energy [mJ] = 1/2 m_a v0^2", 0.5 * ma * V0 ** 2, float(kin[0]), rtol=1e-12,
                  reason="v^(-1/2) = v0 on the nodes of body 'a' only")
    on = np.nonzero(fn > 0)[0]
    t.require(len(on) > 0, "no contact force at all")
    start, end = float(time[on[0]]), float(time[on[-1]])
    t.info(run, "dt [s], contact steps", "%.4e, %d" % (dt, len(on)))
    t.check_close(run, "contact start [s] = t0 = g0/v0", t0, start, atol=dt * (1 + 1e-9), reason="within one step")
    t.check(run, "contact over before t_end", on[-1] < len(fn) - 1, "last force before the last step", str(on[-1]))
    t.check_close(run, "contact duration [s] = 2L/c", duration, end - start, rtol=0.01, reason="1 %")
    inside = (time >= start) & (time <= end)
    t.check_close(run, "mean contact force [N] = rho c v0 w / 2", force, float(fn[inside].mean()), rtol=0.02,
                  reason="2 %: impulse over the duration, both O(h)")
    pa = float((m[nb == 1] * vfin[nb == 1, 0]).sum())
    pb = float((m[nb == 2] * vfin[nb == 2, 0]).sum())
    t.check_close(run, "momentum of 'a' after separation [N s] = 0", 0.0, pa, atol=0.03 * ma * V0,
                  reason="3 % of m v0 (the velocities exchange)")
    t.check_close(run, "momentum of 'b' after separation [N s] = m v0", mb * V0, pb, rtol=0.03,
                  reason="3 % (the velocities exchange)")
    t.require(len(snaps) == 2 * len(pairs), "expected %d snapshots, got %d" % (2 * len(pairs), len(snaps)))
    for j in range(len(pairs)):
        (s0, u0), (s1, u1) = snaps[2 * j], snaps[2 * j + 1]
        t.require(s1 == s0 + 1, "snapshots %d and %d are not one step apart" % (s0, s1))
        p = float((m * (u1[:, 0] - u0[:, 0])).sum() / dt)
        t.check_close(run, "total momentum at step %d + 1/2 [N s] = m_a v0" % s0, ma * V0, p, rtol=1e-10,
                      reason="equal and opposite contact forces: conserved to round-off")
    t.check_le(run, "energy balance error, max over steps", float(np.abs(balance).max()), 1e-10,
               reason="round-off (the normal contact work counted)")
    t.check_le(run, "penetration, max over steps [mm]", float(pen.max()), 1e-12 * G0, reason="the exact LCP solve")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
