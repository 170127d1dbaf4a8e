// A unit square meshed with size 1e-4: 10 000 segments per side, 40 000 curve nodes, about
// 1e8 quads (Gmsh 4.8 meshes it silently for minutes, then runs out of memory). Refused after
// the curves are meshed: a square bounded by 40 000 nodes holds (40000/4)^2 = 1e8 quads > 5e7.
lc = 1e-4;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Surface("square") = {1};
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
