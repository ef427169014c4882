// An elliptic cylinder (semi-axes 1 and 0.75, "core") in the matching cavity
// of a block [-2, 2]^2 ("block"), both of height H along z, meshed
// separately: each cross-section triangulated (edges hc in the core, hb in
// the block) and extruded in layers (nc and nb) into linear tetrahedra, so
// the two triangulations of the curved interface match neither around nor
// along z, and its facets stand vertical. Not being round, the interface
// holds the core's rotation without friction. Faces: core_side, cavity (the
// interface), block_x2, block_xm, block_y2, block_ym (the block's outer
// faces x = 2, x = -2, y = 2, y = -2), ends (z = 0 and z = H of both).
DefineConstant[hc = 0.1, hb = 0.14, H = 0.2, nc = 3, nb = 2];
// The ellipse twice, once for each body (distinct points and arcs, the
// block's split at other angles: the bodies share no node, and no point of
// one lies on a point of the other, which the extrusion would confuse),
// and the square [-2, 2]^2.
Function Ellipse4
  c = newp; Point(c) = {0, 0, 0, h};
  axis = newp; Point(axis) = {0.5, 0, 0, h};
  p[] = {};
  For k In {0 : 3}
    p[k] = newp; Point(p[k]) = {Cos(t0 + k * Pi / 2), 0.75 * Sin(t0 + k * Pi / 2), 0, h};
  EndFor
  arcs[] = {};
  For k In {0 : 3}
    arcs[k] = newc; Ellipse(arcs[k]) = {p[k], c, axis, p[(k + 1) % 4]};
  EndFor
  loop = newll; Curve Loop(loop) = {arcs[]};
Return
h = hc;
t0 = 0;
Call Ellipse4;
Plane Surface(1) = {loop};
h = hb;
t0 = 0.3;
Call Ellipse4;
hole = loop;
q[] = {};
For k In {0 : 3}
  q[k] = newp; Point(q[k]) = {2 * ((k == 1 || k == 2) ? 1 : -1), 2 * ((k >= 2) ? 1 : -1), 0, hb};
EndFor
sides[] = {};
For k In {0 : 3}
  sides[k] = newc; Line(sides[k]) = {q[k], q[(k + 1) % 4]};
EndFor
Curve Loop(100) = {sides[]};
Plane Surface(2) = {100, hole};
core[] = Extrude {0, 0, H} { Surface{1}; Layers{nc}; };
block[] = Extrude {0, 0, H} { Surface{2}; Layers{nb}; };
eps = 1e-6;
For i In {2 : #block[] - 1}
  bb[] = BoundingBox Surface{ block[i] };
  If (bb[0] > 2 - eps)
    x2[] += block[i];
  ElseIf (bb[3] < -2 + eps)
    xm[] += block[i];
  ElseIf (bb[1] > 2 - eps)
    y2[] += block[i];
  ElseIf (bb[4] < -2 + eps)
    ym[] += block[i];
  Else
    cavity[] += block[i];
  EndIf
EndFor
Physical Volume("core") = {core[1]};
Physical Volume("block") = {block[1]};
Physical Surface("core_side") = {core[{2 : #core[] - 1}]};
Physical Surface("cavity") = {cavity[]};
Physical Surface("block_x2") = {x2[]};
Physical Surface("block_xm") = {xm[]};
Physical Surface("block_y2") = {y2[]};
Physical Surface("block_ym") = {ym[]};
Physical Surface("ends") = {1, 2, core[0], block[0]};
