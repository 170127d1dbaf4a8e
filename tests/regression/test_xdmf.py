#!/usr/bin/env python3
"""The XDMF sidecar describes the HDF5 file exactly: the final state, the contact polyline, the time series.

ParaView is not installed here (check_xdmf_paraview*.py run where it is); this test is the
structural check, with Python's xml module and h5py, of what ParaView's XDMF reader reads:
- every HDF DataItem names the run's .h5, an existing dataset, its exact shape (Dimensions) and
  its number type (Int / Float with Precision 8); every XML DataItem holds prod(Dimensions)
  numbers; a HyperSlab's start/stride/count stays inside its source and its count is the
  declared shape; a Function's shape follows from its arguments ($0 - 1, JOIN of columns);
- every Uniform grid: Topology NumberOfElements = the connectivity's rows (4 nodes for
  quadrilaterals, 2 for polyline segments), connectivity indices inside the geometry's points,
  Node attributes with one value per point, Cell attributes one per element;
- the grids present: `final` (the quadrilaterals, element_count elements), `contact_final`
  (runs with contact), and with output:snapshot_times two temporal collections, `snapshots`
  and `contact_snapshots`, with one grid per /fields/<step> group, times strictly increasing and
  equal to the group's `time` attribute bit for bit (17 significant digits round-trip), each
  requested snapshot time t_k matched by a grid at t_k <= T < t_k + dt (the first step at or
  after it, docs/output.md), the times past the end of the run absent, each grid's arrays from
  its own /fields/<step>;
- the contact polyline indexes the contact nodes: its points are /contact/coordinates, equal
  to /mesh/coordinates at /contact/nodes (bit for bit), its segments join consecutive contact
  nodes (0-1, 1-2, ...), and each segment is no longer than the abscissa step between its ends
  (a chord of Gamma_c is not longer than its arc; equal on a straight Gamma_c);
- the snapshot's contact fields are the multipliers of its forces (SPEC section 3): P1
  M_c pressure = F_n and M_c shear = F_t (consistent 1D mass from the abscissae), P0 D pressure
  = F_n and D shear = F_t (D of SPEC section 3), to 1e-12 of max |F|; status 0 exactly where no
  normal force acts (P1: F_n = 0; P0: mu_n = 0 and F_n = 0).
Cases: Coulomb sliding P1 and P0 (3 snapshots written, one time sharing a step, one after the
end), Lame's ring (Gmsh, curved Gamma_c, one snapshot), uniaxial compression (no contact: no
polyline grids), patch compression (no snapshots: no temporal collection) and its static solve,
the two bodies of inputs/bimaterial_bar.nml (static). Every case: the final grid's cell data
`body` is /mesh/body and its point data `node_body` /mesh/node_body.
"""
import os
import re
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import c2dtest

ERR = 1e-12


def dims_of(item):
    return tuple(int(v) for v in item.get("Dimensions", "").split())


