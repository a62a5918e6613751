// Flat-punch benchmark (thesis §5.2.3): half of the 2H × H block, H = 0.2 m,
// symmetry at x = 0, top y = 0, one cell thick (z ∈ [0, 1] m).
// The top edge is split at the punch edge x = b = 0.01 m: nb uniform faces
// under the punch, then faces growing away from it; the block is cut at
// x = b down to the bottom so that the columns follow.
//   gmsh -3 -format msh41 block.geo -o block.msh
b = 0.01; H = 0.2; t = 1.0;
nb = 40;        // faces under the half punch (0.25 mm)
no = 50;        // faces from the punch edge to x = H
ny = 60;        // faces through the depth
Point(1) = {0, -H, 0}; Point(2) = {b, -H, 0}; Point(3) = {H, -H, 0};
Point(4) = {H, 0, 0};  Point(5) = {b, 0, 0};  Point(6) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Transfinite Curve{1, 5} = nb + 1;
Transfinite Curve{2} = no + 1 Using Progression 1.08;
Transfinite Curve{4} = no + 1 Using Progression 1 / 1.08;
Transfinite Curve{3} = ny + 1 Using Progression 1 / 1.09;
Transfinite Curve{6} = ny + 1 Using Progression 1.09;
Transfinite Curve{7} = ny + 1 Using Progression 1 / 1.09;
Curve Loop(1) = {1, 7, 5, 6};  Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Transfinite Surface{1} = {1, 2, 5, 6};
Transfinite Surface{2} = {2, 3, 4, 5};
Recombine Surface{1, 2};
ex[] = Extrude {0, 0, t} { Surface{1, 2}; Layers{1}; Recombine; };
// ex[0] top copy of 1, ex[1] volume, ex[2..5] sides of curves 1, 7, 5, 6;
// ex[6] top copy of 2, ex[7] volume, ex[8..11] sides of curves 2, 3, 4, -7
Physical Surface("bottom") = {ex[2], ex[8]};
Physical Surface("top") = {ex[4], ex[10]};
Physical Surface("symmetry") = {ex[5]};
Physical Surface("right") = {ex[9]};
Physical Surface("frontAndBack") = {1, 2, ex[0], ex[6]};
Physical Volume("block") = {ex[1], ex[7]};
