// Tribos_GmshReader.hpp: bodies read from a Gmsh file (.msh version 4,
// ASCII or binary, through the Gmsh API; or a .geo script, a program, meshed
// by Gmsh in a child process when the caller allows it).
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_MeshFile.hpp"

namespace Tribos {
namespace Mesh {

// Reads the 3D elements of the physical volumes of `path` as Tet4 or Hex8
// cells in Tribos' node order. Every physical volume is a body, named by its
// physical name (or its tag in decimal when it has none), the bodies ordered
// by physical tag (Mesh::cellBody, Mesh::bodyNames); a file without physical
// volumes is one body of all its volumes (bodyNames left empty, as a box
// mesh). Nodes the file shares between two bodies (a conformal interface,
// e.g. after BooleanFragments) stay shared, which bonds the bodies there;
// bodies meant to touch in contact must have distinct nodes (separate
// volumes not fragmented together). Every physical surface becomes a named
// face (its physical name, or its tag in decimal) whose facets are cell faces
// on the boundary, counter-clockwise seen from outside. Nodes no cell uses
// are dropped; each such fact is a line added to `warnings` (printed on
// std::cerr when warnings is null).
//
// A .geo script is a program (System runs shell commands, Include reads
// other files): it is refused unless options.runGeoScript is set, and then
// meshed in 3D by the gmsh executable in a child process with the time and
// memory limits of `options` (GeoScriptMesh, Tribos_GeoScript.hpp); its
// mesh is read as a .msh file, messages naming the script.
//
// Refused with a Tribos::Error naming the file: a missing or unreadable
// file, one that is not a regular file or is larger than
// options.memoryLimit (Gmsh holds a .msh whole), a file Gmsh cannot read, a
// .geo not allowed or that Gmsh cannot mesh within its limits, no 3D
// elements, a node tag defined twice at other coordinates, a coordinate
// that is not finite or beyond kMaxCoordinate or a mesh spanning less than
// kMinExtent, a physical volume without elements, a volume in two physical
// volumes (its elements would be cells of two bodies), two physical volumes
// of one name, elements other than Tet4 and Hex8 (named with their physical
// volume, e.g. "element type 11 (Tet10)
// in physical volume 'shaft' is not supported") or both kinds at once (a
// Mesh has one cell type), inverted or degenerate cells, surface elements
// that are not faces of boundary cells (an interface between two bonded
// bodies is inside the mesh). A file whose name does not end in .geo and
// that does not start with $MeshFormat is refused before Gmsh sees it
// (Gmsh would run it as a script).
Mesh readGmsh(const std::string& path, std::vector<std::string>* warnings = nullptr,
              const MeshFileOptions& options = MeshFileOptions());

// The bounding box of a mesh as a BoxSpec of one cell per axis: what a
// Discretization of a mesh that is not a box takes (one structured
// subdomain when asked for, e.g. by the FCLIB export).
BoxSpec boundingBox(const Mesh& mesh);

}  // namespace Mesh
}  // namespace Tribos
