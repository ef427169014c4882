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

// Whether the cell type is a tetrahedron (Tet4, Tet10); the corners of a
// cell (4 or 8) and of its faces (3 or 4), which come first in its node and
// face lists.
bool isTetrahedron(CellType type);
int cellCorners(CellType type);
int faceCorners(CellType type);

// The mid-edge nodes of Tet10 and Hex20 (Gmsh's order): edgeNodes(type)[k]
// = {mid-edge node, corner, corner}; empty for Tet4 and Hex8.
const std::vector<std::array<int, 3>>& edgeNodes(CellType type);

// Whether a cell has positive volume everywhere: the tetrahedron's volume,
// the hexahedron's Jacobian at each of its corners (the trilinear map is
// one-to-one when all eight are positive), relative to the cell's size so
// that round-off flat cells count as degenerate. Tet10 and Hex20: det J of
// the isoparametric map at each node and each point of cellQuadrature
// (Tribos_ShapeFunctions.hpp), relative to the cell's size; `where`, when
// given, receives the smallest det J and where it is for a cell refused.
bool positiveCell(const Mesh& mesh, int c, std::string* where = nullptr);

// Refuses a mesh with inverted or degenerate cells, naming the first five by
// their ids in the file (cellIds[c]); for second-order cells the first one's
// body (bodyWord and its name, e.g. "physical volume 'block'", when the
// mesh names its bodies) and its smallest det J.
void requirePositiveCells(const Mesh& mesh, const std::string& file, const std::vector<long long>& cellIds,
                          const std::string& bodyWord = "physical volume");

// A mid-edge node's distance from the midpoint of its edge's corners,
// relative to that edge's length, beyond which a read warns
// (kMidEdgeWarn) or refuses (kMidEdgeRefuse): a curved edge has the mid-edge
// node off its chord; moved along the edge by more than a quarter of its
// length the map folds at a corner (det J < 0 there, refused as folded).
constexpr double kMidEdgeWarn = 0.25;
constexpr double kMidEdgeRefuse = 0.5;

// Warns (one line, the worst element by its id in the file and its ratio)
// when a mid-edge node of a second-order mesh lies farther than
// kMidEdgeWarn of its edge from the edge's midpoint, and refuses, naming
// the element, its body and the node, beyond kMidEdgeRefuse. Nothing for
// first-order meshes.
void checkMidEdgeNodes(const Mesh& mesh, const std::string& file, const std::vector<long long>& cellIds,
                       std::vector<std::string>* warnings, const std::string& bodyWord = "physical volume");

// Every cell face, keyed by its sorted corner ids: the cell of a file's
// boundary facet and whether the face lies on the boundary (one cell).
class FaceIndex {
 public:
  struct Entry {
    std::array<int, 4> key;
    int cell, local;
  };
  explicit FaceIndex(const Mesh& mesh);
  // The entry of the one cell whose face has these corners (any order; 3
  // or 4 of them, a second-order facet's first ones), or null: no cell has
  // it, or two do (an interior face).
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
