// A quarter of a cylinder (radius 1, height 2, axis z) in Hex20 cells (Gmsh
// -order 2, Mesh.SecondOrderIncomplete = 1) extruded along z: the mid-edge
// nodes of the arcs lie on the cylinder, and each curved facet of the side
// is an arc swept along z, so the meshed side is exactly a cylinder over a
// quadratic curve, its normal orthogonal to z. The patch test of curved
// second-order cells (test/CMakeLists.txt, driver_quadratic_patch_curved_*):
// under the axial traction p on its top, held on its planes x = 0, y = 0,
// z = 0 in their normal components, the stress is the uniform szz = p and
// the side is free of traction, on the mesh as in the continuum.
// Mesh: gmsh -3 -order 2 cylinder_hex20.geo -o cylinder_hex20.msh
SetFactory("Built-in");
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {0, 1, 0};
Point(4) = {0.45, 0.4, 0};
Point(5) = {Cos(Pi / 4), Sin(Pi / 4), 0};
Point(6) = {0.5, 0, 0};
Point(7) = {0, 0.5, 0};
Line(1) = {1, 6};
Line(2) = {6, 2};
Circle(3) = {2, 1, 5};
Circle(4) = {5, 1, 3};
Line(5) = {3, 7};
Line(6) = {7, 1};
Line(7) = {6, 4};
Line(8) = {4, 5};
Line(9) = {7, 4};
Curve Loop(1) = {1, 7, -9, 6};
Curve Loop(2) = {2, 3, -8, -7};
Curve Loop(3) = {9, 8, 4, 5};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Plane Surface(3) = {3};
Transfinite Curve{1:9} = 3;
Transfinite Surface{1:3};
Recombine Surface{1:3};
v[] = Extrude {0, 0, 2} { Surface{1:3}; Layers{4}; Recombine; };
Physical Volume("block") = {v[1], v[7], v[13]};
e = 1e-6;
Physical Surface("symmetry_x") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 2 + e};
Physical Surface("symmetry_y") = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 2 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 2 - e, 1 + e, 1 + e, 2 + e};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.HighOrderOptimize = 0;
