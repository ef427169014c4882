// The unit block (0,1)^3 for Gmsh, meshed with P1 tetrahedra: one physical
// volume and the named surfaces Tribos' Boundary Conditions and Contact refer
// to. input/gmsh_block.msh is made from it by
//   gmsh -3 -format msh4 input/gmsh_block.geo -o input/gmsh_block.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("block") = {1};
eps = 1e-6;
Physical Surface("symmetry_x") = Surface In BoundingBox {-eps, -eps, -eps, eps, 1 + eps, 1 + eps};
Physical Surface("symmetry_y") = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, eps, 1 + eps};
Physical Surface("bottom") = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Surface("top") = Surface In BoundingBox {-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 1 + eps};
Physical Surface("sides") = Surface In BoundingBox {1 - eps, -eps, -eps, 1 + eps, 1 + eps, 1 + eps};
Physical Surface("sides") += Surface In BoundingBox {-eps, 1 - eps, -eps, 1 + eps, 1 + eps, 1 + eps};
Mesh.MeshSizeMax = 0.2;
