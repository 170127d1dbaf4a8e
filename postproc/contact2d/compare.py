#!/usr/bin/python3
"""Compare the end states of two contact2d runs on nested structured meshes (SPEC section 9).

    postproc/compare.py A.h5 B.h5 [--json OUT.json [--force]] [--allow-mixed-multipliers]

or, from Python (PYTHONPATH=postproc, or a script in postproc/):

    from contact2d.compare import compare, CompareError
    res = compare("p1_k2.h5", "p1_k4.h5")
    res["errors"]["energy"], res["errors"]["pressure_l2"]

Reference. The finer of the two files is the reference; with equal meshes it is B (the second
argument), so `compare.py run.h5 reference.h5` reads naturally. Every relative error is
||u_ref - P u_other|| / ||u_ref||, all norms taken on the reference (finer) mesh.

Measures (all exact for the discrete fields, no sampling):
  energy       ||e||_a, a(u,v) = int eps(u):C:eps(v), plane strain (E, nu of the decks): the norm
               of the fine-mesh Q1 stiffness, e^T K e, 2x2 Gauss as in contact2d
  h1           |e|_1 = (int |grad e|^2)^1/2
  l2           (int |e|^2)^1/2
  max          max over the body of |e| (Euclidean), attained at the fine nodes
  pressure_l2  (int_Gc (p_a - p_b)^2 ds)^1/2, shear_l2 likewise: P1 fields are piecewise linear
               between contact nodes, P0 fields constant on dual cells [z_i, z_{i+1}]; the
               integral is exact on the common refinement of the two partitions
  pressure_max, shear_max  sup over Gamma_c of |p_a - p_b| (one-sided limits at cell ends)
e = u_fine - P u_coarse, P the bilinear (Q1) prolongation of the coarse solution onto the fine
nodes, exact because every fine element lies in one coarse element.

Refusals (exit status 2, one line on stderr; CompareError from compare()): meshes that are not
structured rectangles numbered as SPEC 8, different domains, different base nx:ny ratios,
a non-integer refinement ratio (any integer is accepted, not only powers of 2), coarse grid
lines that are not fine grid lines, different material (E, nu), different multiplier kinds
(P1 against P0 only with --allow-mixed-multipliers / allow_mixed_multipliers=True), a contact
boundary in one file only or contact boundaries that are not the same nested chain, a run that
did not finish (status 'running': a crashed run's .partial file). --json refuses, before comparing,
either input, an existing file (unless --force) and a folder that does not exist; the JSON is
written to a temporary file beside the target and moved into place (os.replace).
Differences in the loading, obstacle or friction data are reported as warnings, as are runs that
did not converge; solver settings may differ freely (that is what speed-versus-accuracy studies
compare).
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np

from . import fem_q1
from .h5 import Run
from .outfile import OutputRefused, check_target, replacing

ERROR_KEYS = ("energy", "h1", "l2", "max", "pressure_l2", "pressure_max", "shear_l2", "shear_max")
_LABELS = {
    "energy": "displacement energy norm",
    "h1": "displacement H1 seminorm",
    "l2": "displacement L2 norm",
    "max": "displacement max norm",
    "pressure_l2": "contact pressure L2",
    "pressure_max": "contact pressure max",
    "shear_l2": "contact shear L2",
    "shear_max": "contact shear max",
}
GEOMETRY_RTOL = 1e-8          # relative to the domain diameter
MATERIAL_RTOL = 1e-12


class CompareError(ValueError):
    """The two files cannot be compared (not nested, different material, ...)."""


def _str(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        return _str(v[()])
    return str(v)


def _load(path):
    """Everything compare() needs from one output file, as a plain dict."""
    if not os.path.isfile(path):
        raise CompareError("%s: no such file" % path)
    try:
        run = Run(path)
    except OSError as exc:
        raise CompareError("%s: not a readable HDF5 file (%s)" % (path, exc))
    with run:
        f = run.file
        status = _str(run.attrs.get("status", "")).strip()
        if status == "running":
            raise CompareError("%s: the run did not finish (status 'running')" % path)
        for name in ("mesh/coordinates", "mesh/connectivity", "final/displacement"):
            if name not in f:
                raise CompareError("%s: no /%s (not a contact2d output file?)" % (path, name))
        d = {"path": path, "deck": run.deck, "attrs": run.attrs}
        d["coordinates"] = run.coordinates.astype(float)
        d["connectivity"] = run.connectivity.astype(np.int64) - 1
        d["displacement"] = run.displacement.astype(float)
        mult = run.attrs.get("multiplier", run.deck.get("contact", {}).get("multiplier"))
        d["multiplier"] = None if mult is None else _str(mult).strip().upper()
        d["has_contact"] = "contact/nodes" in f and "final/contact/pressure" in f
        if d["has_contact"]:
            d["contact_nodes"] = run.contact_nodes.astype(np.int64)
            d["abscissa"] = run.abscissa.astype(float)
            for name in ("pressure", "shear", "status", "normal_force", "tangential_force"):
                d[name] = run.contact(name) if "final/contact/" + name in f else None
        conv = run.attrs.get("converged")
        d["converged"] = None if conv is None else bool(int(np.asarray(conv).ravel()[0]))
    mesh = d["deck"].get("mesh", {})
    nx, ny = d["attrs"].get("nx"), d["attrs"].get("ny")
    if nx is None and "nx" in mesh:
        lev = int(mesh.get("level", 0))
        nx, ny = int(mesh["nx"]) * 2 ** lev, int(mesh["ny"]) * 2 ** lev
    if nx is None:  # infer from the node numbering: the first row shares node 0's y
        y = d["coordinates"][:, 1]
        first = np.flatnonzero(np.abs(y - y[0]) > GEOMETRY_RTOL * max(np.ptp(y), 1e-300))
        nxp1 = int(first[0]) if first.size else y.size
        nx, ny = nxp1 - 1, y.size // max(nxp1, 1) - 1
    d["nx"], d["ny"] = int(np.asarray(nx).ravel()[0]), int(np.asarray(ny).ravel()[0])
    d["level"] = int(mesh["level"]) if "level" in mesh else None
    mat = d["deck"].get("material", {})
    d["young"] = float(mat["young"]) if "young" in mat else None
    d["poisson"] = float(mat["poisson"]) if "poisson" in mat else None
    return d


def _grid(d):
    """Check that d's mesh is a structured rectangle grid (SPEC 8); return its lines (xs, ys)."""
    nx, ny, x = d["nx"], d["ny"], d["coordinates"]
    name = os.path.basename(d["path"])
    if nx < 1 or ny < 1:
        raise CompareError("%s: a Gmsh mesh (mesh:file); compare.py compares runs on the built-in "
                           "rectangle's nested structured meshes only" % name)
    if x.shape != ((nx + 1) * (ny + 1), 2):
        raise CompareError("%s: %d nodes do not form a structured %d x %d mesh"
                           % (name, x.shape[0], nx, ny))
    conn = d["connectivity"]
    if conn.shape != (nx * ny, 4) or not np.array_equal(conn, fem_q1.structured_connectivity(nx, ny)):
        raise CompareError("%s: connectivity is not the structured %d x %d numbering of SPEC 8"
                           % (name, nx, ny))
    xs, ys = x[: nx + 1, 0].copy(), x[:: nx + 1, 1].copy()
    diam = max(xs[-1] - xs[0], ys[-1] - ys[0])
    gx, gy = np.meshgrid(xs, ys, indexing="xy")
    if (not (np.all(np.diff(xs) > 0) and np.all(np.diff(ys) > 0)) or
            np.max(np.abs(gx.ravel() - x[:, 0])) > GEOMETRY_RTOL * diam or
            np.max(np.abs(gy.ravel() - x[:, 1])) > GEOMETRY_RTOL * diam):
        raise CompareError("%s: the mesh is not a structured rectangle grid (tensor-product "
                           "lines)" % name)
    return xs, ys


