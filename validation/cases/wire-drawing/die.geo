// Die of the wire-drawing case (thesis §5.4.1): a quarter of the die,
// elastic (E = 600 GPa), hexahedral. Units mm; the axis is x, drawing
// direction +x; the quarter y >= 0, z >= 0 as the wire (wire.py).
//
//   gmsh -3 -format msh41 die.geo -o die.msh
//
// Inner profile: approach cone, half angle α1 = 6°, from the entry
// x = -2 (radius 0.86 + 2 tan 6° = 1.070) down to the bearing (land),
// radius rd = 0.86 (Ø1.72), for x in [0, 0.45]; then the back relief,
// half angle α2 = 15°, to the exit x = 1.05 (radius 1.021). Outer radius
// 2.5, held. The r-x section (x-y plane) is meshed by three transfinite
// blocks (approach na, land nl, relief nb cells along the profile; nr
// cells radially, finer at the bore) and revolved by 90° about the x axis
// in nc layers (Layers; Recombine: hexahedra).
//
// Patches: "contact" (the bore: approach, land and relief), "outer" (held),
// "entry", "exit" (free), "symmetry-z" (z = 0, the section),
// "symmetry-y" (y = 0, the revolved section). Volume "die".
DefineConstant[ na = 20, nl = 5, nb = 5, nr = 6, pr = 1.3, nc = 16 ];
rd = 0.86; land = 0.45; xa = -2; xb = land + 0.6; ro = 2.5;
ta = Tan(6 * Pi / 180); tb = Tan(15 * Pi / 180);
Point(1) = {xa, rd - xa * ta, 0};
Point(2) = {0, rd, 0};
Point(3) = {land, rd, 0};
Point(4) = {xb, rd + (xb - land) * tb, 0};
Point(5) = {xa, ro, 0};
Point(6) = {0, ro, 0};
Point(7) = {land, ro, 0};
Point(8) = {xb, ro, 0};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};    // bore
Line(4) = {5, 6};  Line(5) = {6, 7};  Line(6) = {7, 8};    // outer
Line(7) = {1, 5};  Line(8) = {2, 6};  Line(9) = {3, 7};  Line(10) = {4, 8};  // radial
Transfinite Curve{1, 4} = na + 1;
Transfinite Curve{2, 5} = nl + 1;
Transfinite Curve{3, 6} = nb + 1;
Transfinite Curve{7:10} = nr + 1 Using Progression pr;
Curve Loop(1) = {1, 8, -4, -7};   Plane Surface(1) = {1};
Curve Loop(2) = {2, 9, -5, -8};   Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -6, -9};  Plane Surface(3) = {3};
Transfinite Surface{1} = {1, 2, 6, 5};
Transfinite Surface{2} = {2, 3, 7, 6};
Transfinite Surface{3} = {3, 4, 8, 7};
Recombine Surface{1:3};

// e<k>[0]: the copy of surface k in the plane y = 0, e<k>[1] the volume,
// e<k>[2..5] the laterals of the curves of its loop, in order
e1[] = Extrude {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Surface{1}; Layers{nc}; Recombine; };
e2[] = Extrude {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Surface{2}; Layers{nc}; Recombine; };
e3[] = Extrude {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Surface{3}; Layers{nc}; Recombine; };

Physical Surface("contact") = {e1[2], e2[2], e3[2]};
Physical Surface("outer") = {e1[4], e2[4], e3[4]};
Physical Surface("entry") = {e1[5]};
Physical Surface("exit") = {e3[3]};
Physical Surface("symmetry-z") = {1:3};
Physical Surface("symmetry-y") = {e1[0], e2[0], e3[0]};
Physical Volume("die") = {e1[1], e2[1], e3[1]};
