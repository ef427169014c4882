// Two unit blocks stacked along z, meshed separately with Q1 hexahedra:
// "lower" (0,1)^2 x (0,1) with nl^3 cells and "upper" (0,1)^2 x (1,2) with
// nu^3 cells. The blocks share no node (two OpenCASCADE boxes that are not
// fragmented): they meet at z = 1 only through a contact pair (or a glued
// one), node-matching when nl = nu (two_blocks_matching.geo), non-matching
// otherwise. An OpenCASCADE box lists its faces as xmin, xmax, ymin, ymax,
// zmin, zmax. input/two_blocks.msh (read by input/two_blocks_coulomb.xml) is
// made from it by
//   gmsh -3 -format msh4 input/two_blocks.geo -o input/two_blocks.msh
SetFactory("OpenCASCADE");
DefineConstant[nl = 3, nu = 4];
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
n[] = {nl, nu};
For v In {1 : 2}
  faces[] = Boundary{ Volume{v}; };
  edges[] = Unique(Abs(Boundary{ Surface{faces[]}; }));
  Transfinite Curve{edges[]} = n[v - 1] + 1;
  Transfinite Surface{faces[]};
  Recombine Surface{faces[]};
  Transfinite Volume{v};
EndFor
lower[] = Boundary{ Volume{1}; };
upper[] = Boundary{ Volume{2}; };
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("lower_bottom") = {lower[4]};
Physical Surface("lower_top") = {lower[5]};
Physical Surface("upper_bottom") = {upper[4]};
Physical Surface("upper_top") = {upper[5]};
Physical Surface("symmetry_x") = {lower[0], upper[0]};
Physical Surface("symmetry_y") = {lower[2], upper[2]};
Physical Surface("lower_x1") = {lower[1]};
Physical Surface("upper_x1") = {upper[1]};
