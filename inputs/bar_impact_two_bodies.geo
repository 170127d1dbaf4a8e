// Two equal bars on a line (inputs/bar_impact_two_bodies_p1.nml): 'a' [0, L] x [0, w] and
// 'b' [L + g0, 2 L + g0] x [0, w], L = 1, w = 0.125, g0 = 1e-4 mm; structured, n = 64
// elements along each bar and one across (every node lies on a top or bottom edge, where
// u_y = 0: a 1D strip).
L = 1.0; w = 0.125; g0 = 1.0e-4; n = 64;
Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, w, 0};
Point(4) = {0, w, 0};
Point(5) = {L + g0, 0, 0};
Point(6) = {2*L + g0, 0, 0};
Point(7) = {2*L + g0, w, 0};
Point(8) = {L + g0, w, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = n + 1;
Transfinite Curve{2, 4, 6, 8} = 2;
Transfinite Surface{1};
Transfinite Surface{2};
Recombine Surface{1, 2};
Physical Curve("edges") = {1, 3, 5, 7};
Physical Curve("a_end") = {2};
Physical Curve("b_end") = {8};
Physical Curve("a_start") = {4};
Physical Surface("a") = {1};
Physical Surface("b") = {2};
