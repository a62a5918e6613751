// two unit-depth boxes side by side (x 0-0.5 and 0.5-1), one hexahedron
// each, NOT fragmented: the face x = 0.5 is two coincident boundary faces,
// so the right box is held by nothing
SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 0.5,1,1};
Box(2) = {0.5,0,0, 0.5,1,1};
e = 1e-6;
Physical Surface("xmin") = Surface In BoundingBox{-e,-e,-e, e,1+e,1+e};
Physical Surface("xmax") = Surface In BoundingBox{1-e,-e,-e, 1+e,1+e,1+e};
Physical Volume("solid") = {1,2};
Transfinite Curve{:} = 2; Transfinite Surface{:}; Recombine Surface{:}; Transfinite Volume{:};