def _check_nested(c, f, xs_c, ys_c, xs_f, ys_f):
    """Refinement ratio r of the fine mesh f over the coarse mesh c, or CompareError."""
    nc, nf = os.path.basename(c["path"]), os.path.basename(f["path"])
    diam = max(xs_f[-1] - xs_f[0], ys_f[-1] - ys_f[0])
    tol = GEOMETRY_RTOL * diam
    dom_c = (xs_c[0], xs_c[-1], ys_c[0], ys_c[-1])
    dom_f = (xs_f[0], xs_f[-1], ys_f[0], ys_f[-1])
    if max(abs(a - b) for a, b in zip(dom_c, dom_f)) > tol:
        raise CompareError("different domains: %s is [%g, %g] x [%g, %g], %s is [%g, %g] x [%g, %g]"
                           % ((nc,) + dom_c + (nf,) + dom_f))
    if c["nx"] * f["ny"] != f["nx"] * c["ny"]:
        raise CompareError("different nx:ny ratios: %s is %d x %d, %s is %d x %d"
                           % (nc, c["nx"], c["ny"], nf, f["nx"], f["ny"]))
    if f["nx"] % c["nx"] != 0:
        raise CompareError("not nested: refinement ratio %d/%d between %s and %s is not an integer"
                           % (f["nx"], c["nx"], nf, nc))
    r = f["nx"] // c["nx"]
    if (np.max(np.abs(xs_f[::r] - xs_c)) > tol or np.max(np.abs(ys_f[::r] - ys_c)) > tol):
        raise CompareError("not nested: the grid lines of %s are not grid lines of %s" % (nc, nf))
    return r


