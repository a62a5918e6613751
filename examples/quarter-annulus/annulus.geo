// Quarter annulus, inner radius 1, outer radius 2, in the x-y plane, one
// cell thick in z (0.1): structured hexahedra, 20 radial x 30 circumferential.
// Mesh with:  gmsh -3 -format msh41 annulus.geo -o annulus.msh
ri = 1.0;
ro = 2.0;
t = 0.1;
nr = 20;   // cells across the wall (radial)
nc = 30;   // cells around the quarter (circumferential)

Point(1) = {0, 0, 0};
Point(2) = {ri, 0, 0};
Point(3) = {ro, 0, 0};
Point(4) = {0, ro, 0};
Point(5) = {0, ri, 0};

Line(1) = {2, 3};          // on y = 0
Circle(2) = {3, 1, 4};     // outer arc
Line(3) = {4, 5};          // on x = 0
Circle(4) = {5, 1, 2};     // inner arc

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = nc + 1;
Transfinite Surface{1} = {2, 3, 4, 5};
Recombine Surface{1};

out[] = Extrude {0, 0, t} { Surface{1}; Layers{1}; Recombine; };
// out[0] = top surface, out[1] = volume, out[2..5] = sides from curves 1..4

Physical Surface("inner") = {out[5]};
Physical Surface("outer") = {out[3]};
Physical Surface("symx") = {out[4]};
Physical Surface("symy") = {out[2]};
Physical Surface("frontAndBack") = {1, out[0]};
Physical Volume("annulus") = {out[1]};
