"""Regression 7: the output contract of SPEC section 8 on one contact run, and the output-file
rules of the command line.

Run inputs/tresca_sliding_p1.nml (contact, two load stages, one snapshot) without -o in an empty
directory, then check:
- <deck stem>.h5 and <deck stem>.xmf appear in the current directory;
- every SPEC section 8 name exists with the documented shape (root attributes, /mesh, /contact,
  /history, /final, /final/contact, /fields/<step>); the structured numbering of nodes and elements
  is the one SPEC section 8 gives; history series are 1D, extendible (maxshape (None,)), chunked
  and of one length; every dataset has a 'units' attribute;
- the XDMF sidecar parses as XML and every HDF reference in it names a dataset of the .h5 file
  with the declared dimensions;
- a second run without --force fails (exit 1, one error line) and leaves both files byte for byte
  intact; with --force it succeeds and rewrites the file.
"""
import hashlib
import os
import time
import xml.etree.ElementTree as ET

import numpy as np

import c2dtest

DECK = "tresca_sliding_p1.nml"
STEM = "tresca_sliding_p1"

ROOT_ATTRS_STR = ["program_version", "deck", "effective_deck", "multiplier", "status"]
ROOT_ATTRS_NUM = ["dt", "dt_critical", "steps", "converged", "wall_seconds", "element_count", "node_count",
                  "nx", "ny", "omega_max_element", "omega_max_power", "dt_stable_estimate"]
HISTORY = ["time", "kinetic_energy", "strain_energy", "external_work", "friction_dissipation",
           "damping_dissipation", "energy_balance_error", "residual", "normal_force_total",
           "tangential_force_total", "normal_contact_work", "step", "damping_alpha", "stick_increment_max"]
FINAL_CONTACT = ["normal_force", "tangential_force", "pressure", "shear", "status"]


