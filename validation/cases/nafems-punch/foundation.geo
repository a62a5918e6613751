// NAFEMS cylindrical punch (thesis §5.2.4): the foundation, radius 100 mm,
// height 200 mm, top on y = 0. Axisymmetric about the y axis (x = r): the
// r-y section is revolved by ±2.5° into a one-cell wedge (Layers{1};
// Recombine); the cells on the axis are prisms with a collapsed edge.
// Units: mm.
//
//   gmsh -3 -format msh41 foundation.geo -o foundation.msh
//
// Two columns: r ≤ rc with nc uniform faces of size h under the punch,
// then faces growing ×g to r = 100; rows growing ×g from h at the top.
// nafems-punch: h = 1, rc = 45, g = 1.1 (the defaults);
// nafems-punch-modified: gmsh -3 -format msh41 -setnumber h 0.25 -setnumber rc 16
//   -setnumber g 1.15 foundation.geo -o ../nafems-punch-modified/foundation.msh
// Patches: "contact" (y = 0), "bottom" (y = -200, fixed), "side" (r = 100),
// "front"/"back" (the wedge planes). No patch on the axis. Volume "foundation".
// With -setnumber disc 1 the top is split at rc into "load" and "outer"
// (elastic check of the wedges under a pressure on a disc, no contact):
//   gmsh -3 -format msh41 -setnumber rc 40 -setnumber disc 1 foundation.geo -o foundation-disc.msh
DefineConstant[ h = 1.0, rc = 45, g = 1.1, angle = 2.5, disc = 0 ];  // face size under the punch, its zone, growth
rf = 100; hf = 200;
nc = Round(rc / h);
// faces growing by g from about h: n with h (g^n - 1)/(g - 1) = length
no = Round(Log(1 + (rf - rc) * (g - 1) / h) / Log(g));
ny = Round(Log(1 + hf * (g - 1) / h) / Log(g));
Point(1) = {0, 0, 0}; Point(2) = {rc, 0, 0}; Point(3) = {rf, 0, 0};
Point(4) = {rf, -hf, 0}; Point(5) = {rc, -hf, 0}; Point(6) = {0, -hf, 0};
Line(1) = {1, 2}; Line(2) = {2, 3};       // top (contact)
Line(3) = {3, 4};                          // side
Line(4) = {5, 4}; Line(5) = {6, 5};        // bottom
Line(6) = {1, 6};                          // axis
Line(7) = {2, 5};
Transfinite Curve{1, 5} = nc + 1;
Transfinite Curve{2, 4} = no + 1 Using Progression g;
Transfinite Curve{3, 6, 7} = ny + 1 Using Progression g;
Curve Loop(1) = {1, 7, -5, -6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, -4, -7}; Plane Surface(2) = {2};
Transfinite Surface{1} = {1, 2, 5, 6};
Transfinite Surface{2} = {2, 3, 4, 5};
Recombine Surface{1, 2};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1, 2}; }
// one extrusion per surface: e<k>[0] is the copy of surface k at +angle, e<k>[1] the volume
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };

e = 1e-6; zw = rf * Sin(th) * 1.01;
Physical Surface("back") = {1, 2};
Physical Surface("front") = {e1[0], e2[0]};
If (disc == 0)
  Physical Surface("contact") = Surface In BoundingBox{-e, -e, -zw, rf + e, e, zw};
Else
  Physical Surface("load") = Surface In BoundingBox{-e, -e, -zw, rc + e, e, zw};
  Physical Surface("outer") = Surface In BoundingBox{rc - e, -e, -zw, rf + e, e, zw};
EndIf
Physical Surface("bottom") = Surface In BoundingBox{-e, -hf - e, -zw, rf + e, -hf + e, zw};
Physical Surface("side") = Surface In BoundingBox{rf * Cos(th) - e, -hf - e, -zw, rf + e, e, zw};
Physical Volume("foundation") = {e1[1], e2[1]};
