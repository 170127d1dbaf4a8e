// Two unit squares of 3 x 3 quads side by side, bonded along x = 1 (they share its nodes), for
// the &body cases of tests/regression/test_bodies_refusals.py: Physical Surfaces "left", "right"
// and "both" (the two, overlapping the others); the curve "bottom" runs under both squares,
// "bottom_left" and "bottom_right" under one each.
Point(1) = {0, 0, 0, 0.3};
Point(2) = {1, 0, 0, 0.3};
Point(3) = {2, 0, 0, 0.3};
Point(4) = {2, 1, 0, 0.3};
Point(5) = {1, 1, 0, 0.3};
Point(6) = {0, 1, 0, 0.3};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Physical Curve("bottom") = {1, 2};
Physical Curve("bottom_left") = {1};
Physical Curve("bottom_right") = {2};
Physical Curve("top") = {4, 5};
Physical Surface("left") = {1};
Physical Surface("right") = {2};
Physical Surface("both") = {1, 2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = 4;
Transfinite Surface{1};
Transfinite Surface{2};
Recombine Surface{1, 2};
