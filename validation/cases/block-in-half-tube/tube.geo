// block-in-half-tube (thesis §4.6.1): the rigid half-tube, radius 3,
// length 15, axis y = 3, z = 0 along x in [0, 15]; its inner surface
// (y <= 3) is triangulated (unstructured, about h m) and extruded outward
// along its normals into one layer of prisms t m thick (a rigid body
// still needs a volume mesh; only the inner surface matters).
//
//   gmsh -3 -format msh41 tube.geo -o tube-coarse.msh       // 780 triangles
//   gmsh -3 -format msh41 -setnumber h 0.372 -setnumber na 13 -setnumber nx 40 tube.geo -o tube-fine.msh   // 2,440
//
// (Gmsh 4.8.4.) The boundary has na uniform segments per quarter arc and nx
// along the axis; h (the interior size) was tuned to the thesis' triangle
// counts (780 and 2,441; a disc's count with an even boundary is even).
//
// Patches: "inner" (the triangulated surface, contact master), "outer"
// (held fixed), "ends" (the rims at y = 3 and the ends x = 0, 15). Volume "tube".
DefineConstant[ h = 0.658, na = 7, nx = 22, t = 0.25 ];
R = 3.0;
L = 15.0;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.Algorithm = 6;    // Frontal-Delaunay
Point(1) = {0, R, 0, h};        // axis
Point(2) = {0, R, -R, h};
Point(3) = {0, 0, 0, h};        // lowest line
Point(4) = {0, R, R, h};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Transfinite Curve{1, 2} = na + 1;
s[] = Extrude {L, 0, 0} { Curve{1, 2}; };   // s[1], s[5]: the two ruled quarter surfaces
// s[0], s[4]: the arcs at x = L; s[2], s[3], s[6], s[7]: the axial lines
Transfinite Curve{s[0], s[4]} = na + 1;
Transfinite Curve{s[2], s[3], s[6], s[7]} = nx + 1;
// boundary-layer extrusion along the surface normals (one layer, t thick)
v[] = Extrude { Surface{s[1], s[5]}; Layers{1, -t}; Recombine; };
// v[0], v[6]: the outer copies; v[1], v[7]: the volumes; v[2..5], v[8..11]: laterals
Physical Surface("inner") = {s[1], s[5]};
Physical Surface("outer") = {v[0], v[6]};
// the laterals of the ruled surfaces' boundary curves in order: x = 0, the
// lowest line (v[3] = v[11]: between the two volumes), x = L, the rim
Physical Surface("ends") = {v[2], v[4], v[5], v[8], v[9], v[10]};
Physical Volume("tube") = {v[1], v[7]};
