// The stick-slip oscillator of input/stick_slip.xml (docs/dynamics.md,
// "Stick-slip oscillator"): a block (the mass) (0,a) x (0,b) x (0,c) on the
// rigid plane z = 0, and a soft bar (the spring) (-L,0) x (0,b) x (0,c)
// bonded to its face x = 0: the two bodies share the nodes of that face. Q1
// hexahedra, a rectangle in the plane z = 0 extruded along z; nb, ns and ny
// cells along x in the block, along x in the bar and along y, nz along z.
// input/stick_slip.msh is made from it by
//   gmsh -3 -format msh4 input/stick_slip.geo -o input/stick_slip.msh
DefineConstant[a = 0.1, b = 0.1, c = 0.05, L = 0.1, nb = 4, ns = 4, ny = 4, nz = 2];
Point(1) = {-L, 0, 0};
Point(2) = {0, 0, 0};
Point(3) = {a, 0, 0};
Point(4) = {a, b, 0};
Point(5) = {0, b, 0};
Point(6) = {-L, b, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 5} = ns + 1;
Transfinite Curve{2, 4} = nb + 1;
Transfinite Curve{3, 6, 7} = ny + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
out[] = Extrude{0, 0, c}{ Surface{1, 2}; Layers{nz}; Recombine; };
Physical Volume("spring") = {out[1]};
Physical Volume("block") = {out[7]};
eps = 1e-6;
Physical Surface("block_bottom") = {2};
Physical Surface("block_top") = Surface In BoundingBox {-eps, -eps, c - eps, a + eps, b + eps, c + eps};
Physical Surface("spring_end") = Surface In BoundingBox {-L - eps, -eps, -eps, -L + eps, b + eps, c + eps};
