// A .geo whose mesh is far too fine (4000^3 hexahedra): stopped at the
// run's memory limit (--max-memory) within a second.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 4000;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("block") = {1};
