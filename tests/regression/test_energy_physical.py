"""The physical energies at whole steps (history kinetic_energy_physical, strain_energy_physical;
docs/output.md) against facts with algebra behind them.

The staggered energies of the balance, kinetic_energy = 1/2 v^(n+1/2)T M v^(n+1/2) and
strain_energy = 1/2 u^(n+1)T K u^n, close the discrete balance exactly but are not the energy of
a state. The sample after step n also holds, at t_n: E_kin^n = 1/2 v^nT M v^n with
v^n = (v^(n-1/2) + v^(n+1/2))/2, and E_strain^n = 1/2 u^nT K u^n. Checked:
- impact_bar_p1 (level 2, undamped, a sample at every step, snapshots u^s at three steps):
  * the first sample is the initial state: E_kin = initial_kinetic_energy, E_strain = 0;
  * before contact the block translates rigidly at v0: E_kin^n = E0 = 1/2 rho L lx v0^2 and
    E_strain^n = 0 (K annihilates a translation along y), to round-off;
  * E_strain^s = 1/2 u^sT K u^s with K assembled here (c2dtest.q1_plane_strain, the lumped mass
    checked against /mesh/mass) from the snapshot u^s;
  * in free flight after the rebound (no contact force, no load, no damping: M a^n = -K u^n on the
    free dofs) the central difference gives, per mode and so for the sums, exactly
        (E_kin^n + E_strain^n) - (kinetic_energy + strain_energy) = dt^2/8 (K u^n)T M^-1 (K u^n),
    (v^(n+-1/2) = v^n -+ dt/2 M^-1 K u^n), checked at two snapshots to round-off: the physical
    energy exceeds the conserved staggered one by an O(dt^2) term;
  * at every sample E_kin^n <= (kinetic_energy of this sample + of the previous one)/2
    (convexity: |(a + b)/2|^2 <= (|a|^2 + |b|^2)/2).
- uniaxial_compression (converged, homogeneous plane strain with sigma_xx = 0): E_strain at the
  end = 1/2 E/(1 - nu^2) (delta/ly)^2 lx ly (Clapeyron: 1/2 u.K u = 1/2 u.f, f the reactions),
  and E_kin^n -> 0: below tol_kinetic x E_strain, the bound the convergence test applies to the
  staggered kinetic energy.
"""
import numpy as np

import c2dtest

E, NU, RHO = 7.0e4, 0.3, 2.7e-9


def history(f):
    return {k: f["history/" + k][()] for k in f["history"]}


