// A .geo that reads another file (Include): refused unless the input sets
// Mesh/Run Geo Script = true.
Include "/etc/passwd";
