// A unit cube of third-order tetrahedra (Tet20, Gmsh type 29): refused.
// Mesh: gmsh -3 -order 3 order3.geo -o order3.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("cube") = {1};
MeshSize{PointsOf{Volume{1};}} = 2;
Mesh.ElementOrder = 3;
