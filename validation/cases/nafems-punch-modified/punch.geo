// Modified NAFEMS punch (thesis §5.2.4, Fig. 5.8 b; appendix A3.1): the
// punch, radius 50 mm, height 100 mm, flat bottom of radius a = 10 mm on
// y = 0 continued by a fillet of radius R = 100 mm (centre (10, 100)) up to
// the side r = 50, which it meets at y = 100 - sqrt(100² - 40²) = 8.35 mm.
// Axisymmetric about the y axis (x = r): the r-y section is revolved by
// ±2.5° into a one-cell wedge (Layers{1}; Recombine); the cells on the axis
// are prisms with a collapsed edge. Units: mm.
//
//   gmsh -3 -format msh41 punch.geo -o punch.msh
//
// Two blocks split at r = rc: faces of size h along the bottom for r ≤ rc
// (the contact radius is about 14 mm), growing ×g beyond; rows growing ×g
// upward from h. Patches: "contact" (flat and fillet), "top" (y = 100,
// pressure), "side" (r = 50), "front"/"back" (the wedge planes). No patch on
// the axis. Volume "punch".
DefineConstant[ h = 0.25, rc = 16, g = 1.15, angle = 2.5 ];
rp = 50; hp = 100; a = 10; R = 100;
yc = R - Sqrt(R * R - (rc - a) * (rc - a));   // fillet height at r = rc
ye = R - Sqrt(R * R - (rp - a) * (rp - a));   // and at the side
nflat = Round(a / h);
narc = Round(R * Asin((rc - a) / R) / h);
lout = R * (Asin((rp - a) / R) - Asin((rc - a) / R));
nout = Round(Log(1 + lout * (g - 1) / h) / Log(g));
ny = Round(Log(1 + hp * (g - 1) / h) / Log(g));
Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {a, R, 0};                     // fillet centre
Point(4) = {rc, yc, 0};
Point(5) = {rp, ye, 0};
Point(6) = {rp, hp, 0};
Point(7) = {rc, hp, 0};
Point(8) = {0, hp, 0};
Line(1) = {1, 2};                          // flat
Circle(2) = {2, 3, 4};                     // fillet, fine part
Circle(3) = {4, 3, 5};                     // fillet, growing
Line(4) = {5, 6};                          // side
Line(5) = {7, 6};                          // top, outer
Line(6) = {8, 7};                          // top, inner
Line(7) = {1, 8};                          // axis
Line(8) = {4, 7};
Transfinite Curve{1} = nflat + 1;
Transfinite Curve{2} = narc + 1;
Transfinite Curve{6} = nflat + narc + 1;
Transfinite Curve{3, 5} = nout + 1 Using Progression g;
Transfinite Curve{4, 7, 8} = ny + 1 Using Progression g;
Curve Loop(1) = {1, 2, 8, -6, -7}; Plane Surface(1) = {1};
Curve Loop(2) = {3, 4, -5, -8};    Plane Surface(2) = {2};
Transfinite Surface{1} = {1, 4, 7, 8};
Transfinite Surface{2} = {4, 5, 6, 7};
Recombine Surface{1, 2};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1, 2}; }
// one extrusion per surface: e<k>[0] is the copy of surface k at +angle, e<k>[1] the volume
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };

e = 1e-6; zw = rp * Sin(th) * 1.01;
Physical Surface("back") = {1, 2};
Physical Surface("front") = {e1[0], e2[0]};
Physical Surface("contact") = Surface In BoundingBox{-e, -e, -zw, rp + e, ye + e, zw};
Physical Surface("top") = Surface In BoundingBox{-e, hp - e, -zw, rp + e, hp + e, zw};
Physical Surface("side") = Surface In BoundingBox{rp * Cos(th) - e, ye - e, -zw, rp + e, hp + e, zw};
Physical Volume("punch") = {e1[1], e2[1]};
