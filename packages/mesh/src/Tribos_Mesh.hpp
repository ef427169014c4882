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
// generateBox. A mesh holds cells of one type.
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
  CellType type = CellType::Hex8;
  std::vector<std::array<double, 3>> coords;    // per node
  std::vector<int> connectivity;                // nodesPerCell() ids per cell
  std::map<std::string, std::vector<Facet>> faces;  // named boundary faces
  std::vector<int> cellBody;                    // body of each cell; empty: every cell is body 0
  std::vector<std::string> bodyNames;           // per body; empty: one body named "body"
  std::map<std::string, std::vector<int>> nodeSets;  // named sets of node ids, no facets
  // A part of a mesh only: every node of the part on each named face,
  // sorted. The part holds the facets of its own cells, and a node of the
  // part may lie on the face through another part's facets only; a whole
  // mesh leaves this empty.
  std::map<std::string, std::vector<int>> partFaceNodes;

  int nodesPerCell() const { return Mesh::nodesPerCellOf(type); }
  int numNodes() const { return static_cast<int>(coords.size()); }
  int numCells() const { return static_cast<int>(connectivity.size()) / nodesPerCell(); }
  const int* cell(int c) const { return &connectivity[static_cast<size_t>(c) * nodesPerCell()]; }

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
  // duplicate names, a body without cells).
  void checkBodies() const;

 private:
  static int nodesPerCellOf(CellType t) { return ::Tribos::Mesh::nodesPerCell(t); }
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
