// Cantilever 2 x 0.2 x 0.2 (m) in linear tetrahedra: root face "root",
// free end "tip", the four long sides "sides".
// gmsh beam.geo -3 -setnumber h 0.05 -o beam.msh   (3,6xx tetrahedra)
// gmsh beam.geo -3 -setnumber h 0.1 -o beam-coarse.msh   (4xx tetrahedra)
SetFactory("OpenCASCADE");
If (!Exists(h))
  h = 0.05;
EndIf
Box(1) = {0, 0, 0, 2, 0.2, 0.2};
Physical Volume("beam") = {1};
eps = 1e-6;
r[] = Surface In BoundingBox{-eps, -eps, -eps, eps, 0.2 + eps, 0.2 + eps};
t[] = Surface In BoundingBox{2 - eps, -eps, -eps, 2 + eps, 0.2 + eps, 0.2 + eps};
Physical Surface("root") = {r[]};
Physical Surface("tip") = {t[]};
s[] = Surface{:};
s[] -= {r[], t[]};
Physical Surface("sides") = {s[]};
Mesh.CharacteristicLengthMax = h;
Mesh.MshFileVersion = 4.1;
