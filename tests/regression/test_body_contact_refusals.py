#!/usr/bin/env python3
"""Regression: refused contact between two bodies (contact:master) gives one line, exit 1, nothing written.

Cases on the shipped deck inputs/bar_impact_two_bodies_p1.nml (two bars 'a', 'b'; slave
'a_end', master 'b_end'; the curve 'a_start' is a's other end) and on a deck written here
whose bars overlap by 1e-3 mm (docs/deck.md &contact, docs/geometry.md "Two bodies"): a master
curve the mesh does not have (the message lists the names it has), the slave boundary as its
own master, a master on the slave's body, a master curve on both bodies, an obstacle and a
master both given (by name and by an obstacle variable), an obstacle motion or geometry =
'initial' with a master, friction, P0 multipliers or the penalty with a master (not yet), the
static engine (--static and compare_static; a body's own initial velocity is refused there
first, named as body#1:velocity), master without a Gmsh boundary (built-in edge),
and bodies that overlap at the start (the worst slave node and its penetration named). Each
runs in an empty directory with -o out.h5: exit 1, exactly one stderr line
'contact2d: error: ...' matching the case's pattern, no out.h5, no out.xmf. The valid deck
runs (exit 0).
"""
import os
import re

import c2dtest

M = "master = 'b_end'"
CASES = [
    ("master_missing", ["--set", "contact:master='nope'"],
     r"contact:master = 'nope' is not a physical curve of bar_impact_two_bodies\.geo; it has 'edges', 'a_end', "
     r"'b_end', 'a_start'"),
    ("master_is_slave", ["--set", "contact:master='a_end'"],
     r"contact: master = 'a_end' is the slave boundary itself; a boundary cannot be paired with itself"),
    ("master_same_body", ["--set", "contact:master='a_start'"],
     r"contact:master = 'a_start' and boundary = 'a_end' are both on body 'a'; contact pairs the boundaries "
     r"of two different bodies"),
    ("master_on_two_bodies", ["--set", "contact:master='edges'"],
     r"contact:master = 'edges' (lies on bodies 'a' and 'b'|is not one connected chain)"),
    ("obstacle_and_master", ["--set", "contact:obstacle='plane'"],
     r"contact: obstacle = 'plane' and master = 'b_end' are both given; the master side is a rigid obstacle "
     r"or another body's boundary, not both"),
    ("obstacle_variable_and_master", ["--set", "contact:obstacle_point=0.0,0.0"],
     r"contact: master = 'b_end' is given but so are an obstacle's variables"),
    ("motion_and_master", ["--set", "contact:obstacle_motion_times=1e-7", "--set", "contact:obstacle_velocity_x=1.0"],
     r"contact: master = 'b_end' takes no obstacle motion"),
    ("initial_geometry", ["--set", "contact:geometry='initial'"],
     r"contact: master = 'b_end' takes no geometry = 'initial'"),
    ("friction", ["--set", "contact:friction='tresca'", "--set", "contact:threshold=1.0"],
     r"contact:friction = 'tresca' with master = 'b_end': contact between two bodies is frictionless only"),
    ("p0", ["--set", "contact:multiplier='P0'"],
     r"contact:multiplier = 'P0' with master = 'b_end': contact between two bodies has P1 multipliers only"),
    ("penalty", ["--set", "contact:method='penalty'", "--set", "contact:penalty_stiffness=1e6"],
     r"contact:method = 'penalty' with master = 'b_end': contact between two bodies has the Lagrange "
     r"multipliers only"),
    ("static", ["--static", "--set", "body#1:velocity=0,0"],
     r"solver:method = 'static' refuses contact:master = 'b_end': contact between two bodies has the "
     r"explicit engine only"),
    ("static_body_velocity", ["--static"],
     r"body#1:velocity = 1000, 0 has no meaning for the static engine"),
    ("compare_static", ["--set", "solver:compare_static=.true.", "--set", "body#1:velocity=0,0"],
     r"solver:compare_static refuses contact:master = 'b_end'"),
]

# the bars overlapping by 1e-3 mm (b from x = 1 - 1e-3), each 4 x 1 elements
OVERLAP_GEO = """L = 1.0; w = 0.125; g0 = -1.0e-3;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, w, 0}; Point(4) = {0, w, 0};
Point(5) = {L + g0, 0, 0}; Point(6) = {2*L + g0, 0, 0}; Point(7) = {2*L + g0, w, 0}; Point(8) = {L + g0, w, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = 5; Transfinite Curve{2, 4, 6, 8} = 2;
Transfinite Surface{1}; Transfinite Surface{2}; Recombine Surface{1, 2};
Physical Curve("edges") = {1, 3, 5, 7}; Physical Curve("a_end") = {2}; Physical Curve("b_end") = {8};
Physical Surface("a") = {1}; Physical Surface("b") = {2};
"""
OVERLAP_DECK = """&mesh file = '%s' /
&material young = 7.0e4, poisson = 0.3, density = 2.7e-9 /
&body name = 'a', surface = 'a' /
&body name = 'b', surface = 'b' /
&dirichlet boundary = 'edges', component = 'y', values = 0.0, times = 1.0e-9 /
&contact boundary = 'a_end', master = 'b_end' /
&solver t_end = 1.0e-7, damping = 'none' /
"""

BUILT_IN = """&mesh lx = 1.0, ly = 1.0, nx = 2, ny = 2 /
&material young = 7.0e4, poisson = 0.3, density = 2.7e-9 /
&dirichlet edge = 'top', component = 'y', values = -1.0e-3 /
&contact edge = 'bottom', master = 'b_end' /
&solver t_ramp = 1.0e-6 /
"""


def body(t):
    deck = t.deck("bar_impact_two_bodies_p1.nml")
    ok = t.run(deck, "--set", "solver:t_end=2e-8", name="valid")
    t.expect_exit(ok, 0)
    cases = [(name, deck, args, pattern) for name, args, pattern in CASES]
    geo = os.path.join(t.workdir, "overlap.geo")
    with open(geo, "w") as f:
        f.write(OVERLAP_GEO)
    for name, text, pattern in (
            ("overlap", OVERLAP_DECK % geo,
             r"contact: the bodies overlap at the start: slave node \d+ at \(1, 0(\.125)?\) is 0\.0010\d* mm inside the "
             r"master boundary \(tolerance 1\.25e-7 mm\)"),
            ("built_in_edge", BUILT_IN,
             r"contact: master = 'b_end' needs the slave side as boundary = '<physical curve>' of another body")):
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
