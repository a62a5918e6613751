// Sphere on a block example: the lower half of a sphere of radius R = 1 m
// (flat top z = R through the centre (0, 0, R), lowest point at the origin),
// quarter model x >= 0, y >= 0 (symmetry planes x = 0 and y = 0).
//
//   gmsh -3 -format msh41 sphere.geo -o sphere.msh
//
// A quarter-disc profile in the x-z plane (the block layout of
// validation/cases/sphere-block/sphere.geo, coarser) is revolved by 90°
// about the z axis in `na` layers (Recombine: hexahedra, and prisms with a
// collapsed edge on the axis). Profile blocks: the inner rectangle
// [0, a] x [R - c, R] in a central and a right column, a right block up to
// the side arc, a bottom-right block, and the contact block under the
// central column whose arc (0 <= theta <= tc from the lowest point) has nc
// uniform faces (R tc / nc = 0.019 m); radial lines graded by q toward the
// arc so that the contact cells are nearly cubic. The Hertz contact radius
// is about 0.10 m: 5 to 6 faces. 2,272 cells.
//
// Patches: "top" (z = R, driven), "curved" (the spherical surface, contact),
// "symmetry" (the faces on x = 0 and on y = 0). Volume "sphere".
DefineConstant[ tc = 0.15, nc = 8, ns = 6, rt = 1.34, nr = 10, q = 0.85,
                ny = 6, pv = 0.92, na = 8 ];
R = 1.0; a = 0.4375; c = 0.4375;
xt = 0.25;      // central column width at z = R
xc = 0.1875;    // and at the rectangle bottom
s = Sqrt(0.5);
Point(1) = {0, 0, R};                            // O (axis, top)
Point(2) = {xt, 0, R};                           // T
Point(3) = {a, 0, R};                            // B
Point(4) = {a, 0, R - c};                        // C
Point(5) = {xc, 0, R - c};                       // Cc
Point(6) = {0, 0, R - c};                        // A0 (axis)
Point(7) = {R, 0, R};                            // E
Point(8) = {R * s, 0, R - R * s};                // F
Point(9) = {R * Sin(tc), 0, R - R * Cos(tc)};    // Q: end of the contact zone
Point(10) = {0, 0, 0};                           // L: lowest point
Point(11) = {0, 0, R};                           // centre
Line(1) = {1, 2};  Line(2) = {2, 3};             // top
Line(3) = {6, 5};  Line(4) = {5, 4};             // rectangle bottom
Line(5) = {1, 6};                                // axis, upper
Line(6) = {2, 5};  Line(7) = {3, 4};             // rectangle verticals
Line(8) = {3, 7};  Line(9) = {4, 8};             // radial, right block
Line(10) = {5, 9}; Line(11) = {6, 10};           // radial, contact block (axis)
Circle(12) = {7, 11, 8};                         // E-F
Circle(13) = {9, 11, 8};                         // Q-F
Circle(14) = {10, 11, 9};                        // L-Q (contact zone)
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

// a quarter turn: e<k>[0] is the copy of surface k on the plane x = 0,
// e<k>[1] the volume, e<k>[2..] the laterals of the surface's curves in
// curve-loop order
e1[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Surface{1}; Layers{na}; Recombine; };
e2[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Surface{2}; Layers{na}; Recombine; };
e3[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Surface{3}; Layers{na}; Recombine; };
e4[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Surface{4}; Layers{na}; Recombine; };
e5[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Surface{5}; Layers{na}; Recombine; };

e = 1e-6;
Physical Surface("symmetry") = {1:5, e1[0], e2[0], e3[0], e4[0], e5[0]};
Physical Surface("top") = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
// the sphere: laterals of curves 12, 13, 14 (loop positions 2, 3, 3)
Physical Surface("curved") = {e3[3], e4[4], e5[4]};
Physical Volume("sphere") = {e1[1], e2[1], e3[1], e4[1], e5[1]};
