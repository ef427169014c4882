// Hertz impact, quarter model: an elastic ball of radius R = 10 mm centred
// at (0, 0, R), touching the rigid plane z = 0 at the origin, cut by the
// symmetry planes x = 0 and y = 0 (input/hertz_impact.xml, docs/dynamics.md,
// "Hertz impact"). One physical volume ("ball"), tetrahedra refined near the
// contact point by a size field: hc up to the distance rc from the origin,
// then growing by `grow` per unit length up to hs.
//
// Units: mm. The contact radius of input/hertz_impact.xml at the peak is
// a ~ 0.5 mm (a/R = 0.05); Level L sets hc = 0.1 / 2^(L - 1) mm.
// input/hertz_impact.msh is Level 1 (1949 nodes, P1):
//   gmsh -3 -format msh4 input/hertz_impact.geo -o input/hertz_impact.msh
// other levels (0: hc = 0.2 mm, 920 nodes; 2: 0.05 mm, 6418 nodes), and
// second-order tetrahedra (Tet10, the mid-edge nodes on the sphere):
//   gmsh -3 -format msh4 -setnumber Level 2 input/hertz_impact.geo -o hertz_impact_2.msh
//   gmsh -3 -order 2 -format msh4 -setnumber Level 0 input/hertz_impact.geo -o hertz_impact_tet10.msh
// rc, grow and hs may be set the same way (-setnumber hs 2.5).
//
// Physical surfaces: ball_surface (the spherical face, the slave side
// against the plane), ball_sym_x (x = 0), ball_sym_y (y = 0).
SetFactory("OpenCASCADE");

If (!Exists(Level))
  Level = 1;  // gmsh -setnumber Level N
EndIf
R = 10;      // ball radius
hc = 0.1 / 2^(Level - 1);  // element size at the contact point
If (!Exists(rc))
  rc = 1.0;  // radius of the uniformly refined zone (about 2 a)
EndIf
If (!Exists(grow))
  grow = 0.2;  // size gradient beyond it
EndIf
If (!Exists(hs))
  hs = 1.5;  // largest element
EndIf

// The ball, rotated so that its poles (degenerate points of the OCC
// parametrisation) lie on the x axis, far from the contact point; the
// quarter x >= 0, y >= 0.
Sphere(1) = {0, 0, R, R};
Rotate {{0, 1, 0}, {0, 0, R}, Pi / 2} { Volume{1}; }
Box(2) = {0, 0, 0, R, R, 2 * R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };

Physical Volume("ball") = {3};

eps = 1e-6;
sx() = Surface In BoundingBox {-eps, -eps, -eps, eps, R + eps, 2 * R + eps};
sy() = Surface In BoundingBox {-eps, -eps, -eps, R + eps, eps, 2 * R + eps};
sall() = Boundary{ Volume{3}; };
scurved() = sall();
scurved() -= sx();
scurved() -= sy();
Physical Surface("ball_surface") = scurved();
Physical Surface("ball_sym_x") = sx();
Physical Surface("ball_sym_y") = sy();

// Size field: the distance to the contact point (the origin), a plateau of
// size hc up to rc, then a linear growth up to hs.
origin() = Point In BoundingBox {-eps, -eps, -eps, eps, eps, eps};
Field[1] = Distance;
Field[1].PointsList = {origin()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hs;
Field[2].DistMin = rc;
Field[2].DistMax = rc + (hs - hc) / grow;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeMax = hs;
Mesh.Optimize = 1;