def _check_contact(c, f, r):
    nc, nf = os.path.basename(c["path"]), os.path.basename(f["path"])
    if c["has_contact"] != f["has_contact"]:
        which = nc if c["has_contact"] else nf
        raise CompareError("contact boundaries differ: only %s has a contact boundary" % which)
    if not c["has_contact"]:
        return
    xc = c["coordinates"][c["contact_nodes"]]
    xf = f["coordinates"][f["contact_nodes"]]
    diam = np.ptp(f["coordinates"])
    tol = GEOMETRY_RTOL * diam
    if (xf.shape[0] - 1 != r * (xc.shape[0] - 1) or
            np.max(np.abs(xf[::r] - xc)) > tol or
            np.max(np.abs(f["abscissa"][::r] - c["abscissa"])) > tol):
        raise CompareError("contact boundaries differ: %s has %d contact nodes from (%g, %g) to "
                           "(%g, %g), %s has %d from (%g, %g) to (%g, %g), not the same nested chain"
                           % (nc, xc.shape[0], xc[0, 0], xc[0, 1], xc[-1, 0], xc[-1, 1],
                              nf, xf.shape[0], xf[0, 0], xf[0, 1], xf[-1, 0], xf[-1, 1]))
    for d, n in ((c, nc), (f, nf)):
        ncon = d["contact_nodes"].size
        for name in ("pressure", "shear"):
            if d[name] is None or d[name].shape != (ncon,):
                raise CompareError("%s: /final/contact/%s missing or not of size %d" % (n, name, ncon))


def _deck_warnings(a, b):
    """Differences in the problem data (not mesh, solver, output) of the two effective decks."""
    out = []
    da, db = a["deck"], b["deck"]
    for group in ("dirichlet", "traction", "contact", "material"):
        ga, gb = da.get(group), db.get(group)
        if group == "contact" and isinstance(ga, dict) and isinstance(gb, dict):
            ga = {k: v for k, v in ga.items() if k != "multiplier"}
            gb = {k: v for k, v in gb.items() if k != "multiplier"}
        if group == "material" and isinstance(ga, dict) and isinstance(gb, dict):
            ga = {k: v for k, v in ga.items() if k not in ("young", "poisson")}
            gb = {k: v for k, v in gb.items() if k not in ("young", "poisson")}
        if ga != gb:
            if isinstance(ga, dict) and isinstance(gb, dict):
                keys = sorted(k for k in set(ga) | set(gb) if ga.get(k) != gb.get(k))
                out.append("decks differ in &%s: %s" % (group, ", ".join(
                    "%s = %s / %s" % (k, ga.get(k), gb.get(k)) for k in keys)))
            else:
                out.append("decks differ in &%s" % group)
    return out


def _rel(absval, refval):
    if refval > 0:
        return absval / refval
    return 0.0 if absval == 0 else math.inf


def _summary(d, xs, ys):
    def size(lines):  # largest spacing; extent / n on a uniform grid (no round-off noise)
        dl = np.diff(lines)
        uniform = np.ptp(dl) <= GEOMETRY_RTOL * (lines[-1] - lines[0])
        return (lines[-1] - lines[0]) / dl.size if uniform else np.max(dl)

    s = {"path": d["path"], "multiplier": d["multiplier"], "nx": d["nx"], "ny": d["ny"],
         "level": d["level"], "h": float(max(size(xs), size(ys))),  # largest element edge
         "converged": d["converged"]}
    if d["has_contact"]:
        for name, key in (("normal_force", "normal_force_total"),
                          ("tangential_force", "tangential_force_total")):
            s[key] = None if d[name] is None else float(np.sum(d[name]))
        st = d["status"]
        s["contact_end"] = (float(d["abscissa"][np.flatnonzero(st > 0)[-1]])
                            if st is not None and np.any(st > 0) else None)
        s["slip_nodes"] = None if st is None else int(np.sum(st == 2))
        s["stick_nodes"] = None if st is None else int(np.sum(st == 1))
    return s


