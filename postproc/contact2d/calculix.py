"""CalculiX (ccx, Debian calculix-ccx) as a peer on the Hertz half-disk: the same mesh, penalty contact.

    from contact2d import calculix
    calculix.available()                                  # the ccx executable, or None
    calculix.write_hertz_cylinder("k1_static.h5", "ccx_k1.inp", penalty=1e8)   # CalculixUnsupported
    seconds, log = calculix.solve("ccx_k1.inp")           # runs ccx (one thread), CalculixFailed
    u = calculix.read_displacement("ccx_k1.dat", nnode)   # (nnode, 2) at the end of the step
    f = calculix.internal_forces(x, conn0, u, E, nu)      # K u, element by element (nnode, 2)

The model (write_hertz_cylinder) is the problem of a contact2d run of inputs/hertz_cylinder_p1.nml
or _p0.nml, written from that run's own mesh (/mesh/coordinates and /mesh/connectivity: the same
nodes and elements): CPE4 plane-strain elements (CalculiX expands them to one layer of C3D8, 2x2x2
Gauss: the Q1 stiffness of contact2d, 2x2 Gauss, times a unit thickness), E and nu of the deck;
u_x = 0 on the symmetry side x = 0; u = (0, -delta) on the flat side y = R; the rigid plane y = 0 a
layer of one CPE4 element below it, all of its nodes held; frictionless node-to-surface contact,
slave the run's contact nodes (its Gamma_c), master the top face of the layer, penalty
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with slope `penalty` [MPa/mm] (contact pressure =
penalty x penetration); one static step, small displacements, the load in one increment.
Anything else in the deck (friction, another obstacle, other loads) is refused
(CalculixUnsupported, one line): CalculiX's *FRICTION is Coulomb's law only, so the Tresca paper
scene (a given slip threshold) is not a problem CalculiX can pose.

The contact pressure of the CalculiX solution is recovered from its displacement as contact2d's
P1 pressure is (SPEC section 3): F_n = (K u)_y at the contact nodes (no other load acts there),
lambda = M_c^-1 F_n (contact2d.hertz.p1_pressure). Only numpy (and h5py to read the run).
"""
import os
import shutil
import subprocess
import time

import numpy as np

from .h5 import Run

#: the Dirichlet data of inputs/hertz_cylinder_*.nml this writer models: (boundary, component)
_HERTZ_DIRICHLET = {("top", "x"), ("top", "y"), ("symmetry", "x")}


class CalculixUnsupported(ValueError):
    """The run's problem is not one this module can write as a CalculiX input (one-line message)."""


class CalculixFailed(RuntimeError):
    """ccx ended without a solution (one-line message)."""


def available():
    """The path of the ccx executable, or None."""
    return shutil.which("ccx")


def _dirichlet(deck):
    groups = deck.get("dirichlet", [])
    return groups if isinstance(groups, list) else [groups]


def _num(v):
    """A real as CalculiX reads it: at most 20 characters per number (14 significant digits when
    the shortest round-trip text is longer)."""
    text = repr(float(v))
    return text if len(text) <= 20 else f"{float(v):.13e}"


def _end_value(group):
    """The value a &dirichlet group reaches at the end of its load curve (frictionless contact:
    the static end state depends on the end values only, not on the path)."""
    v = group["values"]
    return float(v[-1] if isinstance(v, list) else v)


