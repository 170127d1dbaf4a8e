"""Vectorised numpy helpers for Q1 (bilinear quadrilateral) fields, plane strain, 2x2 Gauss.

Used by contact2d.compare (SPEC section 9). Conventions follow the output contract (SPEC 8):
connectivity is 0-based here (callers subtract 1 from the file's ids), counter-clockwise from
the bottom-left node; element dofs are ordered (u1x, u1y, u2x, u2y, ...).

On a mesh of rectangles 2x2 Gauss integrates every quantity below exactly: a Q1 gradient is
linear in one coordinate and constant in the other, so |grad u|^2, eps:C:eps and |u|^2 are at
most biquadratic, and the 2-point rule is exact for cubics in each variable. It is the same rule
contact2d uses for K, so energy_norm_sq(e) == e^T K e to round-off.

Only numpy is needed.
"""
import numpy as np

_G = 1.0 / np.sqrt(3.0)
#: Gauss points in the reference square [-1, 1]^2 (4, 2) and their weights (4,)
GAUSS_POINTS = np.array([[-_G, -_G], [_G, -_G], [_G, _G], [-_G, _G]])
GAUSS_WEIGHTS = np.ones(4)
#: reference node positions, counter-clockwise from the bottom-left node
REF_NODES = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def shape_functions(xi):
    """N (npts, 4) at reference points xi (npts, 2)."""
    xi = np.atleast_2d(xi)
    return 0.25 * (1.0 + xi[:, None, 0] * REF_NODES[None, :, 0]) * \
        (1.0 + xi[:, None, 1] * REF_NODES[None, :, 1])


def shape_gradients_ref(xi):
    """dN/dxi (npts, 4, 2) at reference points xi (npts, 2)."""
    xi = np.atleast_2d(xi)
    sx, sy = REF_NODES[:, 0], REF_NODES[:, 1]
    d = np.empty((xi.shape[0], 4, 2))
    d[:, :, 0] = 0.25 * sx[None, :] * (1.0 + xi[:, None, 1] * sy[None, :])
    d[:, :, 1] = 0.25 * sy[None, :] * (1.0 + xi[:, None, 0] * sx[None, :])
    return d


def plane_strain_lame(young, poisson):
    """(lambda, mu) of the isotropic Hooke law; plane strain uses them unchanged."""
    lam = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
    mu = young / (2.0 * (1.0 + poisson))
    return lam, mu


def plane_strain_D(young, poisson):
    """3x3 plane-strain elasticity matrix for (eps_xx, eps_yy, gamma_xy)."""
    lam, mu = plane_strain_lame(young, poisson)
    return np.array([[lam + 2 * mu, lam, 0.0], [lam, lam + 2 * mu, 0.0], [0.0, 0.0, mu]])