def compare(a_path, b_path, allow_mixed_multipliers=False):
    """SPEC 9 measures between two output files; see the module docstring.

    Returns a dict: 'a', 'b' (per-file summaries: path, multiplier, nx, ny, level, h, converged,
    normal_force_total, tangential_force_total, contact_end = abscissa of the last node not
    separated, slip_nodes, stick_nodes), 'reference' ('a' or 'b': the finer file, 'b' on a tie),
    'coarse' (the other key), 'refinement_ratio', 'errors' (relative, keys ERROR_KEYS),
    'absolute' (the same, absolute), 'reference_norms' (the norms of the reference fields),
    'warnings' (list of str), 'seconds'. Contact keys are None when neither file has contact.
    Raises CompareError when the files cannot be compared.
    """
    t0 = time.perf_counter()
    a, b = _load(str(a_path)), _load(str(b_path))
    na, nb = os.path.basename(a["path"]), os.path.basename(b["path"])
    if a["multiplier"] != b["multiplier"] and (a["has_contact"] or b["has_contact"]):
        if not allow_mixed_multipliers:
            raise CompareError("multiplier kinds differ (%s is %s, %s is %s); pass "
                               "--allow-mixed-multipliers to compare them"
                               % (na, a["multiplier"], nb, b["multiplier"]))
    for key in ("young", "poisson"):
        va, vb = a[key], b[key]
        if va is None and vb is None:
            raise CompareError("no material (%s) in either deck: the energy norm needs E and nu" % key)
        if va is None or vb is None:
            continue
        if abs(va - vb) > MATERIAL_RTOL * max(abs(va), abs(vb)):
            raise CompareError("material differs: %s = %r in %s, %r in %s" % (key, va, na, vb, nb))
    young = a["young"] if a["young"] is not None else b["young"]
    poisson = a["poisson"] if a["poisson"] is not None else b["poisson"]

    grid_a, grid_b = _grid(a), _grid(b)
    if a["nx"] > b["nx"]:
        fine, coarse, fkey, ckey, (xs_f, ys_f), (xs_c, ys_c) = a, b, "a", "b", grid_a, grid_b
    else:
        fine, coarse, fkey, ckey, (xs_f, ys_f), (xs_c, ys_c) = b, a, "b", "a", grid_b, grid_a
    r = _check_nested(coarse, fine, xs_c, ys_c, xs_f, ys_f)
    _check_contact(coarse, fine, r)

    warnings = _deck_warnings(a, b)
    for d, n in ((a, na), (b, nb)):
        if d["converged"] is False:
            warnings.append("%s did not converge (status %s)" % (n, _str(d["attrs"].get("status", "?"))))
        for key in ("young", "poisson"):
            if d[key] is None:
                warnings.append("%s: no material %s in its deck; used the other file's" % (n, key))
    if a["multiplier"] != b["multiplier"] and (a["has_contact"] or b["has_contact"]):
        warnings.append("comparing %s (%s) with %s (%s) multipliers"
                        % (a["multiplier"], na, b["multiplier"], nb))

    # displacement
    u_ref = fine["displacement"]
    u_pro = (coarse["displacement"] if r == 1 else
             fem_q1.prolong_tensor_grid(xs_c, ys_c, coarse["displacement"], xs_f, ys_f))
    err = u_ref - u_pro
    geo = fem_q1.Q1Geometry(fine["coordinates"], fine["connectivity"])
    absolute, refn = {}, {}
    absolute["energy"] = math.sqrt(max(geo.energy_norm_sq(err, young, poisson), 0.0))
    refn["energy"] = math.sqrt(max(geo.energy_norm_sq(u_ref, young, poisson), 0.0))
    absolute["h1"] = math.sqrt(geo.h1_seminorm_sq(err))
    refn["h1"] = math.sqrt(geo.h1_seminorm_sq(u_ref))
    absolute["l2"] = math.sqrt(geo.l2_norm_sq(err))
    refn["l2"] = math.sqrt(geo.l2_norm_sq(u_ref))
    absolute["max"] = float(np.max(np.linalg.norm(err, axis=1)))
    refn["max"] = float(np.max(np.linalg.norm(u_ref, axis=1)))

    # contact fields on the common refinement
    for name in ("pressure", "shear"):
        if fine["has_contact"]:
            pf = fem_q1.contact_pieces(fine["abscissa"], fine[name], fine["multiplier"])
            pc = fem_q1.contact_pieces(coarse["abscissa"], coarse[name], coarse["multiplier"])
            absolute[name + "_l2"], absolute[name + "_max"] = fem_q1.pieces_difference_norms(pf, pc)
            refn[name + "_l2"], refn[name + "_max"] = fem_q1.pieces_difference_norms(pf, None)
        else:
            absolute[name + "_l2"] = absolute[name + "_max"] = None
            refn[name + "_l2"] = refn[name + "_max"] = None
    errors = {k: (None if absolute[k] is None else _rel(absolute[k], refn[k])) for k in ERROR_KEYS}

    return {
        "a": _summary(a, *grid_a), "b": _summary(b, *grid_b),
        "reference": fkey, "coarse": ckey, "refinement_ratio": r,
        "errors": errors, "absolute": absolute, "reference_norms": refn,
        "energy_material": {"young": young, "poisson": poisson},
        "warnings": warnings, "seconds": time.perf_counter() - t0,
    }


