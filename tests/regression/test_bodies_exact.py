"""Regression: several bodies, each on its own material, reproduce their exact linear fields.

--case bimaterial: inputs/bimaterial_bar.nml, two bonded blocks stacked in y (they share the
nodes of y = H1): 'lower' [0, 1] x [0, H1 = 0.5] (E1 = 7e4 MPa, nu1 = 0.3), 'upper' [0, 1] x
[H1, H1 + H2 = 0.9] (E2 = 2.1e5, nu2 = 0.25); u_x = 0 on both sides, u_y = 0 on the bottom,
pressure p = 100 MPa on the top; plane strain with eps_xx = 0, so in body i
    sigma_yy = -p, sigma_xx = -p nu_i / (1 - nu_i), sigma_xy = 0,
    eps_yy,i = -p (1 + nu_i)(1 - 2 nu_i) / (E_i (1 - nu_i)),
    u_y = eps_yy,1 y (y <= H1), eps_yy,1 H1 + eps_yy,2 (y - H1) (y >= H1), u_x = 0.
--case separate: inputs/separate_blocks.nml, two bodies that share no node, each on rollers
(u_y = 0 on its bottom, u_x = 0 on its left side x0_i) with p = 50 MPa on its top: uniaxial
stress in plane strain in each, from its own material only (nothing couples them):
    sigma_yy = -p, sigma_xx = sigma_xy = 0, u_x = p nu_i (1 + nu_i)/E_i (x - x0_i),
    u_y = -p (1 - nu_i^2)/E_i y.
Both with --static (one linear solve: the fields are linear in each body, which Q1 reproduces
exactly, so every element's stress within 1e-10 p and the displacement within 1e-10 relative,
round-off of a direct solve), then the explicit engine (see explicit()). The bodies are read back through the postproc package
(contact2d.open_run: Run.body, node_body, body_names; /mesh/body, /mesh/node_body) and
checked against the geometry: an element's body is the block its centre lies in, a node's the
lowest body of its elements.
--case single: inputs/uniaxial_compression.nml (no &body) writes one body: /mesh/body and
/mesh/node_body all 1, /mesh attributes body_count = 1, body_name_1 = 'body'.
"""
import numpy as np

import c2dtest
import contact2d

CASES = {
    # deck, pressure, bodies: (name, E, nu, x range, y range of the block)
    "bimaterial": ("bimaterial_bar.nml", 100.0, [("lower", 7.0e4, 0.3, (0.0, 1.0), (0.0, 0.5)),
                                                 ("upper", 2.1e5, 0.25, (0.0, 1.0), (0.5, 0.9))]),
    "separate": ("separate_blocks.nml", 50.0, [("left", 7.0e4, 0.3, (0.0, 1.0), (0.0, 0.5)),
                                               ("right", 2.1e5, 0.2, (1.25, 2.25), (0.0, 0.6))]),
}


# the densities of the decks' bodies [t/mm^3] (bimaterial: &material's, the default of both)
RHO = {"bimaterial": (2.7e-9, 2.7e-9), "separate": (2.7e-9, 7.8e-9)}


def inside(p, xr, yr, tol=1e-9):
    return (p[:, 0] >= xr[0] - tol) & (p[:, 0] <= xr[1] + tol) & (p[:, 1] >= yr[0] - tol) & (p[:, 1] <= yr[1] + tol)


def single(t):
    """A deck without &body: one body 'body' of every element, written as such (the datasets
    themselves, not the reader's fallback for older files)."""
    run = t.run(t.deck("uniaxial_compression.nml"), "--static", name="single")
    t.expect_exit(run, 0)
    with run.open() as f:
        nel, nnode = int(f.attrs["element_count"]), int(f.attrs["node_count"])
        have = [name in f for name in ("mesh/body", "mesh/node_body")]
        t.check_equal(run, "/mesh/body and /mesh/node_body written", [True, True], have)
        if all(have):
            t.check_equal(run, "/mesh/body = 1 for every element", [1] * nel, f["mesh/body"][()].tolist())
            t.check_equal(run, "/mesh/node_body = 1 for every node", [1] * nnode, f["mesh/node_body"][()].tolist())
        a = f["mesh"].attrs
        t.check_equal(run, "/mesh body_count, body_name_1", (1, "body"),
                      (int(a.get("body_count", 0)), c2dtest.attr_str(a.get("body_name_1", ""))))


