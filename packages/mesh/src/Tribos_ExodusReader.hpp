// Tribos_ExodusReader.hpp: bodies read from an Exodus II file (the Sandia
// SEACAS format of Cubit, Trelis and Abaqus/Salome exports) through the
// Exodus II C library.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_MeshFile.hpp"

namespace Tribos {
namespace Mesh {

// Reads the element blocks of a 3D Exodus II file as Tet4 or Hex8 cells:
// every non-empty block is a body (Mesh::cellBody, Mesh::bodyNames), in the
// file's block order, named by its block name or "block_<id>". The Exodus
// TETRA (4 nodes) and HEX (8 nodes) node orders are Tribos' (positive
// volume; the hexahedron's bottom 1-4 counter-clockwise seen from above,
// then the top 5-8), checked cell by cell. Nodes two blocks share stay
// shared, which bonds the bodies there. Every side set becomes a named face
// (its name or "sideset_<id>") whose facets are the cell faces it lists,
// counter-clockwise seen from outside; every node set becomes a node set
// (its name or "nodeset_<id>"). Nodes no element uses are dropped and empty
// blocks ignored; each such fact is a line added to `warnings` (printed on
// std::cerr when warnings is null). Messages name cells and nodes by the
// file's ids (its element and node number maps).
//
// Refused with a Tribos::Error naming the file: a missing or unreadable
// file, one that is not a regular file, a file the Exodus II library cannot
// read, a mesh that is not 3D or has no elements, a header whose node and
// element counts need more memory than options.memoryLimit (checked before
// the arrays are allocated; the file's size is not bounded, an Exodus file
// may hold results beside its mesh), a coordinate that is not finite or
// beyond kMaxCoordinate or a mesh spanning less than kMinExtent, elements other than Tet4 and Hex8 (named with their
// block) or both kinds at once, two blocks, side sets or node sets of one
// name, inverted or degenerate cells, side set sides that are not on the
// boundary, node set nodes no element uses.
Mesh readExodus(const std::string& path, std::vector<std::string>* warnings = nullptr,
                const MeshFileOptions& options = MeshFileOptions());

}  // namespace Mesh
}  // namespace Tribos