def _fmt(v, spec="%.4e"):
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return spec % v
    return str(v)


def format_table(res):
    """The printed report of compare()'s result."""
    lines = []
    for key in ("a", "b"):
        s = res[key]
        role = "reference (finer)" if key == res["reference"] else "prolonged onto the reference mesh"
        if res["refinement_ratio"] == 1:
            role = "reference (same mesh; B is the reference)" if key == res["reference"] else "compared"
        lev = "" if s["level"] is None else ", level %d" % s["level"]
        lines.append("%s: %s  (%s, %d x %d%s, h = %.4g) %s"
                     % (key.upper(), s["path"], s["multiplier"], s["nx"], s["ny"], lev, s["h"], role))
    lines.append("refinement ratio %d; errors = reference - P(other), norms on the reference mesh"
                 % res["refinement_ratio"])
    lines.append("%-28s %12s %12s %12s" % ("quantity", "relative", "absolute", "ref. norm"))
    for k in ERROR_KEYS:
        if res["absolute"][k] is None:
            continue
        lines.append("%-28s %12s %12s %12s" % (_LABELS[k], _fmt(res["errors"][k]),
                                                _fmt(res["absolute"][k]), _fmt(res["reference_norms"][k])))
    rows = (("converged", "converged"), ("total normal force", "normal_force_total"),
            ("total tangential force", "tangential_force_total"),
            ("last contact abscissa", "contact_end"), ("stick / slip nodes", None))
    if "normal_force_total" in res["a"]:
        lines.append("%-28s %14s %14s" % ("", "A", "B"))
        for label, key in rows:
            if key is None:
                va = "%s / %s" % (res["a"]["stick_nodes"], res["a"]["slip_nodes"])
                vb = "%s / %s" % (res["b"]["stick_nodes"], res["b"]["slip_nodes"])
            else:
                va, vb = _fmt(res["a"].get(key), "%.6g"), _fmt(res["b"].get(key), "%.6g")
            lines.append("%-28s %14s %14s" % (label, va, vb))
    for w in res["warnings"]:
        lines.append("warning: " + w)
    return "\n".join(lines)


def _jsonable(obj):
    if isinstance(obj, dict):
        return {k: _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        return float(obj) if math.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="SPEC 9 error measures between two contact2d output files on nested "
                    "structured meshes (the finer file is the reference; B on a tie).")
    ap.add_argument("a", help="first output file (.h5)")
    ap.add_argument("b", help="second output file (.h5); the reference when the meshes are equal")
    ap.add_argument("--json", metavar="OUT.json",
                    help="also write the results as JSON (never one of the inputs; an existing file "
                         "only with --force)")
    ap.add_argument("--force", action="store_true", help="let --json replace an existing file")
    ap.add_argument("--allow-mixed-multipliers", action="store_true",
                    help="allow comparing a P1 run with a P0 run")
    args = ap.parse_args(argv)
    try:
        if args.json:
            check_target(args.json, inputs=(args.a, args.b), force=args.force)
        res = compare(args.a, args.b, allow_mixed_multipliers=args.allow_mixed_multipliers)
    except (CompareError, OutputRefused) as exc:
        print("compare.py: refused: %s" % exc, file=sys.stderr)
        return 2
    if args.json:
        try:
            with replacing(args.json, force=args.force) as tmp:
                with open(tmp, "w") as fh:
                    json.dump(_jsonable(res), fh, indent=2)
                    fh.write("\n")
        except (OutputRefused, OSError) as exc:
            print("compare.py: --json not written: %s" % exc, file=sys.stderr)
            return 2
    try:
        print(format_table(res))
        sys.stdout.flush()
    except BrokenPipeError:  # e.g. piped into head
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0


if __name__ == "__main__":
    sys.exit(main())
