// A unit square of 40 x 25 = 1000 quads (transfinite): at mesh:level = 8 it would become
// 1000 * 4^8 = 6.5536e7 elements, over the program's cap of 5e7 (refused before refining).
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {1, 1, 0, 1};
Point(4) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Surface("square") = {1};
Transfinite Curve{1, 3} = 41;
Transfinite Curve{2, 4} = 26;
Transfinite Surface{1};
Recombine Surface{1};
