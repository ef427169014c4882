// A .geo with a syntax error in line 5: Gmsh's own message is quoted.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("block") = {1};
Bx(2) = {0, 0, 0, 1, 1, 1};