class Sidecar:
    """Structural checks of one sidecar against its HDF5 file; collects failures as text."""

    def __init__(self, t, run, f):
        self.t, self.run, self.f = t, run, f
        self.bad = []
        self.nhdf = 0

    def fail(self, what):
        self.bad.append(what)

    def shape(self, item):
        """The shape a DataItem delivers, checked against its content; None if it is wrong."""
        d = dims_of(item)
        kind = item.get("ItemType", "Uniform")
        kids = item.findall("DataItem")
        if kind == "HyperSlab":
            if len(kids) != 2:
                self.fail("HyperSlab with %d children" % len(kids))
                return None
            sel, src = kids[0], self.shape(kids[1])
            vals = [int(v) for v in (sel.text or "").split()]
            rank = len(src) if src else 0
            if src is None or dims_of(sel) != (3, rank) or len(vals) != 3 * rank:
                self.fail("HyperSlab selection %s for a source of shape %s" % (vals, src))
                return None
            start, stride, count = vals[:rank], vals[rank:2 * rank], vals[2 * rank:]
            if any(s0 < 0 or s0 + (c - 1) * st >= n for s0, st, c, n in zip(start, stride, count, src)):
                self.fail("HyperSlab %s outside its source %s" % (vals, src))
            if tuple(count) != d:
                self.fail("HyperSlab count %s, Dimensions %s" % (count, d))
            return d
        if kind == "Function":
            fun = item.get("Function", "")
            args = [self.shape(k) for k in kids]
            if any(a is None for a in args):
                return None
            m = re.fullmatch(r"\s*JOIN\((.*)\)\s*", fun)
            terms = m.group(1).split(",") if m else [fun]
            refs = [[int(i) for i in re.findall(r"\$(\d+)", term)] for term in terms]
            if any(not r or max(r) >= len(args) for r in refs):
                self.fail("Function %r with %d arguments" % (fun, len(args)))
                return None
            # every term combines arrays of one shape element by element; JOIN puts terms side by side
            shapes = [args[r[0]] for r in refs]
            if any(args[i] != s for r, s in zip(refs, shapes) for i in r):
                self.fail("Function %r on arguments of shapes %s" % (fun, args))
            rows = {s[0] for s in shapes}
            cols = sum(s[1] if len(s) > 1 else 1 for s in shapes)
            want = shapes[0] if not m else (rows.pop(), cols) if len(rows) == 1 else None
            if want != d:
                self.fail("Function %r gives %s, Dimensions %s" % (fun, want, d))
            return d
        fmt = item.get("Format", "XML")
        text = (item.text or "").strip()
        if fmt == "HDF":
            self.nhdf += 1
            fname, _, path = text.partition(":")
            ok_file = fname == os.path.basename(self.run.h5)
            ds = self.f.get(path) if path else None
            if not ok_file or not isinstance(ds, h5py.Dataset):
                self.fail("%s: %s" % (text, "another file" if not ok_file else "no such dataset"))
                return None
            if ds.shape != d:
                self.fail("%s: shape %s, Dimensions %s" % (text, ds.shape, d))
            ntype = item.get("NumberType", "Float")
            kind_ok = (ntype == "Int" and ds.dtype.kind == "i") or \
                (ntype == "Float" and ds.dtype.kind == "f" and int(item.get("Precision", "4")) == ds.dtype.itemsize)
            if not kind_ok:
                self.fail("%s: NumberType %s Precision %s for %s" % (text, ntype, item.get("Precision"), ds.dtype))
            return d
        n = len(text.split())
        if n != int(np.prod(d)):
            self.fail("XML DataItem with %d values, Dimensions %s" % (n, d))
        return d

    def values(self, item):
        """An XML or HDF DataItem's numbers (no Function or HyperSlab)."""
        if item.get("Format", "XML") == "HDF":
            return self.f[item.text.strip().partition(":")[2]][()]
        return np.array([float(v) for v in item.text.split()]).reshape(dims_of(item))

    def uniform(self, grid):
        """Topology, geometry and attributes of one Uniform grid; returns (topology type,
        connectivity (XML only, else None), geometry path, {attribute: HDF path})."""
        name = grid.get("Name")
        topo, geo = grid.find("Topology"), grid.find("Geometry")
        if topo is None or geo is None:
            self.fail("grid %s without Topology or Geometry" % name)
            return None
        gitem = geo.find("DataItem")
        gshape = self.shape(gitem)
        npoint = gshape[0] if gshape else -1
        if geo.get("GeometryType") != "XY" or (gshape and gshape[1] != 2):
            self.fail("grid %s: geometry %s of shape %s" % (name, geo.get("GeometryType"), gshape))
        ttype = topo.get("TopologyType")
        nel = int(topo.get("NumberOfElements", "-1"))
        titem = topo.find("DataItem")
        tshape = self.shape(titem)
        per = {"Quadrilateral": 4, "Polyline": int(topo.get("NodesPerElement", "0"))}.get(ttype)
        if tshape != (nel, per):
            self.fail("grid %s: %s topology of %d elements, connectivity %s" % (name, ttype, nel, tshape))
        conn = None
        if titem.get("ItemType") is None:
            conn = np.asarray(self.values(titem), dtype=int)
            if conn.size and (conn.min() < 0 or conn.max() >= npoint):
                self.fail("grid %s: connectivity outside its %d points" % (name, npoint))
        attrs = {}
        for a in grid.findall("Attribute"):
            ashape = self.shape(a.find("DataItem"))
            want = npoint if a.get("Center") == "Node" else nel
            if not ashape or ashape[0] != want:
                self.fail("grid %s: attribute %s (%s) of shape %s, %d expected" % (
                    name, a.get("Name"), a.get("Center"), ashape, want))
            leaves = [d for d in a.iter("DataItem") if d.get("Format") == "HDF"]
            attrs[a.get("Name")] = {d.text.strip().partition(":")[2] for d in leaves}
        return ttype, conn, gitem.text.strip().partition(":")[2], attrs