def body(t):
    if t.args.case == "single":
        single(t)
        return
    deck_name, p, bodies = CASES[t.args.case]
    run = t.run(t.deck(deck_name), "--static", name=t.args.case)
    t.expect_exit(run, 0)
    t.expect_output(run)
    with contact2d.open_run(run.h5) as r:
        eff = r.deck
        t.check_equal(run, "deck bodies (name, young, poisson)", [(n, e, nu) for n, e, nu, _, _ in bodies],
                      [(b["name"], float(b["young"]), float(b["poisson"])) for b in eff["body"]]
                      if isinstance(eff.get("body"), list) else None)
        t.check_equal(run, "converged", 1, int(r.attrs["converged"]))
        x = r.coordinates
        conn = r.connectivity - 1
        u = r.read("final/displacement")
        stress = r.read("final/stress")
        elem_body = r.body
        node_body = r.node_body
        names = r.body_names
    t.check_equal(run, "body names (/mesh body_name_k)", [b[0] for b in bodies], names)
    centre = x[conn].mean(axis=1)
    expect_elem = np.zeros(len(conn), dtype=int)
    for k, (_, _, _, xr, yr) in enumerate(bodies, start=1):
        expect_elem[(expect_elem == 0) & inside(centre, xr, yr)] = k
    t.check_equal(run, "/mesh/body = the block of the element's centre", expect_elem.tolist(), elem_body.tolist())
    expect_node = np.full(len(x), 10 ** 9)
    for e, nodes in enumerate(conn):
        expect_node[nodes] = np.minimum(expect_node[nodes], expect_elem[e])
    t.check_equal(run, "/mesh/node_body = the lowest body of the node's elements", expect_node.tolist(),
                  node_body.tolist())

    reason = "one direct solve of a field Q1 reproduces exactly: round-off only"
    u_exact = np.zeros_like(u)
    for k, (name, E, nu, xr, yr) in enumerate(bodies, start=1):
        sel = elem_body == k
        if t.args.case == "bimaterial":
            s_exact = np.array([-p * nu / (1 - nu), -p, 0.0])
        else:
            s_exact = np.array([0.0, -p, 0.0])
        t.info(run, "%s: sigma (xx, yy, xy) exact" % name, "%.12g, %.12g, %.12g MPa" % tuple(s_exact))
        t.check_close(run, "%s: every element's stress" % name, np.tile(s_exact, (int(sel.sum()), 1)), stress[sel],
                      atol=1e-10 * p, reason=reason)
        nodes = node_body == k
        if t.args.case == "separate":
            exx = p * nu * (1 + nu) / E
            eyy = -p * (1 - nu ** 2) / E
            u_exact[nodes] = np.column_stack([exx * (x[nodes, 0] - xr[0]), eyy * x[nodes, 1]])
    if t.args.case == "bimaterial":
        (_, e1, nu1, _, (y0, h1)), (_, e2, nu2, _, (_, top)) = bodies
        eps1 = -p * (1 + nu1) * (1 - 2 * nu1) / (e1 * (1 - nu1))
        eps2 = -p * (1 + nu2) * (1 - 2 * nu2) / (e2 * (1 - nu2))
        y = x[:, 1]
        u_exact[:, 1] = np.where(y <= h1, eps1 * y, eps1 * h1 + eps2 * (y - h1))
        at_top = np.abs(y - top) < 1e-9
        u_top = eps1 * h1 + eps2 * (top - h1)
        t.info(run, "u_y(top) exact", "%.12g mm" % u_top)
        t.check_close(run, "u_y on the top = eps_yy,1 H1 + eps_yy,2 H2", u_top, u[at_top, 1], rtol=1e-10,
                      scale=abs(u_top), reason=reason)
    scale = float(np.max(np.abs(u_exact)))
    t.check_close(run, "displacement vs each body's exact linear field", u_exact, u, rtol=1e-10, scale=scale,
                  reason=reason)
    explicit(t, deck_name, p, bodies, u_exact, s_all=[(k, stress_exact(t.args.case, p, nu))
                                                     for k, (_, _, nu, _, _) in enumerate(bodies, start=1)])


def stress_exact(case, p, nu):
    return np.array([-p * nu / (1 - nu), -p, 0.0]) if case == "bimaterial" else np.array([0.0, -p, 0.0])


def explicit(t, deck_name, p, bodies, u_exact, s_all):
    """The explicit engine on the same deck: each element's matrix and lumped mass from its own
    body, the time step from the element bound over all bodies. Checked from first principles
    (c2dtest.q1_plane_strain, 2 x 2 Gauss, each element with its body's E, nu, rho): /mesh/mass
    = the assembled lumped masses; dt_critical = 2 / sqrt(max over elements of the largest
    eigenvalue of M_e^-1/2 K_e M_e^-1/2); the run converges (tol_residual 1e-10) to the same
    exact field to 1e-8 (the relaxation residual, as regression_uniaxial)."""
    run = t.run(t.deck(deck_name), name=t.args.case + "_explicit")
    t.expect_exit(run, 0)
    with contact2d.open_run(run.h5) as r:
        x = r.coordinates
        conn = r.connectivity - 1
        elem_body = r.body
        mass = r.mass
        u = r.read("final/displacement")
        stress = r.read("final/stress")
        dt_critical = float(r.attrs["dt_critical"])
        t.check_equal(run, "converged", 1, int(r.attrs["converged"]))
    m_exact = np.zeros(len(x))
    omega2 = 0.0
    for e, nodes in enumerate(conn):
        _, E, nu, _, _ = bodies[elem_body[e] - 1]
        rho = RHO[t.args.case][elem_body[e] - 1]
        ke, me = c2dtest.q1_plane_strain(x[nodes], np.array([[0, 1, 2, 3]]), E, nu, rho)
        m_exact[nodes] += me[0::2]
        sc = 1 / np.sqrt(me)
        omega2 = max(omega2, float(np.linalg.eigvalsh(ke * sc[:, None] * sc[None, :])[-1]))
    t.check_close(run, "/mesh/mass = lumped masses with each element's own density", m_exact, mass, rtol=1e-12,
                  reason="the same integrals, summed in another order")
    t.check_close(run, "dt_critical = 2/sqrt(max over all bodies' elements of omega_e^2)", 2 / np.sqrt(omega2),
                  dt_critical, rtol=1e-10, reason="dense 8 x 8 eigenproblems here, LAPACK dsygv in the program")
    reason = "converged to tol_residual 1e-10; the bound is 1e-8 relative"
    t.check_close(run, "explicit: displacement vs the exact field", u_exact, u, rtol=1e-8,
                  scale=float(np.max(np.abs(u_exact))), reason=reason)
    for k, s_exact in s_all:
        sel = elem_body == k
        t.check_close(run, "explicit: body %d stress" % k, np.tile(s_exact, (int(sel.sum()), 1)), stress[sel],
                      atol=1e-8 * p, reason=reason)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0], extra_args=[(("--case",), {"required": True, "choices": sorted(CASES) + ["single"]})]).main(body)
