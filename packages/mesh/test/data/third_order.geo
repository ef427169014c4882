// A unit cube of cubic tetrahedra (Tet20): refused by the reader.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("shaft") = {1};
Mesh.MeshSizeMax = 0.5;
Mesh.ElementOrder = 3;