def check_sidecar(t, run, snapshot_times, dt, contact, multiplier):
    """Every check of the module docstring on one run's sidecar."""
    try:
        root = ET.parse(run.xmf).getroot()
    except (ET.ParseError, OSError) as exc:
        t.check(run, "sidecar parses as XML", False, "well-formed XML", str(exc))
        return
    with run.open() as f:
        sc = Sidecar(t, run, f)
        domain = root.find("Domain")
        t.check_equal(run, "root element and Domain", ("Xdmf", True), (root.tag, domain is not None))
        grids = {g.get("Name"): g for g in domain.findall("Grid")}
        fields = sorted(((int(k), float(g.attrs["time"])) for k, g in f["fields"].items()),
                        key=lambda kv: kv[1]) if "fields" in f else []
        want = ["final"] + (["contact_final"] if contact else []) + \
            (["snapshots"] + (["contact_snapshots"] if contact else []) if fields else [])
        t.check_equal(run, "top-level grids", want, [g.get("Name") for g in domain.findall("Grid")])
        nel = int(f.attrs["element_count"])
        final = sc.uniform(grids["final"])
        t.check_equal(run, "final: quadrilaterals, element_count", ("Quadrilateral", str(nel)),
                      (final[0], grids["final"].find("Topology").get("NumberOfElements")))
        # the bodies (docs/output.md "/mesh"): cell data body, point data node_body
        t.check_equal(run, "final: body (cell) and node_body (point) from /mesh", ({"/mesh/body"}, {"/mesh/node_body"}),
                      (final[3].get("body"), final[3].get("node_body")))
        if contact:
            check_polyline(t, run, sc, f, grids["contact_final"], "/final/contact/", multiplier)
        if fields:
            check_series(t, run, sc, f, grids, fields, snapshot_times, dt, contact, multiplier)
        # the grids' walks above reached every HDF reference of the file, each once
        nref = sum(1 for d in root.iter("DataItem") if d.get("Format") == "HDF")
        t.check_equal(run, "HDF references checked / in the file", nref, sc.nhdf)
        t.check(run, "every DataItem consistent with the .h5 (%d HDF references)" % sc.nhdf, not sc.bad,
                "no inconsistency", "; ".join(sc.bad[:5]) or "no inconsistency",
                reason="path exists, Dimensions = shape, NumberType = dtype, XML counts, HyperSlab bounds")


def check_polyline(t, run, sc, f, grid, prefix, multiplier, step=None):
    """The contact polyline of one grid: points = contact nodes, segments consecutive, fields."""
    ttype, conn, gpath, attrs = sc.uniform(grid)
    where = "%s (%s)" % (grid.get("Name"), prefix)
    nodes = f["contact/nodes"][()]
    nc = nodes.size
    t.check_equal(run, where + ": polyline of nc - 1 two-node segments", ("Polyline", "2", (nc - 1, 2)),
                  (ttype, grid.find("Topology").get("NodesPerElement"), None if conn is None else conn.shape))
    seg = np.column_stack([np.arange(nc - 1), np.arange(1, nc)])
    t.check(run, where + ": segments join consecutive contact nodes", conn is not None and np.array_equal(conn, seg),
            "[[0 1] [1 2] ...]", "as expected" if conn is not None and np.array_equal(conn, seg) else str(conn))
    if step is None:   # the geometry facts once per run
        pts = f[gpath][()]
        t.check(run, "polyline points = /mesh/coordinates at /contact/nodes (bitwise)",
                gpath == "/contact/coordinates" and np.array_equal(pts, f["mesh/coordinates"][()][nodes - 1]),
                "/contact/coordinates", gpath)
        s = f["contact/abscissa"][()]
        chord = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        t.check_le(run, "segment length - abscissa step (chord <= arc)", chord - np.diff(s),
                   1e-12 * float(s[-1] - s[0]))
    names = {"pressure": "pressure", "shear": "shear", "status": "status", "normal_force": "normal_force",
             "tangential_force": "tangential_force"}
    want = {k: {prefix + v} for k, v in names.items()}
    want["gap"] = {"/contact/gap"}
    t.check_equal(run, where + ": attributes and their datasets", sorted(want.items()), sorted(attrs.items()))
    # the fields are the multipliers of the forces (SPEC section 3)
    def get(k):
        return f[prefix + k][()]
    s = f["contact/abscissa"][()]
    if multiplier == "P0":
        M = c2dtest.dual_coupling(s)
    else:
        h = np.diff(s)
        M = np.zeros((nc, nc))
        for i in range(nc - 1):
            M[i, i] += h[i] / 3
            M[i + 1, i + 1] += h[i] / 3
            M[i, i + 1] = M[i + 1, i] = h[i] / 6
    fn, ft = get("normal_force"), get("tangential_force")
    scale = max(float(np.max(np.abs(fn))), float(np.max(np.abs(ft))), 1e-300)
    t.check_close(run, where + ": M pressure = F_n (%s)" % ("D" if multiplier == "P0" else "M_c"), fn,
                  M @ get("pressure"), rtol=ERR, scale=scale, reason="SPEC section 3; tridiagonal solve round-off")
    t.check_close(run, where + ": M shear = F_t", ft, M @ get("shear"), rtol=ERR, scale=scale,
                  reason="SPEC section 3")
    status = get("status")
    # docs/output.md "Contact status": P0 judges a node on its dual cell (mu_n > 0), and under
    # Coulomb also counts a node with a nodal F_n > 0 from a neighbouring cell; elsewhere F_n > 0
    if multiplier == "P0":
        coulomb = c2dtest.attr_str(f["contact"].attrs["friction"]) == "coulomb"
        carries = (get("pressure") > 0) | ((fn > 0) & coulomb)
    else:
        carries = fn > 0
    t.check(run, where + ": status 0 exactly where no normal force acts",
            np.array_equal(status == 0, ~carries) and set(np.unique(status)) <= {0, 1, 2},
            "status in {0,1,2}, 0 <=> no force", str(status.tolist()))


