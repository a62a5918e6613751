// The mesh of validation/cases/die-drawing, unchanged.
//
// Cylinder drawn through a die (thesis §5.3.1, after Sussman & Bathe
// 1987): the elastic cylinder, radius r1 = 0.025 m, length 0.07 m, whose
// front is extended into the die entry down to the exit radius
// r2 = 0.015 m, where the flat part (land) of the die begins. Axisymmetric
// about the y axis (x = r): the r-y section is revolved by ±2.5° into a
// one-cell wedge (Layers{1}; Recombine); the cells on the axis are prisms
// with a collapsed edge.
//
//   gmsh -3 -format msh41 cylinder.geo -o cylinder.msh
//
// Drawing direction −y; the land starts at y = 0, the die arc (R = 0.15 m)
// has its centre at (r2 + R, 0) and reaches r1 at y = 0.05385 m (die.geo).
// The front (taper, nt = 17 cells axially) follows the die arc from the
// land up to y = yk = 0.03 m and then blends into the cylinder at y = yb =
// 0.08 m by a cubic (value and slope of the arc at yk, r1 and slope 0 at
// yb), which lies inside the die (the arc curves away from its tangent).
// The thesis extends the cylinder along the die curvature all the way to
// r1: that leaves a 21° kink in the surface at the junction, and when the
// kink reaches the land (after 0.12 m of pull) the outer iterations stop
// converging (validation/cases/die-drawing/README.md); the blend has no kink.
// Then the straight part, 0.07 m, ns = 20 cells axially; nr = 3 cells
// radially throughout (thesis: 20 × 3 cells + 17 in the entry). The taper
// cells shrink along the axis by the ratio pt = 0.965 from the pulled end
// (6.2 mm) to the straight part (3.5 mm, as its cells): of equal length
// (4.7 mm), the jump to 3.5 mm at the junction made the drawn material
// recoil when the junction passed the die exit (0.175–0.19 m) — the force
// overshot by up to 7 % and the run stalled there (validation/cases/die-drawing/README.md).
//
// Patches: "pulled" (y = 0, the end in the die, radius r2: pulled),
// "tail" (the free end), "outer" (taper and straight lateral surface,
// contact), "front"/"back" (the wedge planes). No patch on the axis.
// Volume "cylinder".
DefineConstant[ pt = 0.965, nt = 17, ns = 20, nr = 3, angle = 2.5, yk = 0.03, yb = 0.08, np = 40 ];
r1 = 0.025; r2 = 0.015; R = 0.15; L = 0.07;
ye = yb;                                  // end of the taper
yt = ye + L;
rk = r2 + R - Sqrt(R * R - yk * yk);      // arc radius at yk
sk = yk / Sqrt(R * R - yk * yk);          // arc slope dr/dy at yk
Point(1) = {0, 0, 0};           // A0: axis, pulled end
Point(2) = {r2, 0, 0};          // P0: start of the land
Point(3) = {r1, ye, 0};         // P1: end of the taper
Point(4) = {0, ye, 0};          // A1
Point(5) = {r1, yt, 0};         // P2
Point(6) = {0, yt, 0};          // A2: axis, tail
// taper profile: the die arc for y <= yk, then the cubic Hermite blend
// (value and slope of the arc at yk, r1 and slope 0 at yb)
pts[] = {2};
For i In {1 : np - 1}
  y = yb * i / np;
  If (y <= yk)
    r = r2 + R - Sqrt(R * R - y * y);
  Else
    u = (y - yk) / (yb - yk); h = yb - yk;
    r = (2*u^3 - 3*u^2 + 1) * rk + (u^3 - 2*u^2 + u) * h * sk + (-2*u^3 + 3*u^2) * r1;
  EndIf
  pts[] += newp; Point(newp) = {r, y, 0};
EndFor
pts[] += 3;
Line(1) = {1, 2};               // pulled end
Spline(2) = pts[];              // taper
Line(3) = {3, 4};               // taper / straight
Line(4) = {4, 1};               // axis, taper
Line(5) = {3, 5};               // straight lateral
Line(6) = {5, 6};               // tail
Line(7) = {6, 4};               // axis, straight
Transfinite Curve{1, 3, 6} = nr + 1;
Transfinite Curve{2} = nt + 1 Using Progression pt;
Transfinite Curve{4} = nt + 1 Using Progression 1 / pt;
Transfinite Curve{5, 7} = ns + 1;
Curve Loop(1) = {1, 2, 3, 4};   Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};  Plane Surface(2) = {2};
Transfinite Surface{1} = {1, 2, 3, 4};
Transfinite Surface{2} = {4, 3, 5, 6};
Recombine Surface{1:2};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1:2}; }
// e<k>[0] is the copy of surface k at +angle, e<k>[1] the volume,
// e<k>[2..] the laterals of the curves of its loop, in order
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };

e = 1e-6; zw = r1 * Sin(th) * 1.01;
Physical Surface("back") = {1:2};
Physical Surface("front") = {e1[0], e2[0]};
Physical Surface("pulled") = Surface In BoundingBox{-e, -e, -zw, r1 + e, e, zw};
Physical Surface("tail") = Surface In BoundingBox{-e, yt - e, -zw, r1 + e, yt + e, zw};
Physical Surface("outer") = {e1[3], e2[3]};
Physical Volume("cylinder") = {e1[1], e2[1]};
