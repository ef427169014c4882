// Two halves of a unit cube glued along z = 0.5; the physical surface
// "middle" is their interface, inside the body: refused as a named face.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Rectangle(10) = {0, 0, 0.5, 1, 1};
parts() = BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; };
Physical Volume("body") = Volume{:};
eps = 1e-6;
Physical Surface("middle") = Surface In BoundingBox {-eps, -eps, 0.5 - eps, 1 + eps, 1 + eps, 0.5 + eps};
Mesh.MeshSizeMax = 0.5;
