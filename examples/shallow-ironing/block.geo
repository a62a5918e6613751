// The mesh of validation/cases/shallow-ironing, unchanged.
//
// Shallow ironing block (thesis §5.3.2, fig. 5.17; Fischer & Wriggers
// 2006), mm: 1.2 wide (x 0.2–1.4), top at y = 5.4, flat sides from
// y = 4.5 up, bottom a circular arc from (0.2, 4.5) through (0.8, 4.2) to
// (1.4, 4.5): radius 0.75, centre (0.8, 4.95). 12 × 6 cells (transfinite,
// quadrilaterals), one layer of thickness 1 in z (plane strain, the z
// patches are "empty").
//
//   gmsh -3 -format msh41 block.geo -o block.msh
//
// Patches: "top" (driven), "bottom" (the arc, contact), "left", "right"
// (traction-free), "back" (z = 0), "front" (z = 1). Volume "block".
x0 = 0.2; x1 = 1.4; xc = 0.8;
ytop = 5.4; yside = 4.5; ycentre = 4.95;
nx = 12; ny = 6;
Point(1) = {x0, yside, 0};
Point(2) = {x1, yside, 0};
Point(3) = {x1, ytop, 0};
Point(4) = {x0, ytop, 0};
Point(5) = {xc, ycentre, 0};   // arc centre
Circle(1) = {1, 5, 2};         // bottom arc (the short one, through (0.8, 4.2))
Line(2) = {2, 3};              // right
Line(3) = {3, 4};              // top
Line(4) = {4, 1};              // left
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1} = {1, 2, 3, 4};
Recombine Surface{1};
// e[0]: the copy at z = 1, e[1]: the volume, e[2..5]: laterals of curves 1..4
e[] = Extrude {0, 0, 1} { Surface{1}; Layers{1}; Recombine; };
Physical Surface("bottom") = {e[2]};
Physical Surface("right") = {e[3]};
Physical Surface("top") = {e[4]};
Physical Surface("left") = {e[5]};
Physical Surface("back") = {1};
Physical Surface("front") = {e[0]};
Physical Volume("block") = {e[1]};
