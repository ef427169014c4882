// detail/Tribos_MeshFacets.hpp: what the mesh readers (Gmsh, Exodus II) and
// box meshes share: the outward faces of the reference cells, the index of
// cell faces that turns a file's boundary facet into the face of its cell
// (counter-clockwise seen from outside, whatever the file's order), the
// positive-volume check, the dropping of unused nodes. Internal to the mesh
// package (not installed).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {
namespace detail {

using Point = std::array<double, 3>;

// Six times the signed volume of the tetrahedron (o, a, b, c).
double triple(const Point& o, const Point& a, const Point& b, const Point& c);

// The box of generateBox, unchecked.
Mesh boxMesh(const BoxSpec& spec);

// Local faces of the reference cells, counter-clockwise seen from outside;
// for Tet10 and Hex20 the corners, then the mid-edge nodes around the face.
const std::vector<std::vector<int>>& cellFaces(CellType type);

// The face `local` of cell `cell` as a facet, in cellFaces' (outward) order.
Facet outwardFacet(const Mesh& mesh, int cell, int local);

// Whether a cell has positive volume everywhere: the tetrahedron's volume,
// the hexahedron's Jacobian at each of its corners (the trilinear map is
// one-to-one when all eight are positive), relative to the cell's size so
// that round-off flat cells count as degenerate. Refuses Tet10 and Hex20.
bool positiveCell(const Mesh& mesh, int c);

// Refuses a mesh with inverted or degenerate cells, naming the first five by
// their ids in the file (cellIds[c]).
void requirePositiveCells(const Mesh& mesh, const std::string& file, const std::vector<long long>& cellIds);

// Every cell face, keyed by its sorted node ids: the cell of a file's
// boundary facet and whether the face lies on the boundary (one cell).
class FaceIndex {
 public:
  struct Entry {
    std::array<int, 4> key;
    int cell, local;
  };
  explicit FaceIndex(const Mesh& mesh);
  // The entry of the one cell whose face has these nodes (any order), or
  // null: no cell has it, or two do (an interior face).
  const Entry* boundaryFace(const std::vector<int>& nodes) const;

 private:
  static std::array<int, 4> keyOf(std::vector<int> nodes);
  std::vector<Entry> entries_;
};

// The extension of a path in lower case (".msh", "" when none).
std::string lowerExtension(const std::string& path);

// Refuses, naming the file, before it is opened: a path that does not
// exist, is not a regular file (a directory; a FIFO or a device, which
// would block or never end), is larger than maxBytes (when > 0; `why` says
// what the bound is, e.g. "the memory limit of the run: Gmsh holds the whole
// file in memory"), or cannot be opened for reading.
void requireRegularFile(const std::string& path, const std::string& file, double maxBytes = 0,
                        const std::string& why = "");

// "300 MB", "2.50 GB", "12 kB", "500 bytes" (units of 2^10, 2^20 and 2^30
// bytes, as --max-memory reads them).
std::string describeBytes(double bytes);

// Refuses coordinates the geometry cannot compute with, before any
// geometric check: a coordinate that is not finite or beyond
// kMaxCoordinate, a mesh whose extent (the largest side of its bounding
// box) is below kMinExtent. Nodes are named by nodeIds[i] (their numbers in
// the file), or by their index when nodeIds is empty.
void requireUsableCoordinates(const std::vector<Point>& coords, const std::vector<long long>& nodeIds,
                              const std::string& file);

// A reader's warning: added to `warnings`, or printed on std::cerr when null.
void warn(std::vector<std::string>* warnings, const std::string& message);

// Numbers the file's nodes that cells use (usedByCells[i] for the file's
// i-th node), in file order, and -1 for the others, which are dropped with
// a warning naming the first by its id in the file (nodeIds[i]).
std::vector<int> numberUsedNodes(const std::vector<char>& usedByCells, const std::vector<long long>& nodeIds,
                                 const std::string& file, std::vector<std::string>* warnings);

}  // namespace detail
}  // namespace Mesh
}  // namespace Tribos
