"""Measures of an impact_bar run against the exact 1D wave solution (docs/impact.md).

    from contact2d import Run
    from contact2d.impact import exact, measure
    with Run("impact_bar_p1.h5") as run:
        ex = exact(run)        # t0, duration 2L/c, pressure rho c v0, v0, ... from the deck
        me = measure(run)      # the same quantities measured on the history and final state

The exact answer (deck header of inputs/impact_bar_p1.nml): a block of height L with roller sides
(uniaxial strain) hits the rigid plane with velocity v0 after a gap g0. Contact starts at
t0 = g0/v0, lasts 2L/c with c = sqrt(E(1 - nu)/((1 + nu)(1 - 2 nu) rho)), the pressure is rho c v0
throughout, and the block leaves with velocity +v0.

Timing convention of the history (docs/output.md): the sample at time t_(n+1) holds the contact
force of step n, the force at t_n that makes u^(n+1) admissible. So the force history is placed
at time - dt. A force F^n acts on the impulse F^n dt, so contact lasts (number of steps with a
non-zero force) x dt, from the first force step t_first to t_last + dt.

Only numpy and h5py (through contact2d.h5) are needed.
"""
import math

import numpy as np


def exact(run):
    """The exact 1D answer from the run's effective deck and contact geometry."""
    young, poisson, rho = run.material
    mesh = run.deck["mesh"]
    length, width = float(mesh["ly"]), float(mesh["lx"])
    velocity = run.deck["initial"]["velocity"]
    v0 = -float(velocity[1])
    gap = float(np.min(run.file["contact/gap"][()]))
    modulus = young * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson))
    c = math.sqrt(modulus / rho)
    return {
        "c": c,
        "v0": v0,
        "gap": gap,
        "length": length,
        "width": width,
        "t0": gap / v0,
        "duration": 2 * length / c,
        "pressure": rho * c * v0,
        "force": rho * c * v0 * width,
        "kinetic": 0.5 * rho * length * width * v0 ** 2,
    }


def measure(run, exact_answer=None):
    """Contact start, duration, pressures, rebound velocity and energies of one run."""
    ex = exact_answer or exact(run)
    f = run.file
    dt = float(f.attrs["dt"])
    time = run.history("time")
    force = run.history("normal_force_total")
    t_force = time - dt                      # force of step n sits in the sample at t_(n+1)
    step = run.history("step").astype(np.int64)
    if not np.all(np.diff(step) == 1):
        raise ValueError("impact measures need a history sample at every step (output:history_interval = 1)")
    on = np.flatnonzero(force > 0)
    out = {"dt": dt, "dt_ratio": dt / float(f.attrs["dt_critical"]), "steps": int(f.attrs["steps"])}
    mass = f["mesh/mass"][()]
    velocity = f["final/velocity"][()]
    out["rebound_velocity"] = float(np.sum(mass * velocity[:, 1]) / np.sum(mass))
    e0 = float(f.attrs["initial_kinetic_energy"])
    out["initial_kinetic"] = e0
    # all mechanical energy left at the end: the energy of the last whole-step state (the
    # _physical series, docs/output.md); the staggered sum of the balance is E0 - W_normal
    kin, strain = run.history("kinetic_energy_physical"), run.history("strain_energy_physical")
    out["energy_returned"] = float((kin[-1] + strain[-1]) / e0)
    kin, strain = run.history("kinetic_energy"), run.history("strain_energy")
    out["energy_returned_staggered"] = float((kin[-1] + strain[-1]) / e0)
    out["rigid_energy_returned"] = (out["rebound_velocity"] / ex["v0"]) ** 2   # 1/2 M v_reb^2 / E0
    out["normal_work"] = float(run.history("normal_contact_work")[-1] / e0)
    out["balance_error_max"] = float(np.max(run.history("energy_balance_error")))
    out["penetration_max"] = float(np.max(run.history("penetration_max")))
    if on.size == 0:
        out.update(contact=False)
        return out
    first, last = on[0], on[-1]
    inside = force[first:last + 1]
    out["contact"] = True
    out["start"] = float(t_force[first])
    out["end"] = float(t_force[last] + dt)
    out["duration"] = out["end"] - out["start"]
    out["contact_steps"] = int(last - first + 1)
    out["gaps_inside"] = int(np.count_nonzero(inside <= 0))   # chatter: force-free steps in contact
    out["ended"] = bool(last < force.size - 1)                # contact over before t_end
    out["pressure_mean"] = float(np.mean(inside) / ex["width"])
    # plateau: the middle 80 % of the contact (leaves out the arrival and departure of the wave)
    n = inside.size
    mid = inside[int(0.1 * n):max(int(0.9 * n), int(0.1 * n) + 1)] / ex["width"]
    out["pressure_plateau"] = float(np.mean(mid))
    out["pressure_osc_rms"] = float(np.sqrt(np.mean((mid - ex["pressure"]) ** 2)) / ex["pressure"])
    out["pressure_osc_max"] = float(np.max(np.abs(mid - ex["pressure"])) / ex["pressure"])
    out["force_time"] = t_force
    out["force"] = force
    return out


if __name__ == "__main__":
    import sys

    print("contact2d.impact is a module, not a script (docs/postproc.md): it is used by "
          "postproc/impact_study.py and tests/regression/test_impact.py", file=sys.stderr)
    sys.exit(2)
