"""Regression: Hertz contact of a cylinder, P1 or P0, at the shipped level (0).

--scene indenter: inputs/hertz_indenter_<m>.nml, a rigid cylinder (obstacle = 'circle') on an
elastic block; --scene cylinder: inputs/hertz_cylinder_<m>.nml, an elastic half-disk on a rigid
plane (a curved Gamma_c). Both are half models on Gmsh meshes graded towards the contact.
With the run's own total normal force P (2 x the half model's sum), 2D Hertz gives
    a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a), E* = E / (1 - nu^2)
(contact2d.hertz). Checked: convergence, a/R <= 0.1, the run's contact half-width (farthest node
in contact) within one boundary element of a, the pressure at the centre within 1 % of p0, no
penetration; for the circle, /contact/gap and /contact/normal against |x - C| - R and
-(x - C)/|x - C| computed here; the pressure's sign: P0 never negative, P1 tensile just beyond the
contact zone as the tail of M_c^-1, decaying by 2 - sqrt(3) per node (pressure_sign). The L2
error decreasing with level is the study's
(postproc/hertz_study.py, docs/geometry.md), too slow for the suite.
"""
import os
import re
import shutil

import numpy as np

import c2dtest

from contact2d import hertz


def body(t):
    scene, mult = t.args.scene, t.args.multiplier.lower()
    deck = t.deck("hertz_%s_%s.nml" % (scene, mult))
    run = t.run(deck, name=scene)
    t.expect_exit(run, 0)
    t.expect_output(run)
    m = hertz.measure(run.h5)
    t.check_equal(run, "converged", 1, m["converged"])
    t.info(run, "P (N/mm), a (mm), p0 (MPa)", "%.6g %.6g %.6g" % (m["P"], m["a"], m["p0"]))
    t.check_le(run, "a / R", m["a"] / m["R"], 0.1,
               reason="Hertz's small-contact assumption (a << R); measured 0.044 indenter, 0.052 cylinder")
    t.check_le(run, "|a_run - a| / (boundary element at a_run)", abs(m["a_fe"] - m["a"]) / m["h_edge"], 1.0,
               reason="the run's edge is a node: it resolves a only to one element; measured 0.40, 0.65")
    # The centre pressure's error is the graded level-0 mesh's discretisation plus Hertz's
    # half-space idealisation of a finite body (a/R = 0.044, 0.052). Measured |p0_run/p0 - 1|:
    # indenter 0.059 % (P1), 0.023 % (P0); cylinder 0.59 % (P1), 0.48 % (P0), the static engine the
    # same. 1 % is the largest with a margin of 1.7 (2 % was the acceptance bound).
    t.check_close(run, "pressure at the centre vs p0", m["p0"], m["p0_fe"], rtol=0.01,
                  reason="mesh + half-space idealisation; measured <= 0.59 % (cylinder P1)")
    t.info(run, "L2 error of p on Gamma_c / L2 norm of p", "%.4g" % m["l2_rel"])
    pressure_sign(t, run, m, mult)
    with run.open() as f:
        x = f["mesh/coordinates"][()]
        u = f["final/displacement"][()]
        nodes = f["contact/nodes"][()] - 1
        gap = f["contact/gap"][()]
        normal = f["contact/normal"][()]
    if scene == "indenter":
        c = np.array([0.0, 10.0])
        r = np.linalg.norm(x[nodes] - c, axis=1)
        t.check_close(run, "/contact/gap = |x - C| - R", r - 10.0, gap, atol=1e-12,
                      reason="round-off of a norm of 10 mm")
        t.check_close(run, "/contact/normal = -(x - C)/|x - C|", -(x[nodes] - c) / r[:, None], normal,
                      atol=1e-14, reason="round-off")
    else:
        t.check_close(run, "/contact/gap = y", x[nodes, 1], gap, atol=1e-14, reason="round-off")
        t.check_close(run, "/contact/normal = (0, -1)", np.tile([0.0, -1.0], (len(nodes), 1)), normal, atol=0.0)
    d = np.sum(u[nodes] * normal, axis=1) - gap
    if mult == "p1":
        t.check_le(run, "penetration max d_i / (contact half-width)", float(np.max(d)) / m["a"], 1e-12)
    else:
        s = f_abscissa(run)
        dd = c2dtest.dual_coupling(s) @ d
        t.check_le(run, "P0 penetration max (D d)_i / w_i / a", float(np.max(dd / c2dtest.nodal_weights(s))) / m["a"],
                   1e-12)
    if scene == "cylinder" and mult == "p1":
        dropped_node_named_as_in_file(t, deck)


