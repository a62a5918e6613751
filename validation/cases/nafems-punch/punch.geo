// NAFEMS cylindrical punch with rounded edge (thesis §5.2.4): the punch,
// radius 50 mm, height 100 mm, bottom edge filleted with R = 10 mm (flat
// part radius 40 mm), flat bottom on y = 0. Axisymmetric about the y axis
// (x = r): the r-y section is revolved by ±2.5° into a one-cell wedge
// (Layers{1}; Recombine), as OpenFOAM builds axisymmetric meshes; the cells
// on the axis come out as prisms with a collapsed edge. Units: mm.
//
//   gmsh -3 -format msh41 punch.geo -o punch.msh
//
// Blocks (fillet centre O = (40, 10), M = the 45° point of the fillet,
// Z = (35, 15) on the ray from M through O, so that every block corner on
// the smooth bottom-fillet-side boundary is a right angle):
//   A: P0 (0,0) -flat+fillet to M- M - Z - Y (0,15)   (contact zone)
//   B: M -fillet- P2 (50,10) -side- Q (50,100) - X (35,100) - Z
//   C: Y - Z - X - W (0,100)
// Patches: "contact" (flat bottom and fillet), "top" (y = 100, pressure),
// "side" (r = 50), "front"/"back" (the wedge planes). No patch on the
// axis: its faces collapse. Volume "punch".
DefineConstant[ h = 1.0, angle = 2.5 ];  // contact face size (mm), half wedge angle (°)
rp = 50; hp = 100; rf = 10; xf = rp - rf;
s = Sqrt(0.5);
Point(1) = {0, 0, 0};                    // P0
Point(2) = {xf, 0, 0};                   // P1: end of the flat part
Point(3) = {xf, rf, 0};                  // O: fillet centre
Point(4) = {xf + rf * s, rf - rf * s, 0}; // M
Point(5) = {rp, rf, 0};                  // P2
Point(6) = {rp, hp, 0};                  // Q
Point(7) = {xf - 5, hp, 0};              // X
Point(8) = {0, hp, 0};                   // W
Point(9) = {0, 15, 0};                   // Y
Point(10) = {xf - 5, 15, 0};             // Z

nflat = Round(xf / h);                   // faces on the flat part
narc = Round(0.25 * Pi * rf / h);        // faces on each half of the fillet
nA = Round(10 / h);                      // across block A (fine at the bottom)
nside = Round(20 / h);                   // side, growing upward
nC = narc + nside;                       // up block C

Line(1) = {1, 2};                        // flat
Circle(2) = {2, 3, 4};                   // fillet, first half
Circle(3) = {4, 3, 5};                   // fillet, second half
Line(4) = {5, 6};                        // side
Line(5) = {6, 7};                        // top, right
Line(6) = {7, 8};                        // top, left
Line(7) = {9, 8};                        // axis, upper
Line(8) = {1, 9};                        // axis, lower
Line(9) = {9, 10};
Line(10) = {4, 10};
Line(11) = {10, 7};

Transfinite Curve{1} = nflat + 1;
Transfinite Curve{2, 3} = narc + 1;
Transfinite Curve{4} = nside + 1 Using Progression 1.125 ^ h;
Transfinite Curve{5} = nA + 1;
Transfinite Curve{6, 9} = nflat + narc + 1;
Transfinite Curve{7, 11} = nC + 1 Using Progression 1.09 ^ h;
Transfinite Curve{8, 10} = nA + 1 Using Progression 1.1 ^ h;

Curve Loop(1) = {1, 2, 10, -9, -8};  Plane Surface(1) = {1};
Curve Loop(2) = {3, 4, 5, -11, -10}; Plane Surface(2) = {2};
Curve Loop(3) = {9, 11, 6, -7};      Plane Surface(3) = {3};
Transfinite Surface{1} = {1, 4, 10, 9};
Transfinite Surface{2} = {4, 6, 7, 10};
Transfinite Surface{3} = {9, 10, 7, 8};
Recombine Surface{1:3};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1:3}; }
// one extrusion per surface: e<k>[0] is the copy of surface k at +angle, e<k>[1] the volume
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };
e3[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{3}; Layers{1}; Recombine; };

e = 1e-6; zw = rp * Sin(th) * 1.01;
Physical Surface("back") = {1:3};
Physical Surface("front") = {e1[0], e2[0], e3[0]};
Physical Surface("contact") = Surface In BoundingBox{-e, -e, -zw, rp + e, rf + e, zw};
Physical Surface("top") = Surface In BoundingBox{-e, hp - e, -zw, rp + e, hp + e, zw};
Physical Surface("side") = Surface In BoundingBox{rp * Cos(th) - e, rf - e, -zw, rp + e, hp + e, zw};
Physical Volume("punch") = {e1[1], e2[1], e3[1]};
