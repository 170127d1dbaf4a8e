"""Elastic wave speeds and slip fronts on a sliding interface (module, no script).

    from contact2d.slip_fronts import wave_speeds, rayleigh_ratio, slip_map, primary_front, fronts

Wave speeds of an isotropic solid in plane strain (Achenbach, "Wave propagation in elastic solids",
1973, ch. 5): shear c_s = sqrt(G/rho), G = E/(2(1+nu)); P wave c_p = c_s sqrt(2(1-nu)/(1-2nu));
Rayleigh c_R = xi c_s with xi the root in (0, 1) of Rayleigh's equation

    R(xi) = (2 - xi^2)^2 - 4 sqrt(1 - xi^2) sqrt(1 - kappa xi^2) = 0,   kappa = (c_s/c_p)^2.

R(xi) = -2 (1 - kappa) xi^2 + O(xi^4) < 0 near 0 and R(1) = 1 > 0: one root in (0, 1), found by
bisection to round-off. At nu = 1/4 (kappa = 1/3) the root is exact: xi^2 = 2 - 2/sqrt(3).

Slip fronts. The history series contact_slip_velocity (docs/output.md) is 0 at a node that sticks
(the node moved with the obstacle over the step) and non-zero where it slips. A front is where a
node goes from stick to slip: sample k with s[k-1, i] == 0 and s[k, i] != 0, at time t[k].
- primary_front: the detachment front that brings the interface from stick to gross slip: after
  the sample where the most nodes stick (t_stick), the time at which each node has slipped a
  given distance. Counting the slip distance rather than the first non-zero sample keeps the
  one-sample flickers of slip ahead of the front (and the stick-slip chatter behind it) from
  marking a node as detached; a uniform delay distance/V shifts every onset alike and leaves the
  fitted speed unchanged.
- fronts: every onset event, linked into fronts along the interface (events at neighbouring nodes
  whose times differ by at most `window`), each front with its least-squares speed.
A speed is fitted as a slowness (t = t0 + x/c, least squares of t on x), so that a front that
reaches many nodes in one sample (apparent speed beyond any wave speed) gives slowness ~ 0, not a
division by a vanishing time spread.
"""
import math
import sys

import numpy as np


def plane_strain_kappa(nu):
    """(c_s/c_p)^2 in plane strain: (1 - 2 nu) / (2 (1 - nu))."""
    return (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))


def rayleigh_residual(xi, nu):
    """R(xi) = (2 - xi^2)^2 - 4 sqrt(1 - xi^2) sqrt(1 - kappa xi^2), xi = c/c_s in [0, 1]."""
    k = plane_strain_kappa(nu)
    return (2.0 - xi * xi) ** 2 - 4.0 * math.sqrt(1.0 - xi * xi) * math.sqrt(1.0 - k * xi * xi)


def rayleigh_ratio(nu):
    """c_R / c_s: the root in (0, 1) of Rayleigh's equation for Poisson's ratio nu (-1 < nu < 0.5)."""
    if not -1.0 < nu < 0.5:
        raise ValueError("Poisson's ratio %g is outside (-1, 0.5)" % nu)
    a, b = 1.0e-3, 1.0           # R(a) < 0 (R ~ -2 (1 - kappa) a^2), R(1) = 1 > 0
    if rayleigh_residual(a, nu) >= 0.0:
        raise ValueError("no sign change of Rayleigh's equation on (1e-3, 1) at nu = %g" % nu)
    for _ in range(200):
        m = 0.5 * (a + b)
        if m <= a or m >= b:
            break
        if rayleigh_residual(m, nu) < 0.0:
            a = m
        else:
            b = m
    return 0.5 * (a + b)


def wave_speeds(young, nu, density):
    """{'c_s', 'c_p', 'c_R'} [length/time of the inputs' units]: shear, plane-strain P, Rayleigh."""
    g = young / (2.0 * (1.0 + nu))
    cs = math.sqrt(g / density)
    return {"c_s": cs, "c_p": cs / math.sqrt(plane_strain_kappa(nu)), "c_R": cs * rayleigh_ratio(nu)}


def slip_map(run):
    """(t (samples,), x (ncontact,), s (samples, ncontact)) of a contact2d.h5.Run with a moving
    obstacle: time, abscissa along Gamma_c and contact_slip_velocity reshaped; x increasing."""
    if not run.has("history/contact_slip_velocity"):
        raise ValueError("%s has no history/contact_slip_velocity (the obstacle does not move)" % run.path)
    ds = run.file["history/contact_slip_velocity"]
    nc = int(ds.attrs["ncontact"])
    s = ds[()].reshape(-1, nc)
    x = run.abscissa
    order = np.argsort(x, kind="stable")
    return run.history("time"), x[order], s[:, order]


