// Cantilever 2 x 0.2 x 0.2 meshed with unstructured tetrahedra (Gmsh's
// default 3-D algorithm): `gmsh -3 -format msh41 beam.geo -o beam.msh`
// (h = 0.05, 3,566 tets) and `-setnumber h 0.1 ... -o beam-coarse.msh`
// (434 tets).
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.05 ];
Box(1) = {0, 0, 0, 2, 0.2, 0.2};
Mesh.MeshSizeMax = h;
Physical Surface("xmin") = {1};
Physical Surface("xmax") = {2};
Physical Surface("ymin") = {3};
Physical Surface("ymax") = {4};
Physical Surface("zmin") = {5};
Physical Surface("zmax") = {6};
Physical Volume("beam") = {1};
