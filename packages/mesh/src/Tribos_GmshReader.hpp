// Tribos_GmshReader.hpp: one body read from a Gmsh file (.msh version 4,
// ASCII or binary, or a .geo script meshed on the fly) through the Gmsh API.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Reads the 3D elements of all physical volumes of `path` (of all volumes
// when the file has none) as one body of Tet4 or Hex8 cells, in Tribos' node
// order; every physical surface becomes a named face (its physical name, or
// its tag in decimal when it has none) whose facets are cell faces on the
// boundary, counter-clockwise seen from outside. A .geo file is meshed in 3D
// first. Nodes no cell uses are dropped; each such fact is a line added to
// `warnings` (printed on std::cerr when warnings is null).
//
// Refused with a Tribos::Error naming the file: a missing or unreadable file,
// a file Gmsh cannot read, no 3D elements, elements other than Tet4 and Hex8
// or both kinds at once (a Mesh has one cell type), inverted or degenerate
// cells, surface elements that are not faces of boundary cells. A file that
// does not start with $MeshFormat is refused before Gmsh sees it unless its
// name ends in .geo (Gmsh's script parser does not recover from a syntax
// error: after a broken .geo, later .geo reads in the process fail too).
Mesh readGmsh(const std::string& path, std::vector<std::string>* warnings = nullptr);

// The bounding box of a mesh as a BoxSpec of one cell per axis: what a
// Discretization of a mesh that is not a box takes (one structured
// subdomain when asked for, e.g. by the FCLIB export).
BoxSpec boundingBox(const Mesh& mesh);

}  // namespace Mesh
}  // namespace Tribos
