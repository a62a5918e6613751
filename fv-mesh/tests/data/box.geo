// Test fixture for the Gmsh reader: a 1 x 0.5 x 0.25 box of tetrahedra.
// Physical surfaces: xmin, xmax, bottom (z = 0), top (z = 0.25), and the two
// y faces together as "sides" except y = 0.5, which is left in no group
// (it must end up in defaultFaces).
//   gmsh -3 -format msh41 box.geo -o box_ascii.msh
//   gmsh -3 -format msh41 -bin box.geo -o box_binary.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.25};
Mesh.CharacteristicLengthMax = 0.2;
Mesh.CharacteristicLengthMin = 0.2;
// OpenCASCADE box faces: 1 x=0, 2 x=1, 3 y=0, 4 y=0.5, 5 z=0, 6 z=top
Physical Surface("xmin") = {1};
Physical Surface("xmax") = {2};
Physical Surface("sides") = {3};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
Physical Volume("box") = {1};
