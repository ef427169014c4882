// A 2 x 1 x 1 block of Tet10 cells (Gmsh -order 2): the patch test of the
// quadratic tetrahedra (test/CMakeLists.txt, quadratic_patch_*).
// Mesh: gmsh -3 -order 2 block_tet10.geo -o block_tet10.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
e = 1e-6;
Physical Volume("block") = {1};
Physical Surface("symmetry_x") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("side_x") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("symmetry_y") = Surface In BoundingBox{-e, -e, -e, 2 + e, e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
MeshSize{PointsOf{Volume{1};}} = 0.6;
Mesh.ElementOrder = 2;
