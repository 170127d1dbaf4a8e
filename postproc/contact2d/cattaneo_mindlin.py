#!/usr/bin/python3
"""Hertz line contact and Cattaneo-Mindlin partial slip: the closed forms the mindlin_cylinder
scene is compared with.

    from contact2d.cattaneo_mindlin import hertz, stick_half_width, shear
    a, p0 = hertz(P, R, E, nu)            # elastic cylinder (plane strain) on a rigid flat
    c = stick_half_width(a, Q, mu, P)     # c = a sqrt(1 - Q / (mu P))
    q = shear(x, a, c, mu, p0)            # q(x) = mu p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2))

Per unit thickness: P, Q [N/mm], R [mm], E [MPa]. Plane strain, elastic on rigid:
E* = E / (1 - nu^2); a = sqrt(4 P R / (pi E*)); p(x) = p0 sqrt(1 - x^2/a^2), p0 = 2 P / (pi a).
The shear formula neglects the normal-tangential coupling (exact for Dundurs beta = 0; elastic
on rigid at nu = 0.3 gives beta = (1 - 2 nu) / (2 (1 - nu)) = 0.286), so the scene reports c/a and
q against it rather than asserting them tightly (docs/friction.md section 9).
"""
import math

import numpy as np


def hertz(P, R, E, nu):
    """Half-width a [mm] and peak pressure p0 [MPa] of an elastic cylinder on a rigid flat."""
    estar = E / (1 - nu ** 2)
    a = math.sqrt(4 * P * R / (math.pi * estar))
    return a, 2 * P / (math.pi * a)


def pressure(x, a, p0):
    x = np.asarray(x, float)
    return p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))


def stick_half_width(a, Q, mu, P):
    """c = a sqrt(1 - Q / (mu P)), 0 <= Q <= mu P."""
    if not 0 <= Q <= mu * P:
        raise ValueError("Cattaneo-Mindlin needs 0 <= Q <= mu P")
    return a * math.sqrt(1 - Q / (mu * P))


def shear(x, a, c, mu, p0):
    """Tangential traction q(x): mu p inside the slip zones c < |x| < a, reduced in the stick zone."""
    x = np.asarray(x, float)
    q = mu * pressure(x, a, p0)
    if c > 0:
        q = q - mu * p0 * (c / a) * np.sqrt(np.clip(1 - (x / c) ** 2, 0, None))
    return q


def dundurs_beta_rigid(nu):
    """Dundurs beta of an elastic body on a rigid one (plane strain)."""
    return (1 - 2 * nu) / (2 * (1 - nu))


if __name__ == "__main__":
    import sys

    print("contact2d.cattaneo_mindlin is a module, not a script (docs/postproc.md): it is used by "
          "contact2d.mindlin and tests/postproc/test_cattaneo_mindlin.py", file=sys.stderr)
    sys.exit(2)
