// One complete second-order hexahedron (Hex27, Gmsh type 12: -order 2
// without Mesh.SecondOrderIncomplete): refused, Hex20 is read.
// Mesh: gmsh -3 -order 2 hex27.geo -o hex27.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 2;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("cube") = {1};
Mesh.ElementOrder = 2;
