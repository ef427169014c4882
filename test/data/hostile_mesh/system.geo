// A .geo that runs a shell command when Gmsh reads it (System): refused
// unless the input sets Mesh/Run Geo Script = true. Were it run, the file
// geo_system_ran would appear in the run's working directory.
System "touch geo_system_ran";
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("block") = {1};
