// Tribos_GmshReader.hpp: bodies read from a Gmsh file (.msh version 4,
// ASCII or binary, or a .geo script meshed on the fly) through the Gmsh API.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

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
// on the boundary, counter-clockwise seen from outside. A .geo file is meshed
// in 3D first. Nodes no cell uses are dropped; each such fact is a line added
// to `warnings` (printed on std::cerr when warnings is null).
//
// Refused with a Tribos::Error naming the file: a missing or unreadable file,
// a file Gmsh cannot read, no 3D elements, a physical volume without
// elements, a volume in two physical volumes (its elements would be cells of
// two bodies), two physical volumes of one name, elements other than Tet4
// and Hex8 (named with their physical volume, e.g. "element type 11 (Tet10)
// in physical volume 'shaft' is not supported") or both kinds at once (a
// Mesh has one cell type), inverted or degenerate cells, surface elements
// that are not faces of boundary cells (an interface between two bonded
// bodies is inside the mesh). A file that does not start with $MeshFormat is
// refused before Gmsh sees it unless its name ends in .geo (Gmsh's script
// parser does not recover from a syntax error: after a broken .geo, later
// .geo reads in the process fail too).
Mesh readGmsh(const std::string& path, std::vector<std::string>* warnings = nullptr);

// The bounding box of a mesh as a BoxSpec of one cell per axis: what a
// Discretization of a mesh that is not a box takes (one structured
// subdomain when asked for, e.g. by the FCLIB export).
BoxSpec boundingBox(const Mesh& mesh);

}  // namespace Mesh
}  // namespace Tribos
