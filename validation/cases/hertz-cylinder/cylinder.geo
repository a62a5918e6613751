// Hertz contact, thesis §5.2.1 (benchmark "hertz-cylinder"): the lower half
// of a cylinder of radius R = 8 m — flat top on y = 0, lowest point (0, -8) —
// pressed onto a rigid flat; plane strain, one cell thick in z (t = 1 m, so
// forces are per metre of length).
//
//   coarse: 1,615 cells  gmsh -3 -format msh41 cylinder.geo -o cylinder-coarse.msh
//   fine:   6,460 cells  gmsh -3 -format msh41 -setnumber refinement 2 cylinder.geo -o cylinder-fine.msh
//
// The fine mesh halves every edge of the coarse one: counts doubled,
// geometric ratios square-rooted, so every coarse node is a fine node.
//
// Block structure (O-grid of a half disc): an inner rectangle
// [-a, a] x [-c, 0] with its corners on the ±45° rays, a left and a right
// block up to the side arcs, and a bottom ring block up to the arc between
// -135° and -45°. The bottom arc has nc uniform faces over the contact zone
// |θ| ≤ θc (θ from the lowest point; the Hertz half-width is ≈ 0.6 m) and
// ns faces on each side growing geometrically away from it; the radial
// lines bounding the contact zone are graded toward the arc so that the
// cells at the contact are nearly square. The rectangle is split into three
// columns continuing the contact-zone rays.
//
// Patches: "top" (y = 0), "curved" (the arc, contact), "frontAndBack"
// (the two z faces: "empty"). Volume: "cylinder".
DefineConstant[ refinement = 1, mirror = 1, tc = 0.055, nc1 = 13, rt1 = 1.284, q1 = 0.8826 ];
// mirror = -1 reflects the half-cylinder about y = 0 (flat side at y = 0,
// arc above it); tc, nc1, rt1, q1: contact-zone half-angle, faces on it, and
// the coarse gradings (defaults: the hertz-cylinder meshes).
R = 8.0;        // radius
a = 3.5;        // inner rectangle: half-width
c = 3.5;        //                  depth
t = 1.0;        // thickness (z)
xt = 1.0;       // half-width of the central column at y = 0

nc = nc1 * refinement;  // faces on the contact-zone arc
ns = 12 * refinement;   // faces on each side of it, along the bottom arc
ny = 13 * refinement;   // along the side arcs and the rectangle height
nr = 18 * refinement;   // radial, rectangle to arc
// geometric ratios (coarse values; the fine mesh takes their square roots):
rt = rt1 ^ (1 / refinement);       // side arcs: geometric growth per face away from the contact zone
q = q1 ^ (1 / refinement);         // contact-zone radial lines, finer toward the arc
pv = 0.92 ^ (1 / refinement);       // rectangle height, finer toward its bottom

s = Sqrt(0.5);
xc = 0.5;       // central column half-width at the rectangle bottom
Point(1) = {0, mirror * (0), 0};
Point(2) = {-a, mirror * (0), 0};                      // A  top-left of the rectangle
Point(3) = {a, mirror * (0), 0};                      // B
Point(4) = {a, mirror * (-c), 0};                     // C
Point(5) = {-a, mirror * (-c), 0};                     // D
Point(6) = {R, mirror * (0), 0};                      // E
Point(7) = {R * s, mirror * (-R * s), 0};             // F
Point(8) = {-R * s, mirror * (-R * s), 0};             // G
Point(9) = {-R, mirror * (0), 0};                      // H
Point(10) = {-xt, mirror * (0), 0};                    // central column, top
Point(11) = {xt, mirror * (0), 0};
Point(12) = {-xc, mirror * (-c), 0};                   // central column, bottom
Point(13) = {xc, mirror * (-c), 0};
Point(14) = {-R * Sin(tc), mirror * (-R * Cos(tc)), 0}; // contact zone on the arc
Point(15) = {R * Sin(tc), mirror * (-R * Cos(tc)), 0};

