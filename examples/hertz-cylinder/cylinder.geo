// Hertz cylinder example: the lower half of a cylinder of radius R = 8 m,
// flat top on y = 0, lowest point (0, -8). A plane mesh (x-y plane): fvc
// extrudes it one cell thick (z from 0 to 1, so forces are per metre of
// cylinder) and names the two new faces "frontAndBack".
//
//   gmsh -2 -format msh41 cylinder.geo -o cylinder.msh
//
// Layout: the mesh of validation/cases/hertz-cylinder (an O-grid of the half
// disc: an inner rectangle split into three columns, a left and a right
// block up to the side arcs, three ring blocks along the bottom arc),
// refined at the contact only: nc faces of 0.034 m over the bottom
// |theta| <= tc (the Hertz half-width here is about 0.28 m, so about 16
// faces touch), ns faces on each side growing by rt per face, radial
// cells at the contact graded by q so that they are nearly square.
// 2,018 quadrilaterals.
//
// Physical curves (patches): "top" (y = 0, driven), "contact" (the bottom
// arc, -45 deg to +45 deg, the contact surface), "free" (the two side arcs,
// traction-free). Physical surface "cylinder".
DefineConstant[ tc = 0.055, nc = 26, ns = 12, rt = 1.39, q = 0.831 ];
R = 8.0;        // radius
a = 3.5;        // inner rectangle: half-width
c = 3.5;        //                  depth
xt = 1.0;       // half-width of the central column at y = 0
xc = 0.5;       // and at the rectangle bottom
ny = 13;        // cells along the side arcs and the rectangle height
nr = 18;        // cells radially, rectangle to arc
pv = 0.92;      // rectangle height: finer toward its bottom
s = Sqrt(0.5);

Point(1) = {0, 0, 0};                          // centre
Point(2) = {-a, 0, 0};                         // rectangle corners
Point(3) = {a, 0, 0};
Point(4) = {a, -c, 0};
Point(5) = {-a, -c, 0};
Point(6) = {R, 0, 0};                          // arc: right end
Point(7) = {R * s, -R * s, 0};                 //      -45 deg
Point(8) = {-R * s, -R * s, 0};                //      -135 deg
Point(9) = {-R, 0, 0};                         //      left end
Point(10) = {-xt, 0, 0};                       // central column, top
Point(11) = {xt, 0, 0};
Point(12) = {-xc, -c, 0};                      // central column, bottom
Point(13) = {xc, -c, 0};
Point(14) = {-R * Sin(tc), -R * Cos(tc), 0};   // contact zone on the arc
Point(15) = {R * Sin(tc), -R * Cos(tc), 0};

// rectangle: top, bottom (each left, centre, right), verticals
Line(1) = {2, 10};   Line(2) = {10, 11};   Line(3) = {3, 11};
Line(4) = {5, 12};   Line(5) = {12, 13};   Line(6) = {4, 13};
Line(7) = {2, 5};    Line(8) = {10, 12};   Line(9) = {11, 13};   Line(10) = {3, 4};
// radial lines, rectangle to arc
Line(11) = {3, 6};   Line(12) = {4, 7};    Line(13) = {13, 15};
Line(14) = {12, 14}; Line(15) = {5, 8};    Line(16) = {2, 9};
// arcs
Circle(17) = {6, 1, 7};      // right side
Circle(18) = {7, 1, 15};     // bottom right, toward the contact zone
Circle(19) = {14, 1, 15};    // contact zone
Circle(20) = {8, 1, 14};     // bottom left, toward the contact zone
Circle(21) = {9, 1, 8};      // left side

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
Recombine Surface{1:8};                       // quadrilaterals

Physical Curve("top") = {1, 2, 3, 11, 16};
Physical Curve("contact") = {18, 19, 20};
Physical Curve("free") = {17, 21};
Physical Surface("cylinder") = {1:8};
