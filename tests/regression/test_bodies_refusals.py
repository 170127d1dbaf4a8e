"""Regression: refused &body input gives one line, exit 1, nothing written.

Cases on the two-body deck tests/regression/geometry/bodies.nml (geometry/two_blocks.geo: the
squares 'left' and 'right' bonded along x = 1, Physical Surfaces 'left', 'right', 'both') and on
decks written here: a surface the mesh does not have (the message lists the names it has), an
element in two bodies (two &body on overlapping surfaces), an element in no body (one &body of
a two-surface mesh), a body with no material value (no &material to default from), a repeated
body name, &body with the built-in rectangle (no surfaces), and a &contact boundary that lies
on two bodies (docs/deck.md, "&body"). Each runs in an empty directory with -o out.h5: exit 1,
exactly one stderr line 'contact2d: error: ...' matching the case's pattern, no out.h5, no
out.xmf. The valid deck itself runs (exit 0), --static too, and its contact pair records its
slave body (/contact attribute slave_body: 1 for 'bottom_left', 2 for 'bottom_right').
"""
import os
import re

import c2dtest

CASES = [
    ("surface_missing", ["--set", "body#2:surface='nope'"],
     r"&body \(#2\) 'right': surface = 'nope' is not a physical surface of two_blocks\.geo; "
     r"it has 'left', 'right', 'both'"),
    ("element_in_two_bodies", ["--set", "body#1:surface='both'"],
     r"&body \(#2\) 'right': element \d+ of surface 'right' is also in body 'left'; an element belongs to one body"),
    ("name_repeated", ["--set", "body#2:name='left'"],
     r"&body \(#2\): name = 'left' is the name of an earlier &body"),
    ("surface_empty", ["--set", "body#2:surface=''"],
     r"&body \(#2\) 'right': surface is required"),
    ("contact_on_two_bodies", ["--set", "contact:boundary='bottom'"],
     r"contact:boundary = 'bottom' lies on bodies 'left' and 'right'; a contact boundary lies on one body"),
]

ONE_BODY = """&mesh file = '%s' /
&material young = 7.0e4, poisson = 0.3, density = 2.7e-9 /
&body name = 'left', surface = 'left' /
&dirichlet boundary = 'top', component = 'y', values = -1.0e-3 /
&dirichlet boundary = 'bottom', component = 'x', values = 0.0 /
&solver t_ramp = 1.0e-6 /
"""

NO_MATERIAL = """&mesh file = '%s' /
&body name = 'left', surface = 'left', poisson = 0.3, density = 2.7e-9 /
&body name = 'right', surface = 'right', young = 7.0e4, poisson = 0.3, density = 2.7e-9 /
&dirichlet boundary = 'top', component = 'y', values = -1.0e-3 /
&solver t_ramp = 1.0e-6 /
"""

BUILT_IN = """&mesh lx = 1.0, ly = 1.0, nx = 2, ny = 2 /
&body name = 'all', surface = 'all', young = 7.0e4, poisson = 0.3, density = 2.7e-9 /
&dirichlet edge = 'top', component = 'y', values = -1.0e-3 /
&solver t_ramp = 1.0e-6 /
"""


def body(t):
    deck = os.path.join(t.here, "geometry", "bodies.nml")
    geo = os.path.join(t.here, "geometry", "two_blocks.geo")
    # the contact pair records its slave body: /contact@slave_body, 1-based as /mesh/body
    for name, args, slave in (("valid", [], 1), ("valid_static", ["--static"], 1),
                              ("valid_right", ["--set", "contact:boundary='bottom_right'"], 2)):
        ok = t.run(deck, *args, name=name)
        t.expect_exit(ok, 0)
        with ok.open() as f:
            t.check_equal(ok, "/contact slave_body (the body of Gamma_c)", slave,
                          int(f["contact"].attrs.get("slave_body", 0)))
    cases = [(name, deck, args, pattern) for name, args, pattern in CASES]
    for name, text, pattern in (
            ("element_in_no_body", ONE_BODY % geo,
             r"element \d+ of .*two_blocks\.geo is in no body \(9 element\(s\) are\): give every element a &body"),
            ("no_material_value", NO_MATERIAL % geo,
             r"&body \(#1\) 'left': young is required \(MPa\): give it here or in &material"),
            ("built_in_mesh", BUILT_IN,
             r"&body \(#1\): a body is the elements of a Gmsh physical surface; the built-in rectangle has none")):
        path = os.path.join(t.workdir, name + ".nml")
        with open(path, "w") as f:
            f.write(text)
        cases.append((name, path, [], pattern))
    for name, path, args, pattern in cases:
        run = t.run(path, *args, name=name, timeout=60)
        t.expect_exit(run, 1, stop=False)
        lines = run.stderr_lines()
        t.check_equal(run, "one line on stderr", 1, len(lines))
        line = lines[0] if lines else ""
        t.check(run, "message", line.startswith("contact2d: error: ") and re.search(pattern, line) is not None,
                pattern, line)
        t.check_equal(run, "nothing written", [], sorted(os.listdir(run.cwd)))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