def check_series(t, run, sc, f, grids, fields, snapshot_times, dt, contact, multiplier):
    """The temporal collections: one grid per /fields group, its time, its own arrays."""
    series = grids["snapshots"]
    t.check_equal(run, "snapshots: a temporal collection", ("Collection", "Temporal"),
                  (series.get("GridType"), series.get("CollectionType")))
    members = series.findall("Grid")
    times = [float(g.find("Time").get("Value")) for g in members]
    t.check_equal(run, "snapshots: one grid per /fields group, times = its 'time' attribute",
                  [tm for _, tm in fields], times, reason="17-digit round trip")
    t.check(run, "snapshot times strictly increasing", all(b > a for a, b in zip(times, times[1:])),
            "increasing", str(times))
    end = float(f.attrs["final_time"])
    for tk in snapshot_times:
        hit = [tm for tm in times if tk * (1 - 1e-12) <= tm < tk + dt * (1 + 1e-9)]
        if tk <= end:
            t.check(run, "requested snapshot %.6g s: a grid at t_k <= T < t_k + dt" % tk, len(hit) == 1,
                    "one grid", str(hit))
        else:
            t.check(run, "requested snapshot %.6g s (after the end, %.6g s): no grid" % (tk, end), not hit, "none", str(hit))
    for g, (step, tm) in zip(members, fields):
        _, _, _, attrs = sc.uniform(g)
        t.check_equal(run, "grid %s: displacement from its own /fields group" % g.get("Name"),
                      {"displacement": {"/fields/%d/displacement" % step}}, attrs)
    if contact:
        cs = grids["contact_snapshots"]
        cm = cs.findall("Grid")
        t.check_equal(run, "contact_snapshots: temporal, same times",
                      ("Collection", "Temporal", times),
                      (cs.get("GridType"), cs.get("CollectionType"), [float(g.find("Time").get("Value")) for g in cm]))
        for g, (step, _) in zip(cm, fields):
            check_polyline(t, run, sc, f, g, "/fields/%d/contact_" % step, multiplier, step=step)


CASES = [
    # name, deck, extra args, snapshot times, contact
    ("coulomb_p1", "coulomb_sliding_p1.nml", [1e-6, 2e-6, 3e-6, 3.001e-6, 1.0], True),
    ("coulomb_p0", "coulomb_sliding_p0.nml", [1e-6, 2e-6, 3e-6, 3.001e-6, 1.0], True),
    ("lame_p1", "lame_cavity_p1.nml", [2e-6], True),
    ("uniaxial", "uniaxial_compression.nml", [1e-6], False),
    ("patch_p1", "patch_compression_p1.nml", [], True),
]


def body(t):
    for name, deck, times, contact in CASES:
        print()
        print("## case %s" % name)
        extra = ["--set", "output:snapshot_times=" + ",".join(repr(x) for x in times)] if times else []
        run = t.run(t.deck(deck), *extra, name=name)
        t.expect_exit(run, 0)
        t.expect_output(run)
        with run.open() as f:
            dt = float(f.attrs["dt"])
            multiplier = c2dtest.attr_str(f.attrs["multiplier"])
        check_sidecar(t, run, times, dt, contact, multiplier)
    print()
    print("## case patch_static (the static engine: no snapshots)")
    run = t.run(t.deck("patch_compression_p0.nml"), "--static", name="patch_static")
    t.expect_exit(run, 0)
    check_sidecar(t, run, [], 0.0, True, "P0")
    print()
    print("## case bimaterial_static (two bodies: body and node_body of each)")
    run = t.run(t.deck("bimaterial_bar.nml"), "--static", name="bimaterial_static")
    t.expect_exit(run, 0)
    check_sidecar(t, run, [], 0.0, False, "none")


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
