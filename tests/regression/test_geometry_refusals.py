"""Regression: refused geometry input gives one line, exit 1, nothing written.

Cases on the small deck tests/regression/geometry/base.nml (a 3 x 3 quad square from Gmsh):
triangles (a .geo without recombination), a boundary name the mesh lacks (the message lists the
names it has), a Gamma_c group that is not one chain (bottom and top), an inverted (self-
intersecting) element in a .msh file (element 12 of geometry/inverted.msh, named by that id, not its index 2), a
quadrilateral with a node twice (geometry/degenerate.msh), a node with a NaN coordinate
(geometry/nan_coordinate.msh), a circle obstacle without its
centre, a mesh file that does not exist, a .geo with Mesh.Algorithm = 8 (crashes Gmsh 4.8). Each runs in an empty directory with -o out.h5: exit 1,
exactly one stderr line 'contact2d: error: ...' matching the case's pattern, no out.h5, no out.xmf.

Size and Gmsh's own exits (docs/geometry.md "Size" and "What a Gmsh file may do"): a .msh of
40 x 25 = 1000 quads (written here as MSH 2.2) and geometry/quads_1000.geo at level 8 are
1000 * 4^8 = 6.5536e7 elements, over the cap of 5e7 (the built-in mesh's): refused before refining,
within 60 s (today's main refined for more than 5 minutes); geometry/quads_1e8.geo (size 1e-4 on a
unit square: 40 000 curve nodes, (40000/4)^2 = 1e8 quads) is refused after its curves are meshed,
before its surface; geometry/exit.geo ends with `Exit;` (Gmsh calls exit(0): today's main ended
with status 0, no line, no file).
"""
import os
import re

import c2dtest

CASES = [
    ("algorithm_8", ["--set", "mesh:file='algorithm8.geo'"],
     r"mesh:file = '[^']*algorithm8\.geo' sets Mesh\.Algorithm = 8, which crashes.*Mesh\.Algorithm = 6"),
    ("triangles", ["--set", "mesh:file='triangles.geo'"],
     r"'Triangle 3'.*4-node quadrilaterals only.*Mesh\.RecombineAll = 1"),
    ("missing_name_contact", ["--set", "contact:boundary='bottm'"],
     r"contact:boundary = 'bottm' is not a physical curve.*'bottom', 'top', 'two_pieces'"),
    ("missing_name_dirichlet", ["--set", "dirichlet#1:boundary='nope'"],
     r"&dirichlet \(#1\).*boundary = 'nope' is not a physical curve.*'bottom'"),
    ("not_one_chain", ["--set", "contact:boundary='two_pieces'"],
     r"contact:boundary = 'two_pieces' is not one connected chain"),
    ("inverted_element", ["--set", "mesh:file='inverted.msh'", "--set", "dirichlet#1:boundary='bottom'",
                          "--set", "dirichlet#2:boundary='bottom'"],
     r"element 12 has a non-positive Jacobian"),
    ("degenerate_element", ["--set", "mesh:file='degenerate.msh'", "--set", "dirichlet#1:boundary='bottom'",
                            "--set", "dirichlet#2:boundary='bottom'"],
     r"element 12 has node 6 twice \(a degenerate quadrilateral\)"),
    # a NaN coordinate in a .msh file is named as such (it was a non-positive Jacobian, and trapped in Debug)
    ("nan_coordinate", ["--set", "mesh:file='nan_coordinate.msh'", "--set", "dirichlet#1:boundary='bottom'",
                        "--set", "dirichlet#2:boundary='bottom'"],
     r"nan_coordinate\.msh': node 5 has a coordinate that is not finite"),
    ("circle_without_centre", ["--set", "contact:obstacle='circle'"],
     r"obstacle = 'circle' needs obstacle_center"),
    ("missing_mesh_file", ["--set", "mesh:file='no_such_mesh.msh'"],
     r"no_such_mesh\.msh': no such file"),
    ("geo_refined_beyond_cap", ["--set", "mesh:file='quads_1000.geo'", "--set", "mesh:level=8"],
     r"mesh:file = '[^']*quads_1000\.geo' has 1000 2D elements; refined level = 8 times that is "
     r"1000\*4\*\*8 = 6\.5536e7 elements, more than this program is meant for \(5e7\)"),
    ("geo_meshes_beyond_cap", ["--set", "mesh:file='quads_1e8.geo'"],
     r"mesh:file = '[^']*quads_1e8\.geo': its curves are meshed with 40000 nodes; .* \(n/4\)\^2 = 1e8 "
     r"quadrilaterals, more than this program is meant for \(5e7\)"),
    ("geo_exit_statement", ["--set", "mesh:file='exit.geo'"],
     r"mesh:file = '[^']*exit\.geo': Gmsh ended the program while reading it .*Exit"),
    ("edge_with_gmsh_mesh", ["--set", "contact:boundary=''", "--set", "contact:edge='bottom'"],
     r"contact:edge = 'bottom' needs the built-in rectangle.*boundary ="),
]


def body(t):
    deck = os.path.join(t.here, "geometry", "base.nml")
    ok = t.run(deck, name="valid")
    t.expect_exit(ok, 0)
    # a directory named like a mesh file (made here, outside the source tree)
    folder = os.path.join(t.workdir, "a_folder.msh")
    os.makedirs(folder, exist_ok=True)
    msh = os.path.join(t.workdir, "quads_1000.msh")
    c2dtest.write_grid_msh(msh, 40, 25)
    cases = CASES + [("directory_as_mesh", ["--set", "mesh:file='%s'" % folder],
                      r"mesh:file = '[^']*a_folder\.msh' is a directory, not a regular file"),
                     ("msh_refined_beyond_cap", ["--set", "mesh:file='%s'" % msh, "--set", "mesh:level=8"],
                      r"mesh:file = '[^']*quads_1000\.msh' has 1000 2D elements; refined level = 8 times that is "
                      r"1000\*4\*\*8 = 6\.5536e7 elements, more than this program is meant for \(5e7\)")]
    for name, args, pattern in cases:
        # a refusal comes before the work: 60 s is ample (loading Gmsh takes about 1 s)
        run = t.run(deck, *args, name=name, timeout=60)
        t.expect_exit(run, 1, stop=False)
        lines = run.stderr_lines()
        t.check_equal(run, "one line on stderr", 1, len(lines))
        line = lines[0] if lines else ""
        t.check(run, "message", line.startswith("contact2d: error: ") and re.search(pattern, line) is not None,
                pattern, line)
        t.check_equal(run, "nothing written", [], sorted(os.listdir(run.cwd)))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
