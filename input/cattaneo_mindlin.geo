// Cattaneo-Mindlin, half model: an elastic hemisphere (radius R, flat top
// face z = R) touching an elastic block at the origin, both cut by the
// symmetry plane y = 0, which contains the tangential load (along x). Two
// physical volumes ("sphere", "block") meshed separately (no Coherence /
// BooleanFragments: no shared nodes), P1 tetrahedra, refined near the
// contact point by a size field; the block (master side) is the finer: a
// slave finer than its master resolves the master's nodes (docs/hertz.md,
// "Which side is finer").
//
// Units: mm (forces in N, moduli in MPa). Level L sets the element size at
// the contact point, hc = 0.2 / 2^((L - 1) / 2) mm on the sphere (2/3 hc on
// the block): 0.2, 0.141, 0.1 mm for Levels 1, 2, 3; the contact radius of
// input/cattaneo_mindlin.xml is a ~ 1 mm. The shipped meshes:
//   gmsh -3 -format msh4 -setnumber Level L input/cattaneo_mindlin.geo -o input/cattaneo_mindlin_L.msh
// (scripts/cattaneo_mindlin.py makes and runs them; docs/cattaneo_mindlin.md).
//
// Physical surfaces: sphere_contact (the spherical face, slave), sphere_top
// (z = R, displaced), sphere_sym_y; block_top (z = 0, master), block_bottom
// (z = -H, fixed), block_sym_y, block_sides.
SetFactory("OpenCASCADE");

If (!Exists(Level))
  Level = 1;  // gmsh -setnumber Level N
EndIf
R = 10;      // sphere radius
L = 30;      // block half extent along x, extent along y (half model)
H = 30;      // block depth
hc = 0.2 / 2^((Level - 1) / 2);  // element size at the contact point (sphere)
rc = 1.2;    // radius of the uniformly refined zone (about 1.2 a)
grow = 0.4;  // size gradient beyond it
hs = 3;      // largest element, sphere
hb = 6;      // largest element, block
ratio = 2 / 3; // block (master) size / sphere (slave) size near the contact

// The sphere, rotated so that its poles (degenerate points of the OCC
// parametrisation) lie on the x axis at the rim of the top face, far from
// the contact point; the half y >= 0 of its lower half.
Sphere(1) = {0, 0, R, R};
Rotate {{0, 1, 0}, {0, 0, R}, Pi / 2} { Volume{1}; }
Box(2) = {-R, 0, 0, 2 * R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {-L, 0, -H, 2 * L, L, H};

Physical Volume("sphere") = {3};
Physical Volume("block") = {4};

eps = 1e-6;
sy() = Surface In BoundingBox {-R - eps, -eps, -eps, R + eps, eps, R + eps};
st() = Surface In BoundingBox {-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
sall() = Boundary{ Volume{3}; };
scurved() = sall();
scurved() -= sy();
scurved() -= st();
Physical Surface("sphere_contact") = scurved();
Physical Surface("sphere_top") = st();
Physical Surface("sphere_sym_y") = sy();

Physical Surface("block_top") = Surface In BoundingBox {-L - eps, -eps, -eps, L + eps, L + eps, eps};
Physical Surface("block_bottom") = Surface In BoundingBox {-L - eps, -eps, -H - eps, L + eps, L + eps, -H + eps};
Physical Surface("block_sym_y") = Surface In BoundingBox {-L - eps, -eps, -H - eps, L + eps, eps, eps};
Physical Surface("block_sides") = Surface In BoundingBox {-L - eps, -eps, -H - eps, -L + eps, L + eps, eps};
Physical Surface("block_sides") += Surface In BoundingBox {L - eps, -eps, -H - eps, L + eps, L + eps, eps};
Physical Surface("block_sides") += Surface In BoundingBox {-L - eps, L - eps, -H - eps, L + eps, L + eps, eps};

// Size fields: the distance to the contact point (the origin), a plateau of
// size hc up to rc, then a linear growth; one per body, each restricted to
// its body and its boundary.
origin() = Point In BoundingBox {-eps, -eps, -eps, eps, eps, eps};
Field[1] = Distance;
Field[1].PointsList = {origin()};

Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hs;
Field[2].DistMin = rc;
Field[2].DistMax = rc + (hs - hc) / grow;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].VolumesList = {3};
Field[3].SurfacesList = {sall()};
cs() = Abs(Boundary{ Surface{sall()}; });
Field[3].CurvesList = {cs()};

Field[4] = Threshold;
Field[4].InField = 1;
Field[4].SizeMin = ratio * hc;
Field[4].SizeMax = hb;
Field[4].DistMin = rc;
Field[4].DistMax = rc + (hb - ratio * hc) / grow;
ball() = Boundary{ Volume{4}; };
Field[5] = Restrict;
Field[5].InField = 4;
Field[5].VolumesList = {4};
Field[5].SurfacesList = {ball()};
cb() = Abs(Boundary{ Surface{ball()}; });
Field[5].CurvesList = {cb()};

Field[6] = Min;
Field[6].FieldsList = {3, 5};
Background Field = 6;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeMax = hb;
Mesh.Optimize = 1;
