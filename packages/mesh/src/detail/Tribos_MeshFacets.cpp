#include "Tribos_MeshFacets.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <sys/stat.h>

#include "Tribos_Error.hpp"
#include "Tribos_FileKind.hpp"
#include "Tribos_ShapeFunctions.hpp"

namespace Tribos {
namespace Mesh {
namespace detail {

double triple(const Point& o, const Point& a, const Point& b, const Point& c) {
  const double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
  const double v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
  const double w[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

const std::vector<std::vector<int>>& cellFaces(CellType type) {
  static const std::vector<std::vector<int>> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}};
  // The same faces with their mid-edge nodes after the corners, edge by edge
  // around the face (Gmsh's 6-node triangle and 8-node quadrilateral). Tet10
  // edges: 4 = 0-1, 5 = 1-2, 6 = 2-0, 7 = 3-0, 8 = 3-2, 9 = 3-1; Hex20 edges:
  // 8 = 0-1, 9 = 0-3, 10 = 0-4, 11 = 1-2, 12 = 1-5, 13 = 2-3, 14 = 2-6,
  // 15 = 3-7, 16 = 4-5, 17 = 4-7, 18 = 5-6, 19 = 6-7.
  static const std::vector<std::vector<int>> tet10 = {
      {0, 2, 1, 6, 5, 4}, {0, 1, 3, 4, 9, 7}, {1, 2, 3, 5, 8, 9}, {0, 3, 2, 7, 8, 6}};
  static const std::vector<std::vector<int>> hex20 = {
      {0, 3, 2, 1, 9, 13, 11, 8},   {4, 5, 6, 7, 16, 18, 19, 17}, {0, 1, 5, 4, 8, 12, 16, 10},
      {1, 2, 6, 5, 11, 14, 18, 12}, {2, 3, 7, 6, 13, 15, 19, 14}, {0, 4, 7, 3, 10, 17, 15, 9}};
  switch (type) {
    case CellType::Tet4: return tet;
    case CellType::Hex8: return hex;
    case CellType::Tet10: return tet10;
    case CellType::Hex20: return hex20;
  }
  throw Error("cellFaces: cell type " + std::to_string(static_cast<int>(type)) + " unknown");
}

Facet outwardFacet(const Mesh& mesh, int cell, int local) {
  Facet f;
  f.cell = cell;
  for (int ln : cellFaces(mesh.cellType(cell))[local]) f.nodes.push_back(mesh.cell(cell)[ln]);
  return f;
}

bool isTetrahedron(CellType type) { return type == CellType::Tet4 || type == CellType::Tet10; }
int cellCorners(CellType type) { return isTetrahedron(type) ? 4 : 8; }
int faceCorners(CellType type) { return isTetrahedron(type) ? 3 : 4; }

const std::vector<std::array<int, 3>>& edgeNodes(CellType type) {
  static const std::vector<std::array<int, 3>> none;
  static const std::vector<std::array<int, 3>> tet10 = {{4, 0, 1}, {5, 1, 2}, {6, 2, 0},
                                                        {7, 3, 0}, {8, 3, 2}, {9, 3, 1}};
  static const std::vector<std::array<int, 3>> hex20 = {{8, 0, 1},  {9, 0, 3},  {10, 0, 4}, {11, 1, 2},
                                                        {12, 1, 5}, {13, 2, 3}, {14, 2, 6}, {15, 3, 7},
                                                        {16, 4, 5}, {17, 4, 7}, {18, 5, 6}, {19, 6, 7}};
  return type == CellType::Tet10 ? tet10 : type == CellType::Hex20 ? hex20 : none;
}

namespace {

std::string pointText(const Point& p) {
  std::ostringstream os;
  os << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return os.str();
}

// The body of cell c as messages name it: " of physical volume 'name'", or
// "" when the mesh names no bodies.
std::string bodyOfCell(const Mesh& mesh, int c, const std::string& bodyWord) {
  if (mesh.bodyNames.empty()) return "";
  return " of " + bodyWord + " '" + mesh.bodyName(mesh.bodyOf(c)) + "'";
}

// The smallest det J of a second-order cell over its nodes and the points of
// its rule, as a volume relative to h^3 (det J times the reference cell's
// volume: 1/6 for the tetrahedron, 8 for [-1,1]^3), and where it is.
double smallestJacobian(const Mesh& mesh, int c, double h, std::string& where) {
  const CellType type = mesh.cellType(c);
  const int npc = mesh.cellSize(c);
  const int* n = mesh.cell(c);
  const double reference = isTetrahedron(type) ? 1.0 / 6.0 : 8.0;
  std::vector<Point> points = Fem::referenceNodes(type);
  const size_t nodes = points.size();
  for (const auto& q : Fem::cellQuadrature(type)) points.push_back(q.xi);
  double smallest = HUGE_VAL;
  std::vector<Point> X(npc);
  for (int a = 0; a < npc; ++a) X[a] = mesh.coords[n[a]];
  double N[Fem::kMaxNodesPerCell], dN[Fem::kMaxNodesPerCell][3], J[3][3];
  for (size_t k = 0; k < points.size(); ++k) {
    Fem::referenceShape(type, points[k], N, dN);
    Fem::isoparametricJacobian(dN, X.data(), npc, J);
    const double det = Fem::determinant3(J);
    const double relative = det * reference / (h * h * h);
    if (relative < smallest) {
      smallest = relative;
      std::ostringstream os;
      os << "det J = " << det << " at ";
      if (k < nodes) os << "its node " << k << " " << pointText(mesh.coords[n[k]]);
      else os << "the quadrature point " << pointText(points[k]) << " of its reference cell";
      where = os.str();
    }
  }
  return smallest;
}

}  // namespace

bool positiveCell(const Mesh& mesh, int c, std::string* where) {
  const int* n = mesh.cell(c);
  const auto& x = mesh.coords;
  double h = 0;
  for (int a = 0; a < mesh.cellSize(c); ++a)
    for (int d = 0; d < 3; ++d) h = std::max(h, std::abs(x[n[a]][d] - x[n[0]][d]));
  if (isSecondOrder(mesh.cellType(c))) {
    // Corner volumes do not bound the Jacobian of a cell with mid-edge nodes.
    if (!(h > 0)) {
      if (where) *where = "all its nodes at one point";
      return false;
    }
    std::string at;
    const bool positive = smallestJacobian(mesh, c, h, at) > 1e-12;
    if (!positive && where) *where = at;
    return positive;
  }
  const double floor = 1e-12 * h * h * h;
  if (mesh.cellType(c) == CellType::Tet4) return triple(x[n[0]], x[n[1]], x[n[2]], x[n[3]]) > floor;
  // Corner k and its three neighbours in right-handed order (Tribos' Hex8
  // order: the bottom quadrilateral 0-3 counter-clockwise seen from above, the top 4-7).
  static const int corner[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                   {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  for (int k = 0; k < 8; ++k)
    if (triple(x[n[k]], x[n[corner[k][0]]], x[n[corner[k][1]]], x[n[corner[k][2]]]) <= floor) return false;
  return true;
}

void requirePositiveCells(const Mesh& mesh, const std::string& file, const std::vector<long long>& cellIds,
                          const std::string& bodyWord) {
  std::vector<long long> bad;
  std::string first;  // the first refused cell, when second order: its body and det J
  int firstCell = -1;
  for (int c = 0; c < mesh.numCells(); ++c) {
    std::string where;
    if (positiveCell(mesh, c, &where)) continue;
    if (bad.empty() && isSecondOrder(mesh.cellType(c)))
      first = "element " + std::to_string(cellIds[c]) + " (" + cellTypeName(mesh.cellType(c)) + ")" +
              bodyOfCell(mesh, c, bodyWord) + ": " + where;
    if (bad.empty()) firstCell = c;
    bad.push_back(cellIds[c]);
  }
  if (bad.empty()) return;
  std::ostringstream os;
  for (size_t i = 0; i < std::min<size_t>(bad.size(), 5); ++i) os << (i ? ", " : "") << bad[i];
  if (isSecondOrder(mesh.cellType(firstCell)))
    throw Error(file + ": " + std::to_string(bad.size()) + " inverted or folded " + cellTypeName(mesh.cellType(firstCell)) +
                " element" + (bad.size() > 1 ? "s" : "") + " (det J <= 0 at a node or quadrature point): " + first +
                (bad.size() > 1 ? "; elements " + os.str() + (bad.size() > 5 ? ", ..." : "") : "") +
                " (a mid-edge node too far from the middle of its edge folds the cell)");
  throw Error(file + ": " + std::to_string(bad.size()) + " inverted or degenerate element" +
              (bad.size() > 1 ? "s" : "") + " (non-positive volume): element" + (bad.size() > 1 ? "s " : " ") + os.str() +
              (bad.size() > 5 ? ", ..." : ""));
}

void checkMidEdgeNodes(const Mesh& mesh, const std::string& file, const std::vector<long long>& cellIds,
                       std::vector<std::string>* warnings, const std::string& bodyWord) {
  if (!mesh.hasSecondOrderCells()) return;
  double worst = 0;
  int worstCell = -1, worstNode = -1;
  long long beyond = 0;
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int* n = mesh.cell(c);
    for (const auto& e : edgeNodes(mesh.cellType(c))) {
      const Point& m = mesh.coords[n[e[0]]];
      const Point& a = mesh.coords[n[e[1]]];
      const Point& b = mesh.coords[n[e[2]]];
      double off = 0, length = 0;
      for (int d = 0; d < 3; ++d) {
        off += std::pow(m[d] - 0.5 * (a[d] + b[d]), 2);
        length += std::pow(b[d] - a[d], 2);
      }
      const double ratio = length > 0 ? std::sqrt(off / length) : (off > 0 ? HUGE_VAL : 0);
      if (ratio > kMidEdgeRefuse) ++beyond;
      if (ratio > worst) worst = ratio, worstCell = c, worstNode = e[0];
    }
  }
  if (worst <= kMidEdgeWarn) return;
  std::ostringstream os;
  os << file << ": element " << cellIds[worstCell] << " (" << cellTypeName(mesh.cellType(worstCell)) << ")"
     << bodyOfCell(mesh, worstCell, bodyWord) << " has its mid-edge node " << worstNode << " at "
     << pointText(mesh.coords[mesh.cell(worstCell)[worstNode]]) << ", " << worst
     << " of its edge's length from the edge's midpoint";
  TRIBOS_REQUIRE(worst <= kMidEdgeRefuse, os.str() << " (" << beyond << " mid-edge node" << (beyond > 1 ? "s" : "")
                                                   << " beyond " << kMidEdgeRefuse
                                                   << "); a mid-edge node farther than " << kMidEdgeRefuse
                                                   << " of its edge from the midpoint is refused: the cell is "
                                                      "too distorted for its quadrature");
  os << " (the worst; beyond " << kMidEdgeWarn << " the element's accuracy degrades)";
  warn(warnings, os.str());
}

std::array<int, 4> FaceIndex::keyOf(std::vector<int> nodes) {
  std::sort(nodes.begin(), nodes.end());
  std::array<int, 4> key{-1, -1, -1, -1};
  std::copy(nodes.begin(), nodes.begin() + std::min<size_t>(nodes.size(), 4), key.begin());
  return key;
}

FaceIndex::FaceIndex(const Mesh& mesh) {
  entries_.reserve(static_cast<size_t>(mesh.numCells()) * 6);
  for (int c = 0; c < mesh.numCells(); ++c) {
    const auto& faces = cellFaces(mesh.cellType(c));
    const size_t corners = static_cast<size_t>(faceCorners(mesh.cellType(c)));
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
      std::vector<int> nodes;
      for (size_t a = 0; a < corners; ++a) nodes.push_back(mesh.cell(c)[faces[f][a]]);
      entries_.push_back({keyOf(nodes), c, f});
    }
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
}

const FaceIndex::Entry* FaceIndex::boundaryFace(const std::vector<int>& nodes) const {
  if (nodes.size() < 3 || nodes.size() > 4) return nullptr;
  const auto key = keyOf(nodes);
  auto lo = std::lower_bound(entries_.begin(), entries_.end(), key,
                             [](const Entry& e, const std::array<int, 4>& k) { return e.key < k; });
  if (lo == entries_.end() || lo->key != key) return nullptr;
  if (lo + 1 != entries_.end() && (lo + 1)->key == key) return nullptr;
  return &*lo;
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return extension;
}

void requireRegularFile(const std::string& path, const std::string& file, double maxBytes, const std::string& why) {
  // stat() follows symbolic links and opens nothing: a FIFO is not waited on.
  struct stat st {};
  TRIBOS_REQUIRE(::stat(path.c_str(), &st) == 0, "cannot open " << file << ": " << std::strerror(errno));
  TRIBOS_REQUIRE(!S_ISDIR(st.st_mode), file << " is a directory");
  TRIBOS_REQUIRE(S_ISREG(st.st_mode), file << " is " << fileKind(st.st_mode)
                                           << ", not a regular file; a mesh file must be a regular file");
  TRIBOS_REQUIRE(maxBytes <= 0 || double(st.st_size) <= maxBytes,
                 file << " is " << describeBytes(double(st.st_size)) << ", more than " << describeBytes(maxBytes)
                      << (why.empty() ? "" : " (" + why + ")"));
  std::ifstream probe(path, std::ios::binary);
  TRIBOS_REQUIRE(probe.good(), "cannot open " << file << ": " << std::strerror(errno));
}

std::string describeBytes(double bytes) {
  const double kB = 1024.0, MB = 1024.0 * kB, GB = 1024.0 * MB;
  std::ostringstream os;
  os << std::fixed << std::setprecision(bytes >= GB ? 2 : bytes >= MB && bytes < 10 * MB ? 1 : 0);
  if (bytes >= GB) os << bytes / GB << " GB";
  else if (bytes >= MB) os << bytes / MB << " MB";
  else if (bytes >= 10 * kB) os << bytes / kB << " kB";
  else os << bytes << " bytes";
  return os.str();
}

void requireUsableCoordinates(const std::vector<Point>& coords, const std::vector<long long>& nodeIds,
                              const std::string& file) {
  auto nodeName = [&](size_t i) { return nodeIds.empty() ? static_cast<long long>(i) : nodeIds[i]; };
  Point lo{0, 0, 0}, hi{0, 0, 0};
  for (size_t i = 0; i < coords.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      const double x = coords[i][d];
      TRIBOS_REQUIRE(std::isfinite(x), file << ": node " << nodeName(i) << " has coordinate " << "xyz"[d] << " = " << x
                                            << "; coordinates must be finite numbers");
      TRIBOS_REQUIRE(std::abs(x) <= kMaxCoordinate,
                     file << ": node " << nodeName(i) << " has coordinate " << "xyz"[d] << " = " << x
                          << ", beyond the " << kMaxCoordinate << " a coordinate may have (the geometry forms products "
                          << "of up to four lengths, which must stay representable); express the mesh in other units");
      lo[d] = i == 0 ? x : std::min(lo[d], x);
      hi[d] = i == 0 ? x : std::max(hi[d], x);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  TRIBOS_REQUIRE(coords.empty() || extent >= kMinExtent,
                 file << ": the mesh spans " << extent << " (the largest side of its bounding box), less than the "
                      << kMinExtent << " a mesh must span (the geometry forms products of up to four lengths, "
                      << "which must not vanish in round-off); express the mesh in other units");
}

void warn(std::vector<std::string>* warnings, const std::string& message) {
  if (warnings) warnings->push_back(message);
  else std::cerr << "warning: " << message << std::endl;
}

std::vector<int> numberUsedNodes(const std::vector<char>& usedByCells, const std::vector<long long>& nodeIds,
                                 const std::string& file, std::vector<std::string>* warnings) {
  std::vector<int> index(usedByCells.size(), -1);
  int used = 0;
  long long firstDropped = -1;
  for (size_t i = 0; i < usedByCells.size(); ++i) {
    if (usedByCells[i]) index[i] = used++;
    else if (firstDropped < 0) firstDropped = nodeIds[i];
  }
  if (used < static_cast<int>(usedByCells.size())) {
    std::ostringstream os;
    os << file << ": " << usedByCells.size() - used << " of its " << usedByCells.size()
       << " nodes belong to no 3D element and are dropped (the first: node " << firstDropped << ")";
    warn(warnings, os.str());
  }
  return index;
}

}  // namespace detail
}  // namespace Mesh
}  // namespace Tribos
