// Elastic half-disk of radius R on a rigid plane (inputs/hertz_cylinder_p1.nml): the quarter
// x >= 0 by symmetry, centre (0, R), the arc from the contact point (0, 0) to (R, R), the flat
// diametral side y = R on top. Graded towards the contact point. Quadrilaterals: Mesh.Algorithm = 6
// with recombination and subdivision (Debian's Gmsh 4.8.4 crashes with Mesh.Algorithm = 8); the
// final size near the contact is h/2.
R = 10;         // radius [mm]
a = 0.5;        // expected contact half-width [mm]
h = 0.1;        // element size near the contact before subdivision [mm]
H = 1.5;        // element size far away [mm]
Point(1) = {0, 0, 0, h};
Point(2) = {0, R, 0, H};
Point(3) = {R, R, 0, H};
Circle(1) = {1, 2, 3};
Line(2) = {3, 2};
Line(3) = {2, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = H;
Field[2].DistMin = 2*a;
Field[2].DistMax = R;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.SubdivisionAlgorithm = 1;
Physical Curve("arc") = {1};
Physical Curve("top") = {2};
Physical Curve("symmetry") = {3};
Physical Surface("disk") = {1};
