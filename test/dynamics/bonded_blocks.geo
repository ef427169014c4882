// Two unit blocks stacked along z and bonded: one mesh whose bodies "lower"
// (0,1)^3 and "upper" (0,1)^2 x (1,2) share the nodes of the plane z = 1
// (BooleanFragments), coarse P1 tetrahedra. Read by bonded_blocks.xml (the
// refusal of shared nodes with different initial velocities,
// test/bad_inputs/cases.txt). bonded_blocks.msh is made from it by
//   gmsh -3 -format msh4 test/dynamics/bonded_blocks.geo -o test/dynamics/bonded_blocks.msh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
eps = 1e-6;
Physical Volume("lower") = Volume In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, 1 + eps};
Physical Volume("upper") = Volume In BoundingBox{-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 2 + eps};
Physical Surface("bottom") = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Mesh.MeshSizeMax = 0.5;
