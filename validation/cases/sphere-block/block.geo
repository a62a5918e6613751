// sphere-block (thesis §5.2.5): the block under the sphere, half-symmetry
// model: x ∈ [-L, L], y ∈ [0, L], z ∈ [-H, 0]; the sphere touches the top
// z = 0 at the origin.
//
//   gmsh -3 -format msh41 block.geo -o block.msh
//
// Hexahedra, graded toward the contact point: along x (both ways), y and
// −z, `nu` uniform cells of size h from the origin, then cells growing by
// the factor g up to the block edge (the last cell takes the remainder).
// The grid is one line extruded twice with explicit layer heights.
//
// Patches: "top" (z = 0, contact), "bottom" (z = −H), "symmetry" (y = 0),
// "sides" (x = ±L, y = L). Volume "block".
DefineConstant[ L = 0.6, H = 0.6, h = 0.014, nu = 8, g = 1.3 ];

// cumulative positions from 0 to the edge: nu cells of h, then m − 1
// cells h g^k (k = 1 … m − 1) and a last one up to the edge
Macro Positions
  m = Floor(Log((D - nu * h) * (g - 1) / h + g) / Log(g) - 1);
  pos[] = {};
  For i In {1 : nu}
    pos[i - 1] = i * h;
  EndFor
  For k In {1 : m - 1}
    pos[nu + k - 1] = pos[nu + k - 2] + h * g^k;
  EndFor
  pos[nu + m - 1] = D;
Return

D = L; Call Positions;
n = #pos[];
// layer fractions over [−L, L] (mirror) and over [0, L]
fx[] = {}; lx[] = {}; fy[] = {}; ly[] = {};
For i In {n - 2 : 0 : -1}
  fx[#fx[]] = (L - pos[i]) / (2 * L);
EndFor
fx[#fx[]] = 0.5;
For i In {0 : n - 1}
  fx[#fx[]] = (L + pos[i]) / (2 * L);
  fy[i] = pos[i] / L; ly[i] = 1;
EndFor
For i In {0 : #fx[] - 1}
  lx[i] = 1;
EndFor
// the depth: the same grading with H in place of L
D = H; Call Positions;
fz[] = {}; lz[] = {};
For i In {0 : #pos[] - 1}
  fz[i] = pos[i] / H; lz[i] = 1;
EndFor

Point(1) = {-L, 0, 0};
ex[] = Extrude {2 * L, 0, 0} { Point{1}; Layers{lx[], fx[]}; };
ey[] = Extrude {0, L, 0} { Line{ex[1]}; Layers{ly[], fy[]}; Recombine; };
ez[] = Extrude {0, 0, -H} { Surface{ey[1]}; Layers{lz[], fz[]}; Recombine; };
// ez[0] bottom copy, ez[1] volume, ez[2..5] laterals of the surface's curves
e = 1e-6;
Physical Surface("top") = {ey[1]};
Physical Surface("bottom") = {ez[0]};
Physical Surface("symmetry") = Surface In BoundingBox{-L - e, -e, -H - e, L + e, e, e};
Physical Surface("sides") = {ez[3], ez[4], ez[5]};
Physical Volume("block") = {ez[1]};