def write_hertz_cylinder(run_h5, inp, penalty):
    """Write the CalculiX input `inp` of the problem of the contact2d run `run_h5` (the Hertz
    half-disk on a rigid plane, frictionless) on the run's mesh; penalty slope [MPa/mm]. Returns
    the number of nodes of the body (CalculiX node ids 1..n are the run's nodes in order)."""
    with Run(run_h5) as r:
        deck = r.deck
        x = r.coordinates
        conn = r.connectivity            # 1-based, counter-clockwise
        cn = r.contact_nodes             # 0-based
        E, nu, _ = r.material
    c = deck.get("contact", {})
    if str(c.get("friction", "")).lower() != "frictionless":
        raise CalculixUnsupported(f"{run_h5}: friction '{c.get('friction')}': CalculiX's *FRICTION is Coulomb's "
                                  "law only (no Tresca threshold); only frictionless scenes are written")
    if str(c.get("obstacle", "")).lower() != "plane" or \
            [float(v) for v in c.get("obstacle_normal", [])] != [0.0, 1.0] or \
            [float(v) for v in c.get("obstacle_point", [])] != [0.0, 0.0]:
        raise CalculixUnsupported(f"{run_h5}: only the rigid plane y = 0 (obstacle 'plane', normal (0, 1)) is "
                                  "written for CalculiX")
    if deck.get("traction"):
        raise CalculixUnsupported(f"{run_h5}: tractions are not written for CalculiX")
    dir_ = {(str(g.get("boundary")).lower(), str(g.get("component")).lower()): g for g in _dirichlet(deck)}
    if set(dir_) != _HERTZ_DIRICHLET or _end_value(dir_[("top", "x")]) != 0.0 or \
            _end_value(dir_[("symmetry", "x")]) != 0.0:
        raise CalculixUnsupported(f"{run_h5}: not the Dirichlet data of inputs/hertz_cylinder_*.nml "
                                  "(top: u = (0, -delta); symmetry: u_x = 0)")
    delta = _end_value(dir_[("top", "y")])
    if not penalty > 0:
        raise CalculixUnsupported(f"penalty {penalty}: must be > 0 [MPa/mm]")
    n, ne = len(x), len(conn)
    R = float(np.max(x[:, 1]))
    tol = 1e-9 * R
    top = np.nonzero(np.abs(x[:, 1] - R) <= tol)[0]            # the flat side y = R ('top')
    sym = np.nonzero(np.abs(x[:, 0]) <= tol)[0]                # the symmetry side x = 0
    if len(top) < 2 or len(sym) < 2 or np.min(x[:, 1]) < -tol:
        raise CalculixUnsupported(f"{run_h5}: not the half-disk of inputs/hertz_cylinder.geo")
    xmax = float(np.max(x[cn, 0]))
    # the rigid layer: from x = -R/10 to beyond the contact boundary, one element R/10 thick
    lay = np.array([[-0.1 * R, -0.1 * R], [xmax + 0.1 * R, -0.1 * R], [xmax + 0.1 * R, 0.0], [-0.1 * R, 0.0]])
    lines = ["*HEADING", f"contact2d {os.path.basename(str(run_h5))}: half-disk on a rigid plane, "
             f"penalty {penalty:g} MPa/mm", "*NODE, NSET=NBODY"]
    lines += [f"{i + 1}, {_num(x[i, 0])}, {_num(x[i, 1])}" for i in range(n)]
    lines.append("*NODE, NSET=NRIGID")
    lines += [f"{n + j + 1}, {_num(lay[j, 0])}, {_num(lay[j, 1])}" for j in range(4)]
    lines.append("*ELEMENT, TYPE=CPE4, ELSET=EBODY")
    lines += [f"{e + 1}, {conn[e, 0]}, {conn[e, 1]}, {conn[e, 2]}, {conn[e, 3]}" for e in range(ne)]
    lines += ["*ELEMENT, TYPE=CPE4, ELSET=ERIGID", f"{ne + 1}, {n + 1}, {n + 2}, {n + 3}, {n + 4}"]

    def nset(name, ids):
        lines.append(f"*NSET, NSET={name}")
        ids = [str(int(i) + 1) for i in ids]
        lines.extend(", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16))

    nset("NSYM", sym)
    nset("NTOP", top)
    # the slave surface: the element faces along Gamma_c (CalculiX gives each slave node the area
    # of its faces, so that the contact pressure is penalty x penetration)
    lines += ["*SURFACE, NAME=SSLAVE, TYPE=ELEMENT"]
    lines += [f"{e + 1}, S{face}" for e, face in _faces(conn - 1, cn)]
    lines += [
              # face S3 of a CPE4 element: its nodes 3-4, the top edge y = 0 of the layer
              "*SURFACE, NAME=SRIGID, TYPE=ELEMENT", f"{ne + 1}, S3",
              "*MATERIAL, NAME=BODY", "*ELASTIC", f"{_num(E)}, {_num(nu)}",
              "*SOLID SECTION, ELSET=EBODY, MATERIAL=BODY", "1.",
              "*SOLID SECTION, ELSET=ERIGID, MATERIAL=BODY", "1.",
              "*SURFACE INTERACTION, NAME=FRICTIONLESS",
              # slope K [MPa/mm]; sigma_inf, the tension at large clearance of node-to-surface
              # contact, as small as accepted: separated nodes carry (almost) no force
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{_num(penalty)}, 1e-6",
              "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE", "SSLAVE, SRIGID",
              "*BOUNDARY", "NRIGID, 1, 2", "NSYM, 1, 1", "NTOP, 1, 1", f"NTOP, 2, 2, {_num(delta)}",
              # the whole load in one increment: frictionless and linear elastic, the end state does not
              # depend on the path (ccx cuts the increment if Newton does not settle)
              "*STEP, INC=1000", "*STATIC", "1.0, 1.0",
              "*NODE PRINT, NSET=NBODY", "U", "*END STEP"]
    with open(inp, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return n


def _faces(conn, chain):
    """(element, face number) of each segment of the node chain: CPE4 face Sj joins the element's
    nodes j and j+1 (S4: nodes 4 and 1); conn 0-based."""
    where = {}
    for e, nodes in enumerate(conn):
        for j in range(4):
            where[frozenset((int(nodes[j]), int(nodes[(j + 1) % 4])))] = (e, j + 1)
    faces = []
    for a, b in zip(chain[:-1], chain[1:]):
        key = frozenset((int(a), int(b)))
        if key not in where:
            raise CalculixUnsupported(f"contact nodes {a + 1} and {b + 1} are not an element edge")
        faces.append(where[key])
    return faces


def solve(inp, threads=1):
    """Run ccx on `inp` (a path ending in .inp) in its folder; (wall seconds, stdout). CalculixFailed
    when ccx is missing, fails, or writes no displacement."""
    exe = available()
    if exe is None:
        raise CalculixFailed("ccx not found (Debian: apt-get install calculix-ccx)")
    inp = os.path.abspath(str(inp))
    stem = inp[:-4] if inp.endswith(".inp") else inp
    dat = stem + ".dat"
    if os.path.exists(dat):
        os.remove(dat)
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "CCX_NPROC_EQUATION_SOLVER": str(threads)}
    t0 = time.perf_counter()
    proc = subprocess.run([exe, "-i", os.path.basename(stem)], cwd=os.path.dirname(inp), env=env,
                          capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not os.path.exists(dat):
        err = [ln.strip() for ln in (proc.stdout + proc.stderr).splitlines() if "ERROR" in ln]
        raise CalculixFailed(f"{inp}: ccx failed (exit {proc.returncode}): {err[0] if err else 'no .dat written'}")
    return seconds, proc.stdout


def read_displacement(dat, nnode):
    """(nnode, 2) displacement of the last *NODE PRINT block of U in the .dat file `dat` (nodes 1..nnode;
    the third component of the expanded plane-strain model is 0)."""
    with open(dat) as fh:
        text = fh.read()
    blocks = text.split("displacements (vx,vy,vz)")
    if len(blocks) < 2:
        raise CalculixFailed(f"{dat}: no displacement block")
    u = np.full((nnode, 2), np.nan)
    for line in blocks[-1].splitlines()[1:]:
        s = line.split()
        if len(s) == 4 and s[0].isdigit():
            i = int(s[0]) - 1
            if i < nnode:
                u[i] = float(s[1]), float(s[2])
        elif s and not s[0].isdigit():
            break
    if np.isnan(u).any():
        raise CalculixFailed(f"{dat}: displacement missing for {int(np.isnan(u[:, 0]).sum())} nodes")
    return u


def internal_forces(coordinates, connectivity, u, young, poisson):
    """K u (nnode, 2) [N per unit thickness]: int B^T sigma(u) element by element, 2x2 Gauss, plane
    strain (the Q1 stiffness of contact2d, contact2d.fem_q1); connectivity 0-based."""
    from .fem_q1 import Q1Geometry, plane_strain_lame
    geo = Q1Geometry(coordinates, connectivity)
    lam, mu = plane_strain_lame(young, poisson)
    g = geo.gradients(u)                                       # (nel, gp, comp, dir)
    eps = 0.5 * (g + np.swapaxes(g, -1, -2))
    tr = eps[..., 0, 0] + eps[..., 1, 1]
    sig = 2 * mu * eps + lam * tr[..., None, None] * np.eye(2)
    dndx = np.broadcast_to(geo.dNdx, (geo.nel,) + geo.dNdx.shape[1:])
    wdet = np.broadcast_to(geo.wdet, (geo.nel, 4))
    fe = np.einsum("eg,egad,egcd->eac", wdet, dndx, sig)     # (nel, 4 nodes, 2)
    f = np.zeros((geo.nnode, 2))
    np.add.at(f, geo.connectivity, fe)
    return f


if __name__ == "__main__":
    import sys

    print("contact2d.calculix is a module, not a script (docs/postproc.md): it is used by "
          "postproc/speed_accuracy.py", file=sys.stderr)
    sys.exit(2)