def onsets(slip):
    """(k, i) index arrays of the stick-to-slip events: s[k-1, i] == 0 and s[k, i] != 0."""
    moving = slip != 0
    k, i = np.nonzero(~moving[:-1] & moving[1:])
    return k + 1, i


def fit_slowness(x, t):
    """Least squares t = t0 + p x; returns (p, t0). Needs two distinct x."""
    x, t = np.asarray(x, float), np.asarray(t, float)
    xm, tm = x.mean(), t.mean()
    sxx = np.sum((x - xm) ** 2)
    if sxx == 0.0:
        raise ValueError("a front needs two distinct positions")
    p = float(np.sum((x - xm) * (t - tm)) / sxx)
    return p, float(tm - p * xm)


def speed_of(p):
    """The speed of slowness p (inf for p = 0; signed: > 0 runs towards +x)."""
    return math.inf if p == 0.0 else 1.0 / p


def primary_front(t, x, slip, distance, t_from=0.0):
    """The detachment front (module doc): dict t_stick and onset (ncontact,): the time at which
    each node has slipped `distance` (the sum of |slip velocity| x sample interval) since t_stick;
    nan where it never has."""
    t = np.asarray(t, float)
    moving = slip != 0
    nstick = np.where(t >= t_from, np.sum(~moving, axis=1), -1)
    ks = int(np.argmax(nstick))
    slid = np.cumsum(np.abs(slip[ks + 1:]) * np.diff(t[ks:])[:, None], axis=0)
    reached = slid >= distance
    first = np.argmax(reached, axis=0)
    onset = np.where(np.any(reached, axis=0), t[ks + 1 + first], np.nan)
    return {"t_stick": t[ks], "onset": onset}


def window_speeds(x, onset, edges):
    """Signed front speeds fitted over the nodes with an onset in each window [edges[j], edges[j+1]]
    (nan where fewer than two)."""
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        sel = (x >= a) & (x <= b) & np.isfinite(onset)
        if np.count_nonzero(sel) < 2:
            out.append(math.nan)
        else:
            out.append(speed_of(fit_slowness(x[sel], onset[sel])[0]))
    return out


def fronts(t, x, slip, window, min_nodes=3, t_from=0.0):
    """Every stick-to-slip event after t_from, linked into fronts: events at neighbouring nodes
    (i, i + 1) whose times differ by at most window are one front. Returns a list of dicts
    (nodes, t0, t1, speed), one per front that reaches at least min_nodes distinct nodes, each
    speed fitted over the front's earliest event per node, in order of t0."""
    t = np.asarray(t, float)
    k, i = onsets(slip)
    keep = t[k] >= t_from
    k, i = k[keep], i[keep]
    n = len(k)
    parent = list(range(n))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    by_node = {}
    for e in range(n):
        by_node.setdefault(int(i[e]), []).append(e)
    for node, evs in by_node.items():
        nxt = by_node.get(node + 1, [])
        if not nxt:
            continue
        tn = t[k[nxt]]
        for e in evs:
            for j in np.nonzero(np.abs(tn - t[k[e]]) <= window)[0]:
                ra, rb = root(e), root(nxt[j])
                if ra != rb:
                    parent[ra] = rb
    groups = {}
    for e in range(n):
        groups.setdefault(root(e), []).append(e)
    out = []
    for evs in groups.values():
        first = {}
        for e in evs:
            node = int(i[e])
            if node not in first or t[k[e]] < first[node]:
                first[node] = t[k[e]]
        if len(first) < min_nodes:
            continue
        nodes = np.array(sorted(first))
        times = np.array([first[j] for j in nodes])
        p, _ = fit_slowness(x[nodes], times)
        out.append({"nodes": len(nodes), "t0": float(times.min()), "t1": float(times.max()),
                    "x0": float(x[nodes].min()), "x1": float(x[nodes].max()), "speed": speed_of(p)})
    return sorted(out, key=lambda f: f["t0"])


if __name__ == "__main__":
    print("contact2d.slip_fronts is a module, not a script (docs/postproc.md): it is used by "
          "postproc/friction_instability_study.py", file=sys.stderr)
    sys.exit(2)
