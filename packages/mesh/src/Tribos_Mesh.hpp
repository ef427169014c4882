// Tribos_Mesh.hpp: meshes of tetrahedra or hexahedra (first or second order) with named boundary
// faces, named node sets and one or several bodies; structured box meshes.
// A run holds the whole mesh on one rank only, while it is read and
// decomposed; every rank then keeps its part (Tribos_Discretization.hpp),
// itself a Mesh in a numbering of its own.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace Tribos {
namespace Mesh {

// The cells of a mesh: Tet4 and Hex8, or Tet10 and Hex20 (second order,
// Gmsh's node ordering: corners, then one node per edge;
// docs/quadratic_elements.md), read from Gmsh and Exodus files or made by
// generateBox. A body holds cells of one type; bodies may differ (a Tet4
// body in contact with a Tet10 one), but bodies that share nodes have one
// type (Mesh::checkBodies).
enum class CellType { Tet4, Hex8, Tet10, Hex20 };

constexpr int nodesPerCell(CellType type) {
  switch (type) {
    case CellType::Tet4: return 4;
    case CellType::Hex8: return 8;
    case CellType::Tet10: return 10;
    case CellType::Hex20: return 20;
  }
  return 0;  // not a CellType
}
std::string cellTypeName(CellType type);             // "Tet4", "Hex8", "Tet10", "Hex20"
CellType cellTypeFromName(const std::string& name);  // the inverse; throws naming the valid names
// Whether the cell has mid-edge nodes (Tet10, Hex20).
bool isSecondOrder(CellType type);

// A boundary facet: a triangle (Tet4) or quadrilateral (Hex8) of one cell; a
// 6-node triangle (Tet10) or 8-node quadrilateral (Hex20) lists its corners
// first, then its mid-edge nodes (docs/quadratic_elements.md).
struct Facet {
  std::vector<int> nodes;  // global node ids, counter-clockwise seen from outside
  int cell = -1;
};

struct BoxSpec {
  std::array<double, 2> x{0, 1}, y{0, 1}, z{0, 1};
  std::array<int, 3> cells{1, 1, 1};
  CellType type = CellType::Hex8;
};

// Bodies: every cell belongs to one body (cellBody), named by bodyNames. A
// mesh that never sets them (box meshes, older code) is one body named
// "body". Two bodies that share nodes are bonded there (a conformal
// interface); bodies meet in contact only through distinct nodes.
class Mesh {
 public:
  // The type of every cell of a mesh of one type. A mixed mesh (bodies of
  // different types, mixed()) has no single type: read cellType(c).
  CellType type = CellType::Hex8;
  std::vector<std::array<double, 3>> coords;    // per node
  std::vector<int> connectivity;                // the node ids of each cell, cell after cell
  std::map<std::string, std::vector<Facet>> faces;  // named boundary faces
  std::vector<int> cellBody;                    // body of each cell; empty: every cell is body 0
  std::vector<std::string> bodyNames;           // per body; empty: one body named "body"
  std::map<std::string, std::vector<int>> nodeSets;  // named sets of node ids, no facets
  // A part of a mesh only: every node of the part on each named face,
  // sorted. The part holds the facets of its own cells, and a node of the
  // part may lie on the face through another part's facets only; a whole
  // mesh leaves this empty.
  std::map<std::string, std::vector<int>> partFaceNodes;

  // The nodes per cell of a mesh of one type; throws on a mixed mesh, whose
  // cells say it one by one (cellSize).
  int nodesPerCell() const;
  int numNodes() const { return static_cast<int>(coords.size()); }
  int numCells() const {
    return mixed() ? static_cast<int>(cellTypes_.size())
                   : static_cast<int>(connectivity.size()) / nodesPerCellOf(type);
  }
  const int* cell(int c) const {
    return &connectivity[mixed() ? cellStart_[c] : static_cast<size_t>(c) * nodesPerCellOf(type)];
  }

  // Cells of several types: the type and the number of nodes of each cell.
  bool mixed() const { return !cellTypes_.empty(); }
  CellType cellType(int c) const { return mixed() ? cellTypes_[c] : type; }
  int cellSize(int c) const { return nodesPerCellOf(cellType(c)); }
  // The types the cells have, in CellType's order; whether any is second order.
  std::vector<CellType> cellTypesPresent() const;
  bool hasSecondOrderCells() const;
  // Appends a cell of the given type; a type other than the cells' so far
  // makes the mesh mixed (an empty mesh takes the first cell's type).
  void addCell(CellType cellType, const int* nodes);
  // The type of every cell at once, for a connectivity already filled cell
  // after cell: a mesh of one type when all are equal. Throws when the
  // types' node counts do not add up to the connectivity.
  void setCellTypes(const std::vector<CellType>& types);

