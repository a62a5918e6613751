// block-in-half-tube (thesis §4.6.1; Neto et al.): the elastic block
// 2 x 2 x 2 m whose bottom is curved like the tube (radius 3 about the
// tube axis y = 3, z = 0), 10 x 10 x 10 = 1,000 hexahedra.
//
//   gmsh -3 -format msh41 block.geo -o block.msh
//
// Axes: x along the tube (sliding direction), y up, z across. The block
// spans x in [x0, x0 + 2], z in [-1, 1], top at y = 2; its bottom is the arc
// y = 3 - sqrt(R^2 - z^2) shifted down by the initial overlap 0.01, i.e.
// the bottom line of the block is 0.01 below the tube's (y = 0).
// Patches: "top" (y = 2 - overlap, driven), "bottom" (curved, contact),
// "sides" (the four vertical faces, free). Volume "block".
DefineConstant[ n = 10, overlap = 0.01, x0 = 1.5 ];
R = 3.0;   // tube radius
a = 2.0;   // block edge
yc = R - overlap;   // axis of the block's bottom arc
zb = Sqrt(R * R - 1.0);
Point(1) = {x0, yc, 0};                 // arc centre
Point(3) = {x0, yc - zb, -1};           // bottom corners
Point(4) = {x0, yc - zb, 1};
Point(5) = {x0, a - overlap, 1};        // top corners
Point(6) = {x0, a - overlap, -1};
Circle(1) = {3, 1, 4};                  // bottom arc (< pi)
Line(2) = {4, 5};
Line(3) = {5, 6};
Line(4) = {6, 3};
Transfinite Curve{1:4} = n + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1} = {3, 4, 5, 6};
Recombine Surface{1};
// ex[0]: copy at x0 + a, ex[1]: volume, ex[2..5]: laterals of curves 1..4
ex[] = Extrude {a, 0, 0} { Surface{1}; Layers{n}; Recombine; };
Physical Surface("bottom") = {ex[2]};
Physical Surface("top") = {ex[4]};
Physical Surface("sides") = {1, ex[0], ex[3], ex[5]};
Physical Volume("block") = {ex[1]};
