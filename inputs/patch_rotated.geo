// The contact patch block of inputs/patch_compression_p1.nml, [0, L] x [0, H] = [0, 1] x [0, 0.5] mm
// in its own axes (e1, e2), rotated by 30 degrees: x = xi e1 + eta e2, e1 = (cos 30, sin 30),
// e2 = (-sin 30, cos 30). Unstructured quadrilaterals (Mesh.Algorithm = 6 with recombination and
// subdivision; Debian's Gmsh 4.8.4 crashes with Mesh.Algorithm = 8). The top has a point at its
// middle (the node that carries u_x = 0 in the deck).
L = 1.0; H = 0.5; h = 0.12;
c = Cos(Pi/6); s = Sin(Pi/6);
Point(1) = {0, 0, 0, h};
Point(2) = {L*c, L*s, 0, h};
Point(3) = {L*c - H*s, L*s + H*c, 0, h};
Point(4) = {L/2*c - H*s, L/2*s + H*c, 0, h};
Point(5) = {-H*s, H*c, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.SubdivisionAlgorithm = 1;
Physical Curve("base") = {1};
Physical Curve("top") = {3, 4};
Physical Curve("sides") = {2, 5};
Physical Surface("block") = {1};
