// square_quads.geo followed by an Exit statement: Gmsh ends the program (exit(0)) while it
// reads the file; contact2d must refuse it (exit 1, one line), not end silently with status 0.
// A unit square of 3 x 3 quads; the group "two_pieces" (bottom and top) is not one chain.
Point(1) = {0, 0, 0, 0.3};
Point(2) = {1, 0, 0, 0.3};
Point(3) = {1, 1, 0, 0.3};
Point(4) = {0, 1, 0, 0.3};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("two_pieces") = {1, 3};
Physical Surface("square") = {1};
Transfinite Curve{1, 2, 3, 4} = 4;
Transfinite Surface{1};
Recombine Surface{1};
Exit;
