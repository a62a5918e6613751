// The mesh of validation/cases/die-drawing, unchanged.
//
// Rigid die of the cylinder-drawing benchmark (thesis §5.3.1): an entry
// arc of radius R = 0.15 m, centre (r2 + R, 0), tangent at y = 0 to the
// flat part (land) of radius r2 = 0.015 m, which runs to y = yl = −0.3 m
// so that all the drawn material stays in it over the 0.25 m pull (the
// analytical force, eq. 5.1, is the energy stored per drawn volume in the
// land). The arc goes on past r1 = 0.025 m (reached at y = 0.0539 m) to
// x = 0.03 m, so that the cylinder's bulge ahead of the die meets a smooth
// flare, not a corner. Axisymmetric about y (x = r), revolved by ±2.5°
// into one-cell wedges, one cell thick radially up to x = ro = 0.04 m.
//
//   gmsh -3 -format msh41 die.geo -o die.msh
//
// Patches: "contact" (arc and land), "outer" (x = ro, held), "ends"
// (y = yl and the top of the flare), "front"/"back" (the wedge planes,
// no condition: the die is rigid). Volume "die".
DefineConstant[ narc = 40, nland = 75, angle = 2.5 ];
r2 = 0.015; R = 0.15; xf = 0.03; ro = 0.04; yl = -0.3;
yf = Sqrt(R * R - (R - xf + r2) * (R - xf + r2));
Point(1) = {r2, yl, 0};         // D0
Point(2) = {r2, 0, 0};          // D1: land / arc
Point(3) = {xf, yf, 0};         // D2: end of the flare
Point(4) = {ro, yf, 0};         // D3
Point(5) = {ro, 0, 0};          // D4
Point(6) = {ro, yl, 0};         // D5
Point(7) = {r2 + R, 0, 0};      // arc centre
Line(1) = {1, 2};               // land
Line(2) = {2, 5};
Line(3) = {5, 6};               // outer, land
Line(4) = {6, 1};               // end
Circle(5) = {2, 7, 3};          // arc
Line(6) = {3, 4};               // top of the flare
Line(7) = {4, 5};               // outer, arc
Transfinite Curve{2, 4, 6} = 2;
Transfinite Curve{1, 3} = nland + 1;
Transfinite Curve{5, 7} = narc + 1;
Curve Loop(1) = {1, 2, 3, 4};   Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};  Plane Surface(2) = {2};
Transfinite Surface{1} = {1, 2, 5, 6};
Transfinite Surface{2} = {2, 3, 4, 5};
Recombine Surface{1:2};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1:2}; }
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };

Physical Surface("back") = {1:2};
Physical Surface("front") = {e1[0], e2[0]};
Physical Surface("contact") = {e1[2], e2[2]};
Physical Surface("outer") = {e1[4], e2[4]};
Physical Surface("ends") = {e1[5], e2[3]};
Physical Volume("die") = {e1[1], e2[1]};
