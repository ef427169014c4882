// A 2 x 1 x 1 block of 3 x 2 x 2 Hex20 cells (Gmsh -order 2 with
// Mesh.SecondOrderIncomplete = 1: serendipity, no face or centre nodes):
// the patch test of the quadratic hexahedra (test/CMakeLists.txt).
// Mesh: gmsh -3 -order 2 block_hex20.geo -o block_hex20.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
e = 1e-6;
Transfinite Curve{:} = 3;
Transfinite Curve{Curve In BoundingBox{-e, -e, -e, 2 + e, e, e}} = 4;
Transfinite Curve{Curve In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, e}} = 4;
Transfinite Curve{Curve In BoundingBox{-e, -e, 1 - e, 2 + e, e, 1 + e}} = 4;
Transfinite Curve{Curve In BoundingBox{-e, 1 - e, 1 - e, 2 + e, 1 + e, 1 + e}} = 4;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("block") = {1};
Physical Surface("symmetry_x") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("side_x") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("symmetry_y") = Surface In BoundingBox{-e, -e, -e, 2 + e, e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
