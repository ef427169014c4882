// A single-bolt lap joint, half model (y >= 0; the plane y = 0 through the
// bolt axis is a symmetry plane). Two steel plates 40 x 20 x 3 mm overlap
// by 20 mm: "lower" (0,40) x (0,10) x (0,3) and "upper" (20,60) x (0,10) x
// (3,6), both with the half bolt hole of radius rh at (30, 0). The bolt is
// not modelled: its clamp is a pressure on the washer annulus rh < r < rw
// on top of "upper" (clamp_top) and under "lower" (clamp_bottom). Each
// plate is cut by the cylinder r = rw so that the annuli are faces of their
// own; the plates share no node and meet at z = 3 only through a contact
// pair. Mesh size h (mm), h / refine on the washer. Units: mm (N, MPa).
// input/lap_joint.msh (read by input/lap_joint.xml) is made by
//   gmsh -3 -format msh4 -setnumber h 1.7 input/lap_joint.geo -o input/lap_joint.msh
SetFactory("OpenCASCADE");

DefineConstant[h = 1.7, refine = 2, rh = 3, rw = 6];
Box(1) = {0, 0, 0, 40, 10, 3};
Box(2) = {20, 0, 3, 40, 10, 3};
// The bolt hole and the half y < 0, cut away.
For p In {1 : 2}
  hole = newv; Cylinder(hole) = {30, 0, -1, 0, 0, 8, rh};
  half = newv; Box(half) = {0, -20, -5, 80, 20, 20};
  BooleanDifference{ Volume{p}; Delete; }{ Volume{hole, half}; Delete; }
EndFor
// Each plate: the ring under the washer and the rest, meshed conformingly.
For p In {1 : 2}
  c = newv; Cylinder(c) = {30, 0, -1, 0, 0, 8, rw};
  ring[] = BooleanIntersection{ Volume{p}; }{ Volume{c}; Delete; };
  c = newv; Cylinder(c) = {30, 0, -1, 0, 0, 8, rw};
  rest[] = BooleanDifference{ Volume{p}; Delete; }{ Volume{c}; Delete; };
  parts[] = BooleanFragments{ Volume{ring[], rest[]}; Delete; }{};
  If (p == 1)
    lower[] = parts[];
  Else
    upper[] = parts[];
  EndIf
EndFor
e = 1e-6;
Physical Volume("lower") = {lower[]};
Physical Volume("upper") = {upper[]};
// Faces by their place: each plate's boundary, kept where it lies in a box.
lowerFaces[] = Abs(Boundary{ Volume{lower[]}; });
upperFaces[] = Abs(Boundary{ Volume{upper[]}; });
Macro Select
  // from faces[] the faces inside (x0,y0,z0)-(x1,y1,z1) into sel[]
  sel[] = {};
  For i In {0 : #faces[] - 1}
    bb[] = BoundingBox Surface{faces[i]};
    If (bb[0] > x0 - e && bb[1] > y0 - e && bb[2] > z0 - e && bb[3] < x1 + e && bb[4] < y1 + e && bb[5] < z1 + e)
      sel[] += faces[i];
    EndIf
  EndFor
Return
faces[] = lowerFaces[];
x0 = 0; y0 = 0; z0 = 0; x1 = 0; y1 = 10; z1 = 3; Call Select;
Physical Surface("lower_end") = {sel[]};
x0 = 0; y0 = 0; z0 = 3; x1 = 40; y1 = 10; z1 = 3; Call Select;
Physical Surface("lower_top") = {sel[]};
x0 = 30 - rw; y0 = 0; z0 = 0; x1 = 30 + rw; y1 = rw; z1 = 0; Call Select;
Physical Surface("clamp_bottom") = {sel[]};
x0 = 0; y0 = 0; z0 = 0; x1 = 40; y1 = 0; z1 = 3; Call Select;
lowerSym[] = sel[];
faces[] = upperFaces[];
x0 = 60; y0 = 0; z0 = 3; x1 = 60; y1 = 10; z1 = 6; Call Select;
Physical Surface("upper_end") = {sel[]};
x0 = 20; y0 = 0; z0 = 3; x1 = 60; y1 = 10; z1 = 3; Call Select;
Physical Surface("upper_bottom") = {sel[]};
x0 = 30 - rw; y0 = 0; z0 = 6; x1 = 30 + rw; y1 = rw; z1 = 6; Call Select;
Physical Surface("clamp_top") = {sel[]};
x0 = 20; y0 = 0; z0 = 3; x1 = 60; y1 = 0; z1 = 6; Call Select;
upperSym[] = sel[];
Physical Surface("symmetry_y") = {lowerSym[], upperSym[]};
MeshSize{:} = h;
MeshSize{PointsOf{ Volume{lower[0], upper[0]}; }} = h / refine;
