// The rectangle of the paper's test (inputs/baillet_sassi_2002_p1.nml) as a Gmsh geometry:
// [0, 1.3] x [0, 0.3] mm in 13 x 3 quadrilaterals (level 0), so that `level = k` in the deck
// (Gmsh's refinement, each quad split in four) gives the nodes of the built-in (13 2^k) x (3 2^k)
// mesh. Structured by extrusion with layers rather than a transfinite surface: Gmsh 4.8.4 places
// transfinite curve nodes to about 1e-12 only, extruded layers to round-off.
// Physical curves carry the side names of the built-in mesher.
lx = 1.3; ly = 0.3;
Point(1) = {0, 0, 0};
bottom[] = Extrude {lx, 0, 0} { Point{1}; Layers{13}; };
body[] = Extrude {0, ly, 0} { Curve{bottom[1]}; Layers{3}; Recombine; };
// body[0]: top curve, body[1]: the surface, body[2]: the side at x = lx, body[3]: at x = 0
Physical Curve("bottom") = {bottom[1]};
Physical Curve("top") = {body[0]};
Physical Curve("left") = {body[3]};
Physical Curve("right") = {body[2]};
Physical Surface("body") = {body[1]};
