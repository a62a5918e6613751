// Solid bar for the axisymmetric patch test (validation test
// axisymmetric_bar): radius a = 1, length L = 2 along the y axis, the
// r-y section (x = r) revolved by ±2.5° into a one-cell wedge
// (Layers{1}; Recombine); the cells on the axis are prisms with a
// collapsed edge. nr × ny cells, nr graded towards the axis so that the
// first ring is thin (the near-axis cells are where a wedge is hardest).
//
//   gmsh -3 -format msh41 bar.geo -o bar.msh
//   gmsh -3 -format msh41 -setnumber start 0 bar.geo -o bar-offset.msh
//
// (`start`: the angle of the back plane, degrees; bar-offset.msh spans 0°
// to 5°, its mid-plane off the coordinate planes.)
//
// Patches: "bottom" (y = 0), "top" (y = L), "outer" (r = a),
// "front"/"back" (the wedge planes). No patch on the axis. Volume "bar".
DefineConstant[ nr = 8, ny = 6, angle = 2.5, grading = 0.8, start = -2.5 ];
a = 1; L = 2;
Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {a, L, 0};
Point(4) = {0, L, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1} = nr + 1 Using Progression 1 / grading;
Transfinite Curve{3} = nr + 1 Using Progression grading;
Transfinite Curve{2, 4} = ny + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1} = {1, 2, 3, 4};
Recombine Surface{1};

th = angle * Pi / 180;
Rotate {{0, 1, 0}, {0, 0, 0}, start * Pi / 180} { Surface{1}; }
// e[0] the copy of the surface at +angle, e[1] the volume, e[2..] the
// laterals of curves 1..4
e[] = Extrude {{0, 1, 0}, {0, 0, 0}, 2 * th} { Surface{1}; Layers{1}; Recombine; };

Physical Surface("back") = {1};
Physical Surface("front") = {e[0]};
Physical Surface("bottom") = {e[2]};
Physical Surface("outer") = {e[3]};
Physical Surface("top") = {e[4]};
Physical Volume("bar") = {e[1]};