// rectangle: top, bottom (each left, centre, right), verticals
Line(1) = {2, 10};   Line(2) = {10, 11};   Line(3) = {3, 11};
Line(4) = {5, 12};   Line(5) = {12, 13};   Line(6) = {4, 13};
Line(7) = {2, 5};    Line(8) = {10, 12};   Line(9) = {11, 13};   Line(10) = {3, 4};
// radial lines, inside to arc
Line(11) = {3, 6};   Line(12) = {4, 7};    Line(13) = {13, 15};
Line(14) = {12, 14}; Line(15) = {5, 8};    Line(16) = {2, 9};
// arcs
Circle(17) = {6, 1, 7};      // E-F  right
Circle(18) = {7, 1, 15};     // F-Q2 bottom right, toward the contact zone
Circle(19) = {14, 1, 15};    // contact zone
Circle(20) = {8, 1, 14};     // G-Q1 bottom left, toward the contact zone
Circle(21) = {9, 1, 8};      // H-G  left

Transfinite Curve{2, 5, 19} = nc + 1;
Transfinite Curve{1, 3, 4, 6, 18, 20} = ns + 1 Using Progression 1 / rt;
Transfinite Curve{7, 8, 9, 10} = ny + 1 Using Progression pv;
Transfinite Curve{17, 21} = ny + 1;
Transfinite Curve{11, 12, 15, 16} = nr + 1;
Transfinite Curve{13, 14} = nr + 1 Using Progression q;

Curve Loop(1) = {1, 8, -4, -7};        Plane Surface(1) = {1};   // rectangle, left column
Curve Loop(2) = {2, 9, -5, -8};        Plane Surface(2) = {2};   // rectangle, centre
Curve Loop(3) = {-3, 10, 6, -9};       Plane Surface(3) = {3};   // rectangle, right column
Curve Loop(4) = {11, 17, -12, -10};    Plane Surface(4) = {4};   // right block
Curve Loop(5) = {-6, 12, 18, -13};     Plane Surface(5) = {5};   // bottom right
Curve Loop(6) = {5, 13, -19, -14};     Plane Surface(6) = {6};   // bottom centre (contact)
Curve Loop(7) = {4, 14, -20, -15};     Plane Surface(7) = {7};   // bottom left
Curve Loop(8) = {16, 21, -15, -7};     Plane Surface(8) = {8};   // left block

Transfinite Surface{1} = {2, 10, 12, 5};
Transfinite Surface{2} = {10, 11, 13, 12};
Transfinite Surface{3} = {11, 3, 4, 13};
Transfinite Surface{4} = {3, 6, 7, 4};
Transfinite Surface{5} = {13, 4, 7, 15};
Transfinite Surface{6} = {12, 13, 15, 14};
Transfinite Surface{7} = {5, 12, 14, 8};
Transfinite Surface{8} = {2, 9, 8, 5};
Recombine Surface{1:8};

// Extrude one layer. For the k-th surface (k = 0..7): ex[6k] is its copy at
// z = t, ex[6k+1] the volume, ex[6k+2..6k+5] the sides extruded from the
// curves of its loop, in loop order.
ex[] = Extrude {0, 0, t} { Surface{1:8}; Layers{1}; Recombine; };
Physical Surface("top") = {ex[2], ex[8], ex[14], ex[20], ex[44]};          // curves 1, 2, 3, 11, 16
Physical Surface("curved") = {ex[21], ex[28], ex[34], ex[40], ex[45]};     // curves 17, 18, 19, 20, 21
Physical Surface("frontAndBack") = {1:8, ex[0], ex[6], ex[12], ex[18], ex[24], ex[30], ex[36], ex[42]};
Physical Volume("cylinder") = {ex[1], ex[7], ex[13], ex[19], ex[25], ex[31], ex[37], ex[43]};