class Q1Geometry:
    """Physical shape-function gradients and quadrature weights of a Q1 mesh, 2x2 Gauss.

    coordinates (nnode, 2), connectivity (nel, 4) 0-based. Attributes:
      dNdx    (nel or 1, 4 gp, 4 nodes, 2)  physical gradients of the shape functions
      N       (4 gp, 4 nodes)               shape function values
      wdet    (nel or 1, 4 gp)              Gauss weight times det J
      uniform True when all elements are translates of one another; the arrays then have a
              leading dimension of 1 and broadcast (one element computation for the mesh).
    """

    def __init__(self, coordinates, connectivity, rtol=1e-10):
        coordinates = np.asarray(coordinates, dtype=float)
        conn = np.asarray(connectivity, dtype=np.int64)
        self.connectivity = conn
        self.nnode = coordinates.shape[0]
        self.nel = conn.shape[0]
        xe = coordinates[conn]                       # (nel, 4, 2)
        offsets = xe - xe[:, :1, :]
        scale = max(np.ptp(coordinates[:, 0]), np.ptp(coordinates[:, 1]), 1e-300)
        self.uniform = bool(np.all(np.abs(offsets - offsets[:1]) <= rtol * scale))
        if self.uniform:
            xe = xe[:1]
        dref = shape_gradients_ref(GAUSS_POINTS)     # (4gp, 4, 2)
        # J[e, g, i, j] = d x_i / d xi_j
        jac = np.einsum("ead,gaj->egdj", xe, dref)
        det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
        if np.any(det <= 0.0):
            raise ValueError("element with non-positive Jacobian (not counter-clockwise?)")
        inv = np.empty_like(jac)
        inv[..., 0, 0] = jac[..., 1, 1] / det
        inv[..., 1, 1] = jac[..., 0, 0] / det
        inv[..., 0, 1] = -jac[..., 0, 1] / det
        inv[..., 1, 0] = -jac[..., 1, 0] / det
        # dN/dx_i = dN/dxi_j * dxi_j/dx_i
        self.dNdx = np.einsum("gaj,egji->egai", dref, inv)
        self.N = shape_functions(GAUSS_POINTS)
        self.wdet = det * GAUSS_WEIGHTS[None, :]

    def gather(self, u):
        """Element nodal values (nel, 4, ncomp) of a nodal field u (nnode, ncomp)."""
        return np.asarray(u, dtype=float)[self.connectivity]

    def gradients(self, u):
        """grad u at the Gauss points, (nel, 4 gp, 2 components, 2 directions)."""
        ue = self.gather(u)
        if self.uniform:  # one set of gradients for all elements: a BLAS contraction
            return np.tensordot(ue, self.dNdx[0], axes=([1], [1])).transpose(0, 2, 1, 3)
        return np.einsum("eac,egad->egcd", ue, self.dNdx, optimize=True)

    def values(self, u):
        """u at the Gauss points, (nel, 4 gp, ncomp)."""
        return np.tensordot(self.gather(u), self.N, axes=([1], [1])).transpose(0, 2, 1)

    def _integrate(self, density):
        """Sum over elements and Gauss points of density (nel, 4) times weight * det J."""
        return float(np.sum(density * self.wdet))

    def energy_norm_sq(self, u, young, poisson):
        """a(u, u) = int eps(u) : C : eps(u), plane strain (twice the strain energy)."""
        lam, mu = plane_strain_lame(young, poisson)
        g = self.gradients(u)
        exx, eyy = g[..., 0, 0], g[..., 1, 1]
        exy = 0.5 * (g[..., 0, 1] + g[..., 1, 0])
        dens = lam * (exx + eyy) ** 2 + 2.0 * mu * (exx ** 2 + eyy ** 2 + 2.0 * exy ** 2)
        return self._integrate(dens)

    def h1_seminorm_sq(self, u):
        """int |grad u|^2 (Frobenius)."""
        g = self.gradients(u)
        return self._integrate(np.sum(g ** 2, axis=(-2, -1)))

    def l2_norm_sq(self, u):
        """int |u|^2."""
        v = self.values(u)
        return self._integrate(np.sum(v ** 2, axis=-1))

    def area(self):
        return float(np.sum(np.broadcast_to(self.wdet, (self.nel, 4))))


def element_stiffness(xy, young, poisson):
    """8x8 plane-strain Q1 stiffness of one element with nodes xy (4, 2), 2x2 Gauss.

    Independent of Q1Geometry (explicit B matrices); dofs (u1x, u1y, u2x, u2y, ...).
    """
    xy = np.asarray(xy, dtype=float)
    D = plane_strain_D(young, poisson)
    K = np.zeros((8, 8))
    for xi, w in zip(GAUSS_POINTS, GAUSS_WEIGHTS):
        dref = shape_gradients_ref(xi[None, :])[0]   # (4, 2)
        J = xy.T @ dref                              # J_ij = dx_i/dxi_j
        dN = dref @ np.linalg.inv(J)                 # (4, 2) dN_a/dx_i
        B = np.zeros((3, 8))
        B[0, 0::2] = dN[:, 0]
        B[1, 1::2] = dN[:, 1]
        B[2, 0::2] = dN[:, 1]
        B[2, 1::2] = dN[:, 0]
        K += w * np.linalg.det(J) * B.T @ D @ B
    return K


def energy_from_element_matrices(coordinates, connectivity, u, young, poisson):
    """e^T K e summed element by element with element_stiffness (one matrix if all identical).

    A second, independent way to the energy norm, for tests; vectorised over elements.
    """
    coordinates = np.asarray(coordinates, dtype=float)
    conn = np.asarray(connectivity, dtype=np.int64)
    ue = np.asarray(u, dtype=float)[conn].reshape(conn.shape[0], 8)
    xe = coordinates[conn]
    offsets = xe - xe[:, :1, :]
    if np.allclose(offsets, offsets[:1], rtol=0, atol=1e-12 * np.ptp(coordinates)):
        K = element_stiffness(xe[0], young, poisson)
        return float(np.einsum("ei,ij,ej->", ue, K, ue))
    return float(sum(ue[e] @ element_stiffness(xe[e], young, poisson) @ ue[e]
                     for e in range(conn.shape[0])))


