// rigid-cylinder-indent: the deformable flat block pressed by a rigid,
// coarsely faceted cylinder (Nagata smoothing acceptance, issue 9).
//
//   gmsh -3 -format msh41 block.geo -o block.msh
//
// Block [-L, L] x [-H, 0] x [0, 1] (one cell thick: plane strain, forces
// per metre). Three transfinite columns: a central one |x| <= xc with nc
// uniform faces of width h = 2 xc / nc on the top (the contact surface),
// and two side columns graded from h at |x| = xc to the sides. Vertically
// every column is graded from about h at the top to the bottom.
// Patches: "top" (y = 0, contact), "bottom" (y = -H, fixed), "sides"
// (x = ±L, free), "frontAndBack" (z = 0, 1: empty). Volume "block".
DefineConstant[ refinement = 1 ];
L = 4.0;
H = 4.0;
xc = 0.5;
t = 1.0;
nc = 50 * refinement;      // central faces: h = 0.02 m
ns = 30 * refinement;      // side columns
ny = 32 * refinement;      // depth
rs = 1.1 ^ (1 / refinement);
ry = 1.1 ^ (1 / refinement);

Point(1) = {-L, -H, 0};
Point(2) = {-xc, -H, 0};
Point(3) = {xc, -H, 0};
Point(4) = {L, -H, 0};
Point(5) = {L, 0, 0};
Point(6) = {xc, 0, 0};
Point(7) = {-xc, 0, 0};
Point(8) = {-L, 0, 0};

Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};   // bottom
Line(4) = {4, 5};                                          // right side, up
Line(5) = {6, 5};  Line(6) = {7, 6};  Line(7) = {7, 8};   // top, outward from the centre
Line(8) = {8, 1};                                          // left side, down
Line(9) = {2, 7};  Line(10) = {3, 6};                      // column boundaries, up

Transfinite Curve{2, 6} = nc + 1;
Transfinite Curve{5, 7} = ns + 1 Using Progression rs;    // from x = ±xc outward
Transfinite Curve{3} = ns + 1 Using Progression rs;       // from x = xc outward
Transfinite Curve{1} = ns + 1 Using Progression 1 / rs;   // toward x = -xc
Transfinite Curve{4, 9, 10} = ny + 1 Using Progression 1 / ry;  // finer toward the top
Transfinite Curve{8} = ny + 1 Using Progression ry;       // downward: finer at the top

Curve Loop(1) = {1, 9, 7, 8};      Plane Surface(1) = {1};   // left
Curve Loop(2) = {2, 10, -6, -9};   Plane Surface(2) = {2};   // centre
Curve Loop(3) = {3, 4, -5, -10};   Plane Surface(3) = {3};   // right
Transfinite Surface{1} = {1, 2, 7, 8};
Transfinite Surface{2} = {2, 3, 6, 7};
Transfinite Surface{3} = {3, 4, 5, 6};
Recombine Surface{1:3};

// ex[6k]: copy at z = t, ex[6k+1]: volume, ex[6k+2..]: sides in loop order
ex[] = Extrude {0, 0, t} { Surface{1:3}; Layers{1}; Recombine; };
Physical Surface("bottom") = {ex[2], ex[8], ex[14]};
Physical Surface("top") = {ex[4], ex[10], ex[16]};
Physical Surface("sides") = {ex[5], ex[15]};
Physical Surface("frontAndBack") = {1:3, ex[0], ex[6], ex[12]};
Physical Volume("block") = {ex[1], ex[7], ex[13]};