def body(t):
    # ---- impact: initial state, rigid flight, the O(dt^2) identity ---------------------------
    snaps = (5.0e-8, 5.0e-7, 5.5e-7)
    run = t.run(t.deck("impact_bar_p1.nml"), "--set", "output:history_interval=1",
                "--set", "output:snapshot_times=%s" % ",".join("%r" % s for s in snaps), name="impact")
    t.expect_exit(run, 0)
    with run.open() as f:
        h = history(f)
        e0 = float(f.attrs["initial_kinetic_energy"])
        dt = float(f.attrs["dt"])
        x = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()] - 1
        mass = f["mesh/mass"][()]
        fields = {int(k): f["fields"][k]["displacement"][()].ravel() for k in f["fields"]}
        eff = c2dtest.parse_effective_deck(c2dtest.attr_str(f.attrs["effective_deck"]))
    lx, ly = float(eff["mesh"]["lx"]), float(eff["mesh"]["ly"])
    v0 = -float(eff["initial"]["velocity"][1])
    t.check_close(run, "E0 = 1/2 rho L lx v0^2 [mJ]", 0.5 * RHO * ly * lx * v0 ** 2, e0, rtol=1e-12, reason="round-off")
    kin, strain = h["kinetic_energy"], h["strain_energy"]
    kph, sph = h["kinetic_energy_physical"], h["strain_energy_physical"]
    step = h["step"].astype(int)
    t.require(np.all(np.diff(step) == 1), "a sample at every step")
    t.check_close(run, "first sample: kinetic_energy_physical = E0", e0, kph[0], rtol=1e-15, reason="the same number")
    t.check_equal(run, "first sample: strain_energy_physical", 0.0, float(sph[0]))
    fn = h["normal_force_total"]
    first = int(np.flatnonzero(fn > 0)[0])          # the sample of the first contact step (+1)
    before = slice(1, first)                         # samples whose t_n precedes any contact force
    t.check(run, "samples before contact", first > 10, "> 10", first)
    t.check_close(run, "before contact: kinetic_energy_physical = E0 (rigid translation)", np.full(first - 1, e0),
                  kph[before], rtol=1e-12, reason="v^n = v0 on every free dof, round-off")
    t.check_le(run, "before contact: |strain_energy_physical| / E0", np.abs(sph[before]) / e0, 1e-12,
               reason="K annihilates a translation; round-off of u ~ v0 t")

    K, m = c2dtest.q1_plane_strain(x, conn, E, NU, RHO)
    t.check_close(run, "lumped mass assembled here = /mesh/mass", mass, m[0::2], rtol=1e-12, reason="round-off")
    free = np.ones(2 * len(x))
    roller = (np.abs(x[:, 0]) < 1e-9 * lx) | (np.abs(x[:, 0] - lx) < 1e-9 * lx)   # u_x = 0 on both sides
    free[0::2][roller] = 0
    t.require(len(fields) == 3, "three snapshots")
    for s in sorted(fields):
        u = fields[s]
        k = int(np.flatnonzero(step == s + 1)[0])   # the sample after step s: energies at t_s
        ku = K @ u
        t.check_close(run, "step %d: strain_energy_physical = 1/2 u^T K u (K assembled here) [mJ]" % s, 0.5 * u @ ku,
                      sph[k], rtol=1e-10, atol=1e-14 * e0, reason="the same sum in another order")
        if s * dt < 4.0e-7:
            continue
        t.check_equal(run, "step %d in free flight: contact force of steps s-1, s, s+1" % s, 0.0,
                      float(np.abs(fn[k - 1:k + 2]).max()))
        gap = dt ** 2 / 8 * float(np.sum(free * ku ** 2 / m))
        diff = float(kph[k] + sph[k] - kin[k] - strain[k])
        t.info(run, "step %d: physical - staggered total [mJ], dt^2/8 |K u|^2_M^-1, of E0" % s,
               "%.6e, %.6e, %.4f" % (diff, gap, gap / e0))
        t.check_close(run, "step %d, free flight: physical - staggered energy = dt^2/8 (K u)^T M^-1 (K u)" % s, gap, diff,
                      atol=1e-12 * e0, reason="exact algebra of the central difference; round-off of E0")
    t.check_le(run, "every sample: E_kin^n - (kin^(n-1/2) + kin^(n+1/2))/2 (of E0)",
               (kph[1:] - 0.5 * (kin[1:] + kin[:-1])) / e0, 1e-14, reason="convexity; round-off")
    t.info(run, "at the end: (E_kin + E_strain)/E0 physical, staggered",
           "%.4f, %.4f" % ((kph[-1] + sph[-1]) / e0, (kin[-1] + strain[-1]) / e0))

    # ---- uniaxial compression at equilibrium -------------------------------------------------
    run = t.run(t.deck("uniaxial_compression.nml"), name="uniaxial")
    t.expect_exit(run, 0)
    with run.open() as f:
        h = history(f)
        eff = c2dtest.parse_effective_deck(c2dtest.attr_str(f.attrs["effective_deck"]))
        t.check_equal(run, "converged", 1, int(f.attrs["converged"]))
    lx, ly = float(eff["mesh"]["lx"]), float(eff["mesh"]["ly"])
    delta = 1.0e-3
    exact = 0.5 * E / (1 - NU ** 2) * (delta / ly) ** 2 * lx * ly
    t.check_close(run, "strain_energy_physical at the end = 1/2 E/(1 - nu^2) (delta/ly)^2 lx ly [mJ]", exact,
                  float(h["strain_energy_physical"][-1]), rtol=1e-8,
                  reason="Clapeyron for the homogeneous state; the run stops at residual 1e-10")
    tol_kin = float(eff["solver"]["tol_kinetic"])
    t.check_le(run, "kinetic_energy_physical / strain_energy_physical at the end",
               float(h["kinetic_energy_physical"][-1] / h["strain_energy_physical"][-1]), tol_kin,
               reason="at rest when converged: the convergence test's bound on the staggered kinetic energy")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
