"""Hertz measures of a contact2d run of inputs/hertz_*.nml (half models, symmetry on x = 0).

    from contact2d.hertz import measure
    m = measure("hertz_indenter_p1.h5")   # dict: P, a, p0, p0_fe, a_fe, h_edge, l2, l2_rel, p_min, ...

With the run's own total normal force P (per unit thickness, twice the half model's sum):
    E* = E / (1 - nu^2),  a = sqrt(4 P R / (pi E*)),  p0 = 2 P / (pi a),  p(x) = p0 sqrt(1 - x^2/a^2).
The contact pressure is the program's multiplier field (/final/contact/pressure): P1 per node
(piecewise linear along Gamma_c), P0 per dual cell (constant between the midpoints of the
adjacent segments); p_min is its most tensile value (P1 only: the tail of M_c^-1 beyond the
contact zone, docs/geometry.md), nonzero_separated the separated nodes where |p| > 1e-8 p0. Its L2 error on Gamma_c is integrated segment by segment with 64 midpoint
samples per segment against the exact p at the horizontal coordinate x of each sample.

For the speed-accuracy chart (postproc/speed_accuracy.py) the same L2 measure is available on its own:
    profile_l2(xc, p, "P1", reference)   # ||p_h - reference||_L2(Gamma_c); reference: a function of x,
                                         # or a second field of the same kind on the same nodes
    p1_pressure(xc, fn)                  # lambda = M_c^-1 F_n (SPEC section 3), from nodal normal forces
Only numpy and h5py.
"""
import numpy as np

from .h5 import Run


def _deck_value(text, group, name):
    """A value of the effective deck (one 'name = value' line inside &group)."""
    inside = False
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("&"):
            inside = s[1:].strip().lower() == group
            continue
        if inside and s.startswith(name + " ") or inside and s.startswith(name + "="):
            return s.split("=", 1)[1].strip()
    raise KeyError("%s:%s" % (group, name))


def hertz(P, R, E, nu):
    """(a, p0) of 2D Hertz for total force P per unit thickness."""
    estar = E / (1 - nu ** 2)
    a = np.sqrt(4 * P * R / (np.pi * estar))
    return a, 2 * P / (np.pi * a)


def measure(path):
    with Run(path) as run:
        eff = run.attr("effective_deck")
        x = run.coordinates
        nodes = run.contact_nodes
        fn = run.contact("normal_force")
        p = run.contact("pressure")
        status = run.contact("status")
        mult = run.attr("multiplier")
        conv = int(run.attr("converged"))
        nel = int(run.attr("element_count"))
    E = float(_deck_value(eff, "material", "young"))
    nu = float(_deck_value(eff, "material", "poisson"))
    if "'circle'" in eff:
        R = float(_deck_value(eff, "contact", "obstacle_radius"))
    else:
        # the half-disk: its radius is the height of its flat side above the contact point
        R = float(np.max(x[:, 1]) - np.min(x[:, 1]))
    P = 2 * float(np.sum(fn))
    a, p0 = hertz(P, R, E, nu)
    xc = x[nodes]
    xs = xc[:, 0]
    seg = np.linalg.norm(np.diff(xc, axis=0), axis=1)
    inc = np.nonzero(status > 0)[0]
    last = int(inc.max())
    # the contact half-width of the run: the farthest node in contact; one boundary element
    # there = the longer of the edges next to it
    a_fe = float(xs[last])
    h_edge = float(max(seg[max(last - 1, 0)], seg[min(last, len(seg) - 1)]))
    # L2 error of p on Gamma_c
    err, ref = profile_l2(xc, p, mult, lambda xq: p0 * np.sqrt(np.clip(1 - (xq / a) ** 2, 0, None)))
    return dict(P=P, R=R, a=a, p0=p0, p0_fe=float(p[0]), a_fe=a_fe, h_edge=h_edge, p_min=float(p.min()),
                nonzero_separated=int(np.count_nonzero((status == 0) & (np.abs(p) > 1e-8 * p0))),
                h_min=float(seg.min()), l2=err, l2_rel=err / ref,
                converged=conv, multiplier=mult, xs=xs, p=p, nel=nel)


def _samples(xc, values, kind, t):
    """The field `values` of kind P1 (per node, linear on each segment) or P0 (per dual cell: the
    node's value up to the segment midpoints) at the parameters t of every segment, (nseg, len(t))."""
    v = np.asarray(values, dtype=float)
    if kind == "P0":
        return np.where(t[None, :] < 0.5, v[:-1, None], v[1:, None])
    return v[:-1, None] + t[None, :] * (v[1:, None] - v[:-1, None])


def profile_l2(xc, values, kind, reference, samples=64):
    """(||values - reference||, ||reference||), L2 on Gamma_c (the polyline of the contact nodes xc
    (n, 2)): midpoint rule with `samples` points per segment, weights the chord length. reference is
    a function of the horizontal coordinate x (an analytic profile) or an array of the same kind on
    the same nodes (the same-mesh distance between two runs)."""
    xc = np.asarray(xc, dtype=float)
    seg = np.linalg.norm(np.diff(xc, axis=0), axis=1)
    t = (np.arange(samples) + 0.5) / samples
    ph = _samples(xc, values, kind, t)
    if callable(reference):
        pe = reference(xc[:-1, 0, None] + t[None, :] * (xc[1:, 0, None] - xc[:-1, 0, None]))
    else:
        pe = _samples(xc, reference, kind, t)
    w = seg[:, None] / samples
    return float(np.sqrt(np.sum((ph - pe) ** 2 * w))), float(np.sqrt(np.sum(pe ** 2 * w)))


def p1_pressure(xc, fn):
    """P1 pressure lambda = M_c^-1 F_n (SPEC section 3) from the nodal normal forces fn along Gamma_c
    (nodes xc (n, 2)): M_c the P1 mass of the polyline, [2 1; 1 2] h/6 per segment of chord h."""
    xc = np.asarray(xc, dtype=float)
    h = np.linalg.norm(np.diff(xc, axis=0), axis=1)
    n = len(xc)
    M = np.zeros((n, n))
    for i in range(n - 1):
        M[i:i + 2, i:i + 2] += h[i] / 6 * np.array([[2.0, 1.0], [1.0, 2.0]])
    return np.linalg.solve(M, np.asarray(fn, dtype=float))


if __name__ == "__main__":
    import sys

    print("contact2d.hertz is a module, not a script (docs/postproc.md): it is used by "
          "postproc/hertz_study.py, contact2d.lame and tests/regression/test_hertz.py", file=sys.stderr)
    sys.exit(2)
