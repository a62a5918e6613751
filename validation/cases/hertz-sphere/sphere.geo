// Axisymmetric Hertz contact (thesis appendix A2, eqs. A13–A16): the lower
// half of a sphere of radius R = 8 m — flat top on y = 0, lowest point
// (0, -8) — pressed onto a rigid flat. Axisymmetric about the y axis
// (x = r): the quarter disc is revolved by ±2.5° into a one-cell wedge
// (Layers{1}; Recombine); the cells on the axis are prisms with a
// collapsed edge.
//
//   gmsh -3 -format msh41 sphere.geo -o sphere.msh
//
// Blocks (the half of hertz-cylinder/cylinder.geo's O-grid with x ≥ 0):
// the inner rectangle [0, a] x [-c, 0] in a central and a right column, a
// right block up to the side arc, a bottom-right block, and the contact
// block under the central column, whose arc (0 ≤ θ ≤ tc from the lowest
// point) has nc uniform faces; radial lines graded toward the arc so that
// the contact cells are nearly square. The Hertz radius for the 0.02 m
// indentation is about 0.37 m (11 faces of 0.032 m).
//
// Patches: "top" (y = 0), "curved" (the arc, contact), "front"/"back" (the
// wedge planes). No patch on the axis. Volume "sphere".
DefineConstant[ tc = 0.08, nc = 20, ns = 14, rt = 1.345, nr = 24, q = 0.882, angle = 2.5 ];
R = 8.0; a = 3.5; c = 3.5;
xt = 2.0;       // central column width at y = 0
xc = 1.5;       // and at the rectangle bottom (cells near the axis not too slender)
ny = 13; pv = 0.92;
s = Sqrt(0.5);
Point(1) = {0, 0, 0};                       // O (axis, top)
Point(2) = {xt, 0, 0};                      // T
Point(3) = {a, 0, 0};                       // B
Point(4) = {a, -c, 0};                      // C
Point(5) = {xc, -c, 0};                     // Cc
Point(6) = {0, -c, 0};                      // A0 (axis)
Point(7) = {R, 0, 0};                       // E
Point(8) = {R * s, -R * s, 0};              // F
Point(9) = {R * Sin(tc), -R * Cos(tc), 0};  // Q: end of the contact zone
Point(10) = {0, -R, 0};                     // L: lowest point
Point(11) = {0, 0, 0};
Line(1) = {1, 2};  Line(2) = {2, 3};        // top
Line(3) = {6, 5};  Line(4) = {5, 4};        // rectangle bottom
Line(5) = {1, 6};                           // axis, upper
Line(6) = {2, 5};  Line(7) = {3, 4};        // rectangle verticals
Line(8) = {3, 7};  Line(9) = {4, 8};        // radial, right block
Line(10) = {5, 9}; Line(11) = {6, 10};      // radial, contact block (axis)
Circle(12) = {7, 1, 8};                     // E-F
Circle(13) = {9, 1, 8};                     // Q-F
Circle(14) = {10, 1, 9};                    // L-Q (contact zone)
Transfinite Curve{1, 3, 14} = nc + 1;
Transfinite Curve{2, 4, 13} = ns + 1 Using Progression rt;
Transfinite Curve{5, 6, 7} = ny + 1 Using Progression pv;
Transfinite Curve{12} = ny + 1;
Transfinite Curve{8, 9} = nr + 1;
Transfinite Curve{10, 11} = nr + 1 Using Progression q;
Curve Loop(1) = {1, 6, -3, -5};     Plane Surface(1) = {1};  // central column
Curve Loop(2) = {2, 7, -4, -6};     Plane Surface(2) = {2};  // right column
Curve Loop(3) = {8, 12, -9, -7};    Plane Surface(3) = {3};  // right block
Curve Loop(4) = {4, 9, -13, -10};   Plane Surface(4) = {4};  // bottom right
Curve Loop(5) = {3, 10, -14, -11};  Plane Surface(5) = {5};  // contact block
Transfinite Surface{1} = {1, 2, 5, 6};
Transfinite Surface{2} = {2, 3, 4, 5};
Transfinite Surface{3} = {3, 7, 8, 4};
Transfinite Surface{4} = {5, 4, 8, 9};
Transfinite Surface{5} = {6, 5, 9, 10};
Recombine Surface{1:5};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, -th} { Surface{1:5}; }
// one extrusion per surface: e<k>[0] is the copy of surface k at +angle, e<k>[1] the volume
e1[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };
e2[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{2}; Layers{1}; Recombine; };
e3[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{3}; Layers{1}; Recombine; };
e4[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{4}; Layers{1}; Recombine; };
e5[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{5}; Layers{1}; Recombine; };

e = 1e-6; zw = R * Sin(th) * 1.01;
Physical Surface("back") = {1:5};
Physical Surface("front") = {e1[0], e2[0], e3[0], e4[0], e5[0]};
Physical Surface("top") = Surface In BoundingBox{-e, -e, -zw, R + e, e, zw};
// the arc: laterals of curves 12, 13, 14 (each lies outside the rectangle's box)
Physical Surface("curved") = {e3[3], e4[4], e5[4]};
Physical Volume("sphere") = {e1[1], e2[1], e3[1], e4[1], e5[1]};