def sha256(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def body(t):
    cwd = t.subdir("default_name")
    run = t.run(t.deck(DECK), cwd=cwd, output=None)
    t.expect_exit(run, 0)
    h5 = os.path.join(cwd, STEM + ".h5")
    xmf = os.path.join(cwd, STEM + ".xmf")
    t.check_equal(run, "files written without -o (in the cwd)", sorted([STEM + ".h5", STEM + ".xmf"]),
                  sorted(os.listdir(cwd)))
    t.expect_output(run)
    where = run

    with run.open() as f:
        a = f.attrs
        # ---- root attributes ------------------------------------------------------------------
        for name in ROOT_ATTRS_STR + ROOT_ATTRS_NUM:
            t.check(where, "root attribute '%s'" % name, name in a, "present",
                    "present" if name in a else "missing")
        missing = [n for n in ROOT_ATTRS_STR + ROOT_ATTRS_NUM if n not in a]
        t.require(not missing, "root attributes missing: " + ", ".join(missing))
        for name in ROOT_ATTRS_STR:
            t.check(where, "root attribute '%s' is a string" % name,
                    isinstance(a[name], (str, bytes)) or getattr(a[name], "dtype", None) is not None
                    and a[name].dtype.kind in "SUO", "a string", type(a[name]).__name__)
        for name in ROOT_ATTRS_NUM:
            ok = np.ndim(a[name]) == 0 and np.issubdtype(np.asarray(a[name]).dtype, np.number)
            t.check(where, "root attribute '%s' is a number" % name, ok, "a scalar number", repr(a[name]))
        multiplier = c2dtest.attr_str(a["multiplier"])
        status = c2dtest.attr_str(a["status"])
        converged = int(a["converged"])
        t.check_equal(where, "multiplier", "P1", multiplier)
        t.check(where, "converged is 0/1 and agrees with status", (converged, status) in
                ((1, "converged"), (0, "not converged"), (0, "blow-up")),
                "(1, 'converged') | (0, 'not converged') | (0, 'blow-up')", (converged, status))
        t.check(where, "program_version non-empty", len(c2dtest.attr_str(a["program_version"])) > 0,
                "non-empty", repr(c2dtest.attr_str(a["program_version"])))
        with open(t.deck(DECK)) as fh:
            deck_text = [line.rstrip() for line in fh.read().splitlines()]
        stored = [line.rstrip() for line in c2dtest.attr_str(a["deck"]).splitlines()]
        t.check_lines_equal(where, "'deck' attribute = the deck file's text (trailing blanks ignored)",
                            deck_text, stored)
        t.check_close(where, "dt_critical = 2 / omega_max_element", 2 / float(a["omega_max_element"]),
                      float(a["dt_critical"]), rtol=1e-14, reason="same number, round-off of one division")
        t.check_close(where, "dt_stable_estimate = 2 / omega_max_power", 2 / float(a["omega_max_power"]),
                      float(a["dt_stable_estimate"]), rtol=1e-14, reason="same number, round-off of one division")

        # ---- /mesh ------------------------------------------------------------------------------
        nx, ny = int(a["nx"]), int(a["ny"])
        nnode, nel = int(a["node_count"]), int(a["element_count"])
        t.check_equal(where, "node_count = (nx+1)(ny+1)", (nx + 1) * (ny + 1), nnode)
        t.check_equal(where, "element_count = nx ny", nx * ny, nel)
        x = f["mesh/coordinates"]
        conn = f["mesh/connectivity"]
        t.check_equal(where, "/mesh/coordinates shape", (nnode, 2), x.shape)
        t.check_equal(where, "/mesh/connectivity shape", (nel, 4), conn.shape)
        t.check(where, "/mesh/connectivity integer", conn.dtype.kind in "iu", "integer", str(conn.dtype))
        x, conn = x[()], conn[()]
        eff = c2dtest.parse_effective_deck(c2dtest.attr_str(a["effective_deck"]))
        lx, ly = float(eff["mesh"]["lx"]), float(eff["mesh"]["ly"])
        i, j = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1))          # x-fastest
        x_expected = np.column_stack([i.ravel() * lx / nx, j.ravel() * ly / ny])
        t.check_close(where, "node (i, j) has id i + (nx+1) j + 1 at (i lx/nx, j ly/ny)", x_expected, x,
                      atol=1e-12 * max(lx, ly), reason="structured mesher: round-off of i*h")
        ie, je = np.meshgrid(np.arange(nx), np.arange(ny))
        ie, je = ie.ravel(), je.ravel()
        n = lambda ii, jj: ii + (nx + 1) * jj + 1                       # noqa: E731
        conn_expected = np.column_stack([n(ie, je), n(ie + 1, je), n(ie + 1, je + 1), n(ie, je + 1)])
        t.check_equal(where, "element (i, j) = id i + nx j + 1, 1-based, CCW from its bottom-left node",
                      True, bool(np.array_equal(conn_expected, conn)))
        xe = x[conn - 1]                                                # (nel, 4, 2)
        area = 0.5 * np.sum(xe[:, :, 0] * np.roll(xe[:, :, 1], -1, axis=1)
                            - np.roll(xe[:, :, 0], -1, axis=1) * xe[:, :, 1], axis=1)
        t.check_ge(where, "signed element areas (counter-clockwise)", area, 0.0)

        # ---- /contact -----------------------------------------------------------------------------
        for name in ("nodes", "abscissa", "weight", "gap"):
            path = "contact/" + name
            t.require(path in f, "/%s exists" % path)
        nc = f["contact/nodes"].shape[0] if f["contact/nodes"].ndim == 1 else -1
        for name in ("nodes", "abscissa", "weight", "gap"):
            t.check_equal(where, "/contact/%s shape" % name, (nc,), f["contact/" + name].shape)
        ids = f["contact/nodes"][()]
        t.check(where, "/contact/nodes 1-based ids", ids.min() >= 1 and ids.max() <= nnode,
                "in 1..%d" % nnode, "%d..%d" % (ids.min(), ids.max()))
        t.check_ge(where, "/contact/abscissa increments (ordered along Gamma_c)", np.diff(f["contact/abscissa"][()]),
                   1e-300)

        # ---- /history -----------------------------------------------------------------------------
        lengths = set()
        for name in HISTORY:
            path = "history/" + name
            if path not in f:
                t.check(where, "/%s" % path, False, "present", "missing")
                continue
            d = f[path]
            lengths.add(d.shape[0] if d.ndim == 1 else -1)
            t.check(where, "/%s 1D, maxshape (None,), chunked" % path,
                    d.ndim == 1 and d.maxshape == (None,) and d.chunks is not None,
                    "ndim 1, maxshape (None,), chunks set",
                    "ndim %d, maxshape %s, chunks %s" % (d.ndim, d.maxshape, d.chunks))
        t.check(where, "history series all of one length >= 2", len(lengths) == 1 and min(lengths) >= 2,
                "one length >= 2", sorted(lengths))

        # ---- /final -------------------------------------------------------------------------------
        expect = {"final/displacement": (nnode, 2), "final/stress": (nel, 3), "final/reaction": (nnode, 2)}
        expect.update({"final/contact/" + k: (nc,) for k in FINAL_CONTACT})
        for path, shape in expect.items():
            actual = f[path].shape if path in f else "missing"
            t.check_equal(where, "/%s shape" % path, shape, actual)
        if "final/contact/status" in f:
            st = f["final/contact/status"][()]
            t.check(where, "/final/contact/status values in {0, 1, 2}", set(st.tolist()) <= {0, 1, 2},
                    "{0, 1, 2}", sorted(set(st.tolist())))

        # ---- /fields/<step> -------------------------------------------------------------------------
        steps = list(f["fields"].keys()) if "fields" in f else []
        t.check_equal(where, "/fields snapshots (output:snapshot_times has one time)", 1, len(steps))
        for s in steps:
            g = f["fields"][s]
            t.check(where, "/fields/%s name is a step number" % s, s.isdigit() and 0 < int(s) <= int(a["steps"]),
                    "an integer in 1..steps", s)
            shape = g["displacement"].shape if "displacement" in g else "missing"
            t.check_equal(where, "/fields/%s/displacement shape" % s, (nnode, 2), shape)
            t.check(where, "/fields/%s has a 'time' attribute" % s, "time" in g.attrs, "present",
                    "present" if "time" in g.attrs else "missing")

        # ---- units on every dataset -------------------------------------------------------------------
        no_units = []
        count = [0]

        def visit(name, obj):
            if hasattr(obj, "shape") and hasattr(obj, "dtype"):
                count[0] += 1
                u = obj.attrs.get("units")
                if u is None or len(c2dtest.attr_str(u).strip()) == 0:
                    no_units.append(name)
        f.visititems(visit)
        t.check(where, "every dataset has a non-empty 'units' attribute (%d datasets)" % count[0], not no_units,
                "all", "all" if not no_units else "missing on " + ", ".join(no_units))

        # ---- XDMF sidecar -----------------------------------------------------------------------------
        try:
            tree = ET.parse(xmf)
            parsed = True
        except ET.ParseError as exc:
            parsed = False
            t.check(STEM + ".xmf", "parses as XML", False, "well-formed XML", str(exc))
        if parsed:
            t.check(STEM + ".xmf", "parses as XML", True, "well-formed XML", "root <%s>" % tree.getroot().tag)
            refs = [d for d in tree.iter("DataItem") if d.get("Format") == "HDF"]
            t.check_ge(STEM + ".xmf", "HDF references", len(refs), 3,
                       reason="at least connectivity, coordinates and the displacement")
            for d in refs:
                text = (d.text or "").strip()
                fname, _, dpath = text.partition(":")
                ok_file = os.path.exists(os.path.join(os.path.dirname(xmf), fname))
                ok_path = dpath in f
                dims = tuple(int(v) for v in d.get("Dimensions", "").split())
                shape = f[dpath].shape if ok_path else None
                t.check(STEM + ".xmf", "reference %s" % text, ok_file and ok_path and dims == shape,
                        "existing file and dataset with shape %s" % (dims,),
                        "file %s, dataset %s, shape %s" % ("found" if ok_file else "missing",
                                                           "found" if ok_path else "missing", shape))
            topo = tree.find(".//Topology")
            t.check_equal(STEM + ".xmf", "Topology NumberOfElements",
                          str(nel), topo.get("NumberOfElements") if topo is not None else None)

    # ---- an existing output is never overwritten without --force ---------------------------------------
    before_h5, before_xmf = sha256(h5), sha256(xmf)
    mtime = os.stat(h5).st_mtime_ns
    again = t.run(t.deck(DECK), cwd=cwd, output=None)
    t.check_equal(again, "exit code without --force", 1, again.returncode)
    lines = again.stderr_lines()
    t.check(again, "one error line naming the file and --force",
            len(lines) == 1 and lines[0].startswith(c2dtest.ERROR_PREFIX) and STEM + ".h5" in lines[0]
            and "--force" in lines[0], "1 line 'contact2d: error: ... %s.h5 ... --force'" % STEM, lines)
    t.check_equal(again, "%s.h5 unchanged (sha256)" % STEM, before_h5, sha256(h5))
    t.check_equal(again, "%s.xmf unchanged (sha256)" % STEM, before_xmf, sha256(xmf))
    t.check_equal(again, "%s.h5 mtime unchanged" % STEM, mtime, os.stat(h5).st_mtime_ns)

    time.sleep(0.05)   # so that a rewrite shows in the modification time on any file system
    forced = t.run(t.deck(DECK), "--force", cwd=cwd, output=None)
    t.check_equal(forced, "exit code with --force", 0, forced.returncode)
    t.check(forced, "%s.h5 rewritten (mtime)" % STEM, os.stat(h5).st_mtime_ns > mtime, "> %d" % mtime,
            os.stat(h5).st_mtime_ns)
    with forced.open() as f:
        t.check_equal(forced, "rewritten file status", "converged", c2dtest.attr_str(f.attrs["status"]))
    t.check_equal(forced, "files in the cwd", sorted([STEM + ".h5", STEM + ".xmf"]), sorted(os.listdir(cwd)))


if __name__ == "__main__":
    c2dtest.Test("output contract (SPEC section 8), default output name, --force").main(body)
