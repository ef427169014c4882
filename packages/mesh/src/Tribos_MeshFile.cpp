#include "Tribos_MeshFile.hpp"

#include "Tribos_BodyShape.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_ExodusReader.hpp"
#include "Tribos_GmshReader.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

bool isGeoScript(const std::string& path) { return detail::lowerExtension(path) == ".geo"; }

void requireGeoScriptAllowed(const std::string& path, const MeshFileOptions& options) {
  TRIBOS_REQUIRE(!isGeoScript(path) || options.runGeoScript,
                 "mesh file \"" << path << "\" is a Gmsh script (.geo): a program, which can run shell commands "
                                   "(System) and read other files (Include), so it is meshed only when the input "
                                   "opts in: set Mesh/Run Geo Script = true for a script you trust, or give the mesh "
                                   "Gmsh makes of it (gmsh -3 -format msh4 SCRIPT.geo -o MESH.msh) as Mesh/File");
}

Mesh readMeshFile(const std::string& path, std::vector<std::string>* warnings, const MeshFileOptions& options) {
  // First, whatever the name: a FIFO or a device would block or never end.
  detail::requireRegularFile(path, "mesh file \"" + path + "\"");
  const std::string extension = detail::lowerExtension(path);
  const bool gmsh = extension == ".msh" || extension == ".geo";
  const bool exodus = extension == ".exo" || extension == ".e" || extension == ".ex2" || extension == ".g";
  if (!gmsh && !exodus)
    throw Error("mesh file \"" + path + "\": unknown extension " + (extension.empty() ? "(none)" : "\"" + extension + "\"") +
                "; Tribos reads Gmsh (.msh, .geo) and Exodus II (.exo, .e, .ex2, .g) files");
  Mesh mesh = gmsh ? readGmsh(path, warnings, options) : readExodus(path, warnings, options);
  requireSolvableBodies(mesh, "mesh file \"" + path + "\"");
  return mesh;
}

}  // namespace Mesh
}  // namespace Tribos