def pressure_sign(t, run, m, mult):
    """The sign of the recovered pressure (docs/geometry.md, Hertz study). P0: mu_n >= 0 on every
    dual cell (its LCP). P1: the nodal forces F_n,i >= 0, but lambda = M_c^-1 F_n is not local:
    beyond the last node j with a force, F_n = 0 makes (M_c lambda)_i = 0, and on edges of equal
    length ([1 4 1] h/6 rows, as next to the contact here) its decaying solution is
    lambda_(i+1) = -(2 - sqrt 3) lambda_i: tensile at j + 1 by 0.27 x lambda_j, alternating."""
    with run.open() as f:
        fn = f["final/contact/normal_force"][()]
        p = f["final/contact/pressure"][()]
    t.info(run, "min pressure / p0 (the most tensile value)", "%+.4f" % (p.min() / m["p0"]))
    if mult == "p0":
        t.check_ge(run, "P0 pressure mu_n,i / p0 at every dual cell", p / m["p0"], 0.0,
                   reason="the P0 LCP keeps mu_n >= 0 exactly")
        return
    t.check_ge(run, "P1 nodal normal force F_n,i / max F_n", fn / fn.max(), 0.0, reason="the P1 LCP: exact")
    j = int(np.flatnonzero(fn > 0).max())
    ratio = p[j + 1:j + 4] / p[j:j + 3]
    t.check_close(run, "lambda_(i+1)/lambda_i beyond the last node with a force (three nodes)",
                  np.full(3, -(2 - np.sqrt(3))), ratio, rtol=1e-8,
                  reason="M_c^-1's decaying mode: the Gamma_c edges there are equal (the .geo's SizeMin h within 2a "
                  "of the contact point); measured to 3.5e-11")
    t.check_equal(run, "the most tensile P1 value is at the edge: node j or j + 1 (j the last with a force)", True,
                  int(np.argmin(p)) in (j, j + 1))


def f_abscissa(run):
    with run.open() as f:
        return f["contact/abscissa"][()]


def dropped_node_named_as_in_file(t, deck):
    """A Gamma_c node with a prescribed normal dof is dropped with a warning naming the node as
    the mesh file (and the output's /mesh) numbers it, not the solver's renumbered index: here
    u_y = 0 on the symmetry line up to y = 0.5 takes the arc's end at (0, 0)."""
    folder = t.subdir("dropped_node")
    with open(deck) as fh:
        text = fh.read()
    line = "&dirichlet  boundary = 'symmetry', component = 'x', values = 0.0 /"
    t.require(line in text, "the cylinder deck has the symmetry condition")
    text = text.replace(line, line + "\n&dirichlet  boundary = 'symmetry', ymax = 0.5, component = 'y', values = 0.0 /")
    with open(os.path.join(folder, "hertz_sym.nml"), "w") as fh:
        fh.write(text)
    shutil.copy(os.path.join(os.path.dirname(deck), "hertz_cylinder.geo"), folder)
    run = t.run(os.path.join(folder, "hertz_sym.nml"), "--set", "solver:max_steps=2", cwd=folder, name="dropped_node")
    with run.open() as f:
        x = f["mesh/coordinates"][()]
    corner = int(np.argmin(np.hypot(x[:, 0], x[:, 1]))) + 1
    said = [ln for ln in run.stderr_lines() if "dropped from Gamma_c" in ln]
    t.check_equal(run, "one warning about the dropped node", 1, len(said))
    got = re.search(r"\(node ([0-9, ]+)\)", said[0]).group(1) if said else ""
    t.check_equal(run, "the warning names the node at (0, 0) by its number in /mesh/coordinates", str(corner), got)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0],
                 [(("--scene",), dict(required=True, choices=["indenter", "cylinder"])),
                  (("--multiplier",), dict(required=True, choices=["P1", "P0"]))]).main(body)
