// Two stacked blocks that share no node (inputs/contact_patch_p1.nml): 'lower' [0, 1] x [0, 0.5]
// with 7 x 3 elements and 'upper' [0, 1] x [0.5, 1] with 5 x 3, touching along y = 0.5 with
// non-matching nodes (structured quadrilaterals).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 0.5, 0};
Point(4) = {0, 0.5, 0};
Point(5) = {0, 0.5, 0};
Point(6) = {1, 0.5, 0};
Point(7) = {1, 1, 0};
Point(8) = {0, 1, 0};
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
Transfinite Curve{1, 3} = 8;
Transfinite Curve{5, 7} = 6;
Transfinite Curve{2, 4, 6, 8} = 4;
Transfinite Surface{1};
Transfinite Surface{2};
Recombine Surface{1, 2};
Geometry.AutoCoherence = 0;
Physical Curve("bottom") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_bottom") = {5};
Physical Curve("top") = {7};
Physical Curve("left_sides") = {4, 8};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