  // Sorted unique node ids of a named face, or of a node set when no face
  // has the name; throws naming it and the valid names when neither exists.
  std::vector<int> faceNodes(const std::string& name) const;
  // The facets of a named face; throws naming the face and the valid faces
  // when it does not exist (saying so when the name is a node set's).
  const std::vector<Facet>& face(const std::string& name) const;
  std::vector<std::string> faceNames() const;
  std::vector<std::string> nodeSetNames() const;

  int numBodies() const { return bodyNames.empty() ? 1 : static_cast<int>(bodyNames.size()); }
  int bodyOf(int cell) const { return cellBody.empty() ? 0 : cellBody[cell]; }
  const std::string& bodyName(int body) const;
  // The index of a named body; throws naming it and the valid bodies.
  int bodyIndex(const std::string& name) const;
  // The body whose cells own the facets of a named face; throws naming the
  // face when it has no facets or its facets lie on several bodies.
  int faceBody(const std::string& face) const;
  // Throws when cellBody and bodyNames disagree (sizes, out-of-range body,
  // duplicate names, a body without cells), when a body mixes cell types,
  // and when bodies of different cell types share a node: a first-order
  // face bonded to a second-order one leaves its mid-edge nodes hanging
  // (contact joins such bodies, through distinct nodes). Messages start with
  // `what` (a reader's "mesh file \"...\"") and name nodes by nodeIds[n]
  // when given (the file's numbers), by their index otherwise.
  void checkBodies(const std::string& what = "mesh", const std::vector<long long>& nodeIds = {}) const;

 private:
  static int nodesPerCellOf(CellType t) { return ::Tribos::Mesh::nodesPerCell(t); }
  void requireOneTypePerBody(const std::string& what, const std::vector<long long>& nodeIds) const;
  std::vector<CellType> cellTypes_;   // per cell of a mixed mesh; empty otherwise
  std::vector<size_t> cellStart_;     // per cell of a mixed mesh: its first entry in connectivity
};

// Box [x0,x1]x[y0,y1]x[z0,z1] with nx,ny,nz hexahedral cells; for Tet4 each
// hexahedron is split into 6 tetrahedra around its main diagonal (Kuhn split),
// which is conforming because every hexahedron is split the same way. Tet10
// and Hex20 boxes are the same cells with their mid-edge nodes at the middle
// of each edge (the lattice of half cells).
// Faces: xmin, xmax, ymin, ymax, zmin, zmax.
Mesh generateBox(const BoxSpec& spec);
// The numbers of nodes and cells of that box (doubles: they are checked
// against int before a mesh is made).
double boxNodeCount(const BoxSpec& spec);
double boxCellCount(const BoxSpec& spec);

// Number of hexahedra along each axis for level L of the semismooth* prism:
// nx = ceil(2^((L+4)/2)), ny = nz = ceil(2^((L+2)/2)).
std::array<int, 3> prismLevelCells(int L);

// More cells along one axis of a box than any run could hold: counts are
// checked against it before they are multiplied.
constexpr int kMaxCellsPerAxis = 1 << 20;

// The coordinates a mesh may have, checked by every reader and for the box
// before any geometric check. The geometry forms products of up to four
// lengths (the squared norm of an area vector; volumes are three): with
// |x| <= 1e50 and an extent of at least 1e-50 they stay within the doubles'
// range (about 1e-308 to 1e308, with room for differences and sums), so a
// mesh in unsuitable units is refused by name instead of failing later as
// "degenerate" or "not planar".
constexpr double kMaxCoordinate = 1e50;
constexpr double kMinExtent = 1e-50;

// Refuses a box of second-order cells, and a box (its ranges) whose
// coordinates are not usable as above,
// naming `what` (e.g. the parameters that give the ranges) and the corner
// node by its number in generateBox's numbering, and a box whose cells or
// whole shape double precision cannot solve (Tribos_BodyShape.hpp).
// generateBox checks it too.
void requireUsableBox(const BoxSpec& spec, const std::string& what);

}  // namespace Mesh
}  // namespace Tribos
