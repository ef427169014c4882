#include "Tribos_MeshFile.hpp"

#include <algorithm>
#include <filesystem>

#include "Tribos_Error.hpp"
#include "Tribos_ExodusReader.hpp"
#include "Tribos_GmshReader.hpp"

namespace Tribos {
namespace Mesh {

Mesh readMeshFile(const std::string& path, std::vector<std::string>* warnings) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (extension == ".msh" || extension == ".geo") return readGmsh(path, warnings);
  if (extension == ".exo" || extension == ".e" || extension == ".ex2" || extension == ".g") return readExodus(path, warnings);
  throw Error("mesh file \"" + path + "\": unknown extension " + (extension.empty() ? "(none)" : "\"" + extension + "\"") +
              "; Tribos reads Gmsh (.msh, .geo) and Exodus II (.exo, .e, .ex2, .g) files");
}

}  // namespace Mesh
}  // namespace Tribos
