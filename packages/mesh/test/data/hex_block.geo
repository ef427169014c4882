// A 2 x 1 x 1 block of 4 x 2 x 2 hexahedra (transfinite, recombined), meshed
// by Gmsh at run time (the tests opt in: Mesh/Run Geo Script): the Hex8 path
// of the Gmsh reader and of the driver (test/CMakeLists.txt). Surfaces:
// bottom z = 0, top z = 1, clamp x = 0, front y = 0.
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 5;
Transfinite Curve{2, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("beam") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("clamp") = {out[5]};
Physical Surface("front") = {out[2]};