def structured_connectivity(nx, ny):
    """0-based (nx*ny, 4) connectivity of the structured numbering of SPEC 8:
    node (i, j) = i + (nx+1) j, element (i, j) = i + nx j, counter-clockwise from bottom-left."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
    n0 = (i + (nx + 1) * j).ravel()
    return np.stack([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1], axis=1)


def prolong_tensor_grid(xs_c, ys_c, u_c, xs_f, ys_f):
    """Bilinear (exact Q1) interpolation of a coarse nodal field onto fine tensor-grid nodes.

    xs_c (nxc+1,), ys_c (nyc+1,) coarse grid lines; u_c (nnode_c, ncomp) numbered x-fastest;
    xs_f, ys_f the fine grid lines (each inside [xs_c[0], xs_c[-1]] etc.). Returns
    (nnode_f, ncomp) numbered x-fastest. On axis-aligned rectangles the Q1 map is affine per
    axis, so this is the coarse finite-element function evaluated at the fine nodes.
    """
    xs_c, ys_c = np.asarray(xs_c, float), np.asarray(ys_c, float)
    xs_f, ys_f = np.asarray(xs_f, float), np.asarray(ys_f, float)
    nxc, nyc = xs_c.size - 1, ys_c.size - 1
    u = np.asarray(u_c, dtype=float).reshape(nyc + 1, nxc + 1, -1)

    def locate(lines, pts):
        k = np.clip(np.searchsorted(lines, pts, side="right") - 1, 0, lines.size - 2)
        t = (pts - lines[k]) / (lines[k + 1] - lines[k])
        return k, t

    ix, tx = locate(xs_c, xs_f)
    iy, ty = locate(ys_c, ys_f)
    tx = tx[None, :, None]
    ty = ty[:, None, None]
    u00 = u[iy[:, None], ix[None, :]]
    u10 = u[iy[:, None], ix[None, :] + 1]
    u11 = u[iy[:, None] + 1, ix[None, :] + 1]
    u01 = u[iy[:, None] + 1, ix[None, :]]
    uf = (1 - tx) * (1 - ty) * u00 + tx * (1 - ty) * u10 + tx * ty * u11 + (1 - tx) * ty * u01
    return uf.reshape(xs_f.size * ys_f.size, -1)


# ---------------------------------------------------------------------------------------------
# Fields on the contact boundary, as functions of the abscissa s.


def contact_pieces(abscissa, values, kind):
    """A multiplier field on Gamma_c as pieces linear on [breaks[k], breaks[k+1]].

    kind 'P1': nodal values, piecewise linear between the nodes x_0 < ... < x_N.
    kind 'P0': one constant per dual cell [z_i, z_{i+1}], z_0 = x_0, z_{N+1} = x_N, other z_i the
               edge midpoints (SPEC 3).
    Returns (breaks (m+1,), left (m,), right (m,)): the value at the left and right end of piece k.
    """
    s = np.asarray(abscissa, dtype=float)
    v = np.asarray(values, dtype=float)
    if s.size != v.size:
        raise ValueError("field and abscissa sizes differ (%d, %d)" % (v.size, s.size))
    if kind == "P1":
        return s, v[:-1], v[1:]
    if kind == "P0":
        z = np.concatenate([s[:1], 0.5 * (s[:-1] + s[1:]), s[-1:]])
        return z, v, v
    raise ValueError("unknown multiplier kind %r" % (kind,))


def _evaluate_pieces(pieces, a, b):
    """Values of a piecewise-linear field at a+ and b- for sub-intervals [a, b] of its pieces."""
    breaks, left, right = pieces
    mid = 0.5 * (a + b)
    k = np.clip(np.searchsorted(breaks, mid, side="right") - 1, 0, left.size - 1)
    x0, x1 = breaks[k], breaks[k + 1]
    span = np.where(x1 > x0, x1 - x0, 1.0)
    ta, tb = (a - x0) / span, (b - x0) / span
    return left[k] + ta * (right[k] - left[k]), left[k] + tb * (right[k] - left[k])


def pieces_difference_norms(pa, pb, rtol=1e-10):
    """(L2 norm, max norm) of field_a - field_b, exactly, on the common refinement.

    pa, pb from contact_pieces (pb may be None: the norms of field_a). The union of both sets
    of breakpoints cuts the interval into sub-intervals on which both fields are linear, so the
    difference d is linear there and int d^2 = (b - a)/3 (d_a^2 + d_a d_b + d_b^2) exactly;
    the max of |d| is attained at a sub-interval end.
    """
    brk = pa[0] if pb is None else np.concatenate([pa[0], pb[0]])
    brk = np.sort(brk)
    length = brk[-1] - brk[0]
    keep = np.concatenate([[True], np.diff(brk) > rtol * max(length, 1e-300)])
    brk = brk[keep]
    if brk.size < 2:
        return 0.0, 0.0
    a, b = brk[:-1], brk[1:]
    da, db = _evaluate_pieces(pa, a, b)
    if pb is not None:
        ea, eb = _evaluate_pieces(pb, a, b)
        da, db = da - ea, db - eb
    l2sq = np.sum((b - a) / 3.0 * (da * da + da * db + db * db))
    return float(np.sqrt(max(l2sq, 0.0))), float(max(np.max(np.abs(da)), np.max(np.abs(db))))


if __name__ == "__main__":
    import sys

    print("contact2d.fem_q1 is a module, not a script (docs/postproc.md): it is used by "
          "contact2d.compare, contact2d.lame and tests/regression/test_static.py", file=sys.stderr)
    sys.exit(2)
