// A quarter of an elastic ring, inner radius ra = 1 mm, outer rb = 2 mm, centre (0, 0)
// (inputs/lame_cavity_p1.nml). Transfinite quadrilaterals, 6 along the arcs and 3 across at
// level 0; Gmsh's refinement (deck level) puts the new boundary nodes on the circles.
ra = 1.0; rb = 2.0;
Point(1) = {0, 0, 0};
Point(2) = {ra, 0, 0};
Point(3) = {rb, 0, 0};
Point(4) = {0, rb, 0};
Point(5) = {0, ra, 0};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{2, 4} = 7;
Transfinite Curve{1, 3} = 4;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("xcut") = {1};
Physical Curve("outer") = {2};
Physical Curve("ycut") = {3};
Physical Curve("inner") = {4};
Physical Surface("ring") = {1};
