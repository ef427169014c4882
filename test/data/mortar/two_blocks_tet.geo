// input/two_blocks.geo with linear tetrahedra: two unit blocks stacked
// along z, "lower" with nl^3 and "upper" with nu^3 structured cells, each
// cell split into tetrahedra (no recombination), so the contact faces are
// triangulations whose diagonals do not match. Faces named as in
// two_blocks.geo. The upper block is tu thick (default 1), its mesh lines
// graded by the progression qu (default 1: uniform).
SetFactory("OpenCASCADE");
DefineConstant[nl = 3, nu = 4, tu = 1, qu = 1];
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, tu};
n[] = {nl, nu};
For v In {1 : 2}
  faces[] = Boundary{ Volume{v}; };
  edges[] = Unique(Abs(Boundary{ Surface{faces[]}; }));
  Transfinite Curve{edges[]} = n[v - 1] + 1 Using Progression (v == 2 ? qu : 1);
  Transfinite Surface{faces[]};
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
