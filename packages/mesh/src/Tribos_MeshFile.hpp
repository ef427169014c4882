// Tribos_MeshFile.hpp: a mesh file read by the reader its extension names.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Gmsh (.msh, .geo: readGmsh) or Exodus II (.exo, .e, .ex2, .g: readExodus),
// the extension compared without case; another extension is refused naming
// the file and the valid ones.
Mesh readMeshFile(const std::string& path, std::vector<std::string>* warnings = nullptr);

}  // namespace Mesh
}  // namespace Tribos
