// Tribos_MeshFile.hpp: a mesh file read by the reader its extension names,
// and what every read of a mesh file may do (MeshFileOptions).
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// What a read of a mesh file may do. A .msh or Exodus II file is data; a
// .geo is a Gmsh program (it can run shell commands with System and read
// other files with Include), meshed only when runGeoScript is set, by the
// gmsh executable in a child process of bounded time and memory
// (Tribos_GeoScript.hpp). The defaults refuse a .geo and bound nothing
// else; the driver takes them from the input (Mesh/Run Geo Script, Mesh/Geo
// Time Limit) and from its memory limit (--max-memory, or the machine's
// available memory).
struct MeshFileOptions {
  bool runGeoScript = false;  // mesh a .geo (a program) at all
  double geoTimeLimit = 600;  // seconds of wall clock (and of CPU) Gmsh may take for a .geo
  // Bytes the read may use, 0 for no bound: the address space of the Gmsh
  // process meshing a .geo, the largest Gmsh file read (Gmsh holds a whole
  // .msh in memory), the arrays an Exodus II header asks for.
  double memoryLimit = 0;
};

// Gmsh (.msh, .geo: readGmsh) or Exodus II (.exo, .e, .ex2, .g: readExodus),
// the extension compared without case; another extension is refused naming
// the file and the valid ones. A path that is not a regular file (a FIFO, a
// device, a directory) is refused before it is opened.
Mesh readMeshFile(const std::string& path, std::vector<std::string>* warnings = nullptr,
                  const MeshFileOptions& options = MeshFileOptions());

// Refuses a .geo (extension compared without case) unless
// options.runGeoScript is set, naming the file and Mesh/Run Geo Script: what
// a caller checks before any work; readGmsh checks it again.
void requireGeoScriptAllowed(const std::string& path, const MeshFileOptions& options);

// Whether the path names a .geo script (extension compared without case).
bool isGeoScript(const std::string& path);

}  // namespace Mesh
}  // namespace Tribos
