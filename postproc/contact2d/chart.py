"""The speed-accuracy chart's table and measures (postproc/speed_accuracy.py, docs/performance.md).

    from contact2d.chart import FIELDS, pareto, hertz_errors
    FIELDS                  # the columns of docs/figures/speed_accuracy.csv, one row per run
    pareto([(wall, err), ...])   # the non-dominated points, by wall time
    hertz_errors(xc, p, "P1", P, R, E, nu, p_static)   # (error against Hertz, against --static)

Rows of the paper scene have routes without prefix (static, explicit, ...; errors in the energy
norm, contact2d.compare); rows of the Hertz half-disk (inputs/hertz_cylinder_p1.nml) have routes
starting with 'hertz_' and both errors on the contact pressure (relative L2 on Gamma_c): against
2D Hertz with the run's own force, and against the --static run on the same mesh.
Only numpy.
"""
import numpy as np

from . import hertz

FIELDS = ("route", "multiplier", "level", "elements", "wall_seconds", "error_reference", "error_same_mesh")
#: the route-name prefix of the Hertz rows
HERTZ = "hertz_"


def pareto(points):
    """The non-dominated (wall, error) points, sorted by wall time."""
    front, best = [], float("inf")
    for w, e in sorted(points):
        if e < best:
            front.append((w, e))
            best = e
    return front


def hertz_errors(xc, p, kind, P, R, E, nu, p_static):
    """Relative L2 errors on Gamma_c (nodes xc (n, 2)) of the pressure p of kind 'P1' or 'P0':
    against Hertz's p0 sqrt(1 - x^2/a^2) for the total force P (per unit thickness, whole body),
    radius R, plane-strain E* = E/(1 - nu^2) (contact2d.hertz.hertz); and against p_static, the
    --static run's pressure on the same nodes, relative to its norm."""
    a, p0 = hertz.hertz(P, R, E, nu)
    err, ref = hertz.profile_l2(xc, p, kind, lambda x: p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None)))
    dist, _ = hertz.profile_l2(xc, p, kind, p_static)
    _, norm = hertz.profile_l2(xc, p_static, kind, p_static)
    return err / ref, dist / norm
