#include "Tribos_Mesh.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_BodyShape.hpp"
#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

constexpr CellType kCellTypes[] = {CellType::Tet4, CellType::Hex8, CellType::Tet10, CellType::Hex20};

}  // namespace

std::string cellTypeName(CellType type) {
  switch (type) {
    case CellType::Tet4: return "Tet4";
    case CellType::Hex8: return "Hex8";
    case CellType::Tet10: return "Tet10";
    case CellType::Hex20: return "Hex20";
  }
  throw Error("cell type " + std::to_string(static_cast<int>(type)) + " unknown");
}

CellType cellTypeFromName(const std::string& name) {
  std::string valid;
  for (CellType t : kCellTypes) {
    if (name == cellTypeName(t)) return t;
    valid += (valid.empty() ? "" : ", ") + cellTypeName(t);
  }
  throw Error("element \"" + name + "\" unknown; valid: " + valid);
}

bool isSecondOrder(CellType type) { return type == CellType::Tet10 || type == CellType::Hex20; }

int Mesh::nodesPerCell() const {
  TRIBOS_REQUIRE(!mixed(), "the mesh holds cells of several types (" << [&] {
    std::string names;
    for (CellType t : cellTypesPresent()) names += (names.empty() ? "" : ", ") + cellTypeName(t);
    return names;
  }() << "); their nodes per cell differ");
  return nodesPerCellOf(type);
}

std::vector<CellType> Mesh::cellTypesPresent() const {
  if (!mixed()) return connectivity.empty() ? std::vector<CellType>{} : std::vector<CellType>{type};
  std::vector<CellType> present;
  for (CellType t : kCellTypes)
    if (std::find(cellTypes_.begin(), cellTypes_.end(), t) != cellTypes_.end()) present.push_back(t);
  return present;
}

bool Mesh::hasSecondOrderCells() const {
  for (CellType t : cellTypesPresent())
    if (isSecondOrder(t)) return true;
  return false;
}

void Mesh::addCell(CellType cellType, const int* nodes) {
  if (connectivity.empty() && !mixed()) type = cellType;
  if (!mixed() && cellType != type) {
    const int cells = numCells();
    cellTypes_.assign(cells, type);
    cellStart_.resize(cells);
    for (int c = 0; c < cells; ++c) cellStart_[c] = static_cast<size_t>(c) * nodesPerCellOf(type);
  }
  if (mixed()) cellTypes_.push_back(cellType), cellStart_.push_back(connectivity.size());
  connectivity.insert(connectivity.end(), nodes, nodes + nodesPerCellOf(cellType));
}

void Mesh::setCellTypes(const std::vector<CellType>& types) {
  size_t entries = 0;
  for (CellType t : types) entries += nodesPerCellOf(t);
  TRIBOS_REQUIRE(entries == connectivity.size(), "mesh: " << types.size() << " cell types name " << entries
                                                          << " nodes, but the connectivity holds " << connectivity.size());
  cellTypes_.clear();
  cellStart_.clear();
  if (types.empty()) return;
  type = types.front();
  if (std::all_of(types.begin(), types.end(), [&](CellType t) { return t == type; })) return;
  cellTypes_ = types;
  cellStart_.resize(types.size());
  size_t start = 0;
  for (size_t c = 0; c < types.size(); ++c) cellStart_[c] = start, start += nodesPerCellOf(types[c]);
}

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list.empty() ? "(none)" : list;
}

}  // namespace

const std::vector<Facet>& Mesh::face(const std::string& name) const {
  auto it = faces.find(name);
  if (it == faces.end()) {
    // A node set has no facets to integrate a load over or to put in contact.
    TRIBOS_REQUIRE(!nodeSets.count(name), "\"" << name << "\" is a node set without facets; a face is needed here; "
                                                         "valid faces: " << joined(faceNames()));
    throw Error("mesh has no face named \"" + name + "\"; valid faces: " + joined(faceNames()));
  }
  return it->second;
}

std::vector<int> Mesh::faceNodes(const std::string& name) const {
  auto part = partFaceNodes.find(name);
  if (part != partFaceNodes.end()) return part->second;
  std::vector<int> nodes;
  if (!faces.count(name) && nodeSets.count(name)) {
    nodes = nodeSets.at(name);
  } else if (!faces.count(name)) {
    throw Error("mesh has no face named \"" + name + "\"; valid faces: " + joined(faceNames()) +
                (nodeSets.empty() ? "" : "; node sets: " + joined(nodeSetNames())));
  } else {
    for (const Facet& f : face(name)) nodes.insert(nodes.end(), f.nodes.begin(), f.nodes.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<std::string> Mesh::faceNames() const {
  std::vector<std::string> names;
  for (const auto& f : faces) names.push_back(f.first);
  return names;
}

std::vector<std::string> Mesh::nodeSetNames() const {
  std::vector<std::string> names;
  for (const auto& s : nodeSets) names.push_back(s.first);
  return names;
}

const std::string& Mesh::bodyName(int body) const {
  static const std::string single = "body";
  TRIBOS_REQUIRE(body >= 0 && body < numBodies(), "body " << body << " out of range; the mesh has " << numBodies()
                                                          << " bod" << (numBodies() == 1 ? "y" : "ies"));
  return bodyNames.empty() ? single : bodyNames[body];
}

int Mesh::bodyIndex(const std::string& name) const {
  std::vector<std::string> names;
  for (int b = 0; b < numBodies(); ++b) {
    if (bodyName(b) == name) return b;
    names.push_back(bodyName(b));
  }
  throw Error("mesh has no body named \"" + name + "\"; valid bodies: " + joined(names));
}

int Mesh::faceBody(const std::string& name) const {
  const std::vector<Facet>& facets = face(name);
  TRIBOS_REQUIRE(!facets.empty(), "face \"" << name << "\" has no facets, so it lies on no body");
  const int body = bodyOf(facets.front().cell);
  for (const Facet& f : facets)
    TRIBOS_REQUIRE(bodyOf(f.cell) == body, "face \"" << name << "\" has facets on bodies \"" << bodyName(body)
                                                      << "\" and \"" << bodyName(bodyOf(f.cell))
                                                      << "\"; a face here must lie on one body");
  return body;
}

void Mesh::checkBodies(const std::string& what, const std::vector<long long>& nodeIds) const {
  TRIBOS_REQUIRE(cellBody.empty() || static_cast<int>(cellBody.size()) == numCells(),
                 what << ": cellBody has " << cellBody.size() << " entries for " << numCells() << " cells");
  std::vector<int> cells(numBodies(), 0);
  for (int c = 0; c < static_cast<int>(cellBody.size()); ++c) {
    TRIBOS_REQUIRE(cellBody[c] >= 0 && cellBody[c] < numBodies(),
                   what << ": cell " << c << " is in body " << cellBody[c] << " but the mesh has " << numBodies()
                                 << " bod" << (numBodies() == 1 ? "y" : "ies") << " (bodyNames)");
    ++cells[cellBody[c]];
  }
  if (cellBody.empty()) cells[0] = numCells();
  for (int b = 0; b < numBodies(); ++b) {
    TRIBOS_REQUIRE(numCells() == 0 || cells[b] > 0, what << ": body \"" << bodyName(b) << "\" has no cells");
    for (int a = 0; a < b; ++a)
      TRIBOS_REQUIRE(bodyName(a) != bodyName(b), what << ": two bodies are named \"" << bodyName(b) << "\"");
  }
  if (mixed()) requireOneTypePerBody(what, nodeIds);
}

void Mesh::requireOneTypePerBody(const std::string& what, const std::vector<long long>& nodeIds) const {
  std::vector<int> firstCell(numBodies(), -1);
  for (int c = 0; c < numCells(); ++c) {
    int& first = firstCell[bodyOf(c)];
    if (first < 0) first = c;
    TRIBOS_REQUIRE(cellType(c) == cellType(first),
                   what << ": body \"" << bodyName(bodyOf(c)) << "\" mixes " << cellTypeName(cellType(first)) << " (cell "
                                   << first << ") and " << cellTypeName(cellType(c)) << " (cell " << c
                                   << ") cells; a body holds cells of one type (mesh it with one element type and "
                                      "one order)");
  }
  // The first cell of each node; a cell of another type at the node is a
  // bonded interface between bodies of different types.
  std::vector<int> nodeCell(numNodes(), -1);
  for (int c = 0; c < numCells(); ++c)
    for (int a = 0; a < cellSize(c); ++a) {
      const int n = cell(c)[a];
      if (nodeCell[n] < 0) nodeCell[n] = c;
      const int o = nodeCell[n];
      TRIBOS_REQUIRE(cellType(o) == cellType(c),
                     what << ": node " << (nodeIds.empty() ? n : nodeIds[n]) << " is shared by body \"" << bodyName(bodyOf(o)) << "\" ("
                                   << cellTypeName(cellType(o)) << " cells) and body \"" << bodyName(bodyOf(c)) << "\" ("
                                   << cellTypeName(cellType(c))
                                   << " cells): bodies bonded through shared nodes need one cell type (a face of one "
                                      "would not match the other's); give the bodies distinct nodes and join them "
                                      "by contact (Type = Glued ties them)");
    }
}

namespace {

// Collects the cell faces lying on the six planes of the box.
void collectBoundaryFaces(Mesh& mesh, const BoxSpec& spec) {
  const std::array<std::string, 6> names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  const double h = std::min({(spec.x[1] - spec.x[0]) / spec.cells[0], (spec.y[1] - spec.y[0]) / spec.cells[1],
                             (spec.z[1] - spec.z[0]) / spec.cells[2]});
  const double tol = 1e-8 * h;
  const std::array<double, 6> planes = {spec.x[0], spec.x[1], spec.y[0], spec.y[1], spec.z[0], spec.z[1]};
  for (const auto& n : names) mesh.faces[n];
  for (int c = 0; c < mesh.numCells(); ++c) {
    for (const auto& lf : detail::cellFaces(mesh.type)) {
      for (int p = 0; p < 6; ++p) {
        const int axis = p / 2;
        bool on = true;
        for (int ln : lf) on = on && std::abs(mesh.coords[mesh.cell(c)[ln]][axis] - planes[p]) < tol;
        if (!on) continue;
        Facet f;
        f.cell = c;
        for (int ln : lf) f.nodes.push_back(mesh.cell(c)[ln]);
        mesh.faces[names[p]].push_back(f);
      }
    }
  }
}

}  // namespace

double boxNodeCount(const BoxSpec& spec) {
  const double nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  const double corners = (nx + 1) * (ny + 1) * (nz + 1);
  switch (spec.type) {
    case CellType::Tet10:  // every point of the lattice of half cells
      return (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1);
    case CellType::Hex20:  // the corners and the middles of the edges
      return corners + nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    default:
      return corners;
  }
}

double boxCellCount(const BoxSpec& spec) {
  return double(spec.cells[0]) * spec.cells[1] * spec.cells[2] * (detail::isTetrahedron(spec.type) ? 6 : 1);
}

void requireUsableBox(const BoxSpec& spec, const std::string& what) {
  // The corners hold the box's extreme coordinates; every other node lies between them.
  const long long nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  std::vector<std::array<double, 3>> corners;
  std::vector<long long> ids;
  for (int k : {0, 1})
    for (int j : {0, 1})
      for (int i : {0, 1}) {
        corners.push_back({spec.x[i], spec.y[j], spec.z[k]});
        ids.push_back(i * nx + (nx + 1) * (j * ny + (ny + 1) * k * nz));
      }
  detail::requireUsableCoordinates(corners, ids, what);
  const bool box = nx > 0 && ny > 0 && nz > 0 && spec.x[1] > spec.x[0] && spec.y[1] > spec.y[0] && spec.z[1] > spec.z[0];
  if (box) requireSolvableBox(spec, what);
}

Mesh generateBox(const BoxSpec& spec) {
  const int nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  TRIBOS_REQUIRE(nx > 0 && ny > 0 && nz > 0,
                 "box cells: need at least one cell per axis, got " << nx << "x" << ny << "x" << nz);
  TRIBOS_REQUIRE(spec.x[1] > spec.x[0] && spec.y[1] > spec.y[0] && spec.z[1] > spec.z[0],
                 "Mesh: box ranges must be increasing intervals");
  requireUsableBox(spec, "the box");
  return detail::boxMesh(spec);
}

namespace detail {

namespace {

// A box of second-order cells: the first-order box of the same cells on the
// lattice of half cells, each cell's mid-edge nodes the lattice points
// halfway between its corners (edgeNodes); the lattice points no cell uses
// (Hex20's face and cell centres) are dropped, the others keep the
// lattice's order.
Mesh secondOrderBoxMesh(const BoxSpec& spec) {
  BoxSpec lattice = spec;
  lattice.type = isTetrahedron(spec.type) ? CellType::Tet4 : CellType::Hex8;
  lattice.cells = {2 * spec.cells[0], 2 * spec.cells[1], 2 * spec.cells[2]};
  const Mesh fine = boxMesh(lattice);  // its nodes: the lattice
  BoxSpec coarse = lattice;
  coarse.cells = spec.cells;
  const Mesh corners = boxMesh(coarse);
  const int nx = spec.cells[0], ny = spec.cells[1];
  auto latticeId = [&](int node) {  // corner node (i, j, k) -> lattice point (2i, 2j, 2k)
    const int i = node % (nx + 1), j = (node / (nx + 1)) % (ny + 1), k = node / ((nx + 1) * (ny + 1));
    return 2 * i + (2 * nx + 1) * (2 * j + (2 * ny + 1) * 2 * k);
  };
  auto latticeMid = [&](int a, int b) {  // the lattice point halfway between two lattice points
    const int ax = a % (2 * nx + 1), ay = (a / (2 * nx + 1)) % (2 * ny + 1), az = a / ((2 * nx + 1) * (2 * ny + 1));
    const int bx = b % (2 * nx + 1), by = (b / (2 * nx + 1)) % (2 * ny + 1), bz = b / ((2 * nx + 1) * (2 * ny + 1));
    return (ax + bx) / 2 + (2 * nx + 1) * ((ay + by) / 2 + (2 * ny + 1) * ((az + bz) / 2));
  };
  Mesh mesh;
  mesh.type = spec.type;
  const int npc = nodesPerCell(spec.type), cornersPerCell = corners.nodesPerCell();
  std::vector<int> cell(npc);
  for (int c = 0; c < corners.numCells(); ++c) {
    for (int a = 0; a < cornersPerCell; ++a) cell[a] = latticeId(corners.cell(c)[a]);
    for (const auto& e : detail::edgeNodes(spec.type)) cell[e[0]] = latticeMid(cell[e[1]], cell[e[2]]);
    mesh.connectivity.insert(mesh.connectivity.end(), cell.begin(), cell.end());
  }
  std::vector<int> newId(fine.numNodes(), -1);
  for (int n : mesh.connectivity) newId[n] = 0;
  for (int n = 0; n < fine.numNodes(); ++n)
    if (newId[n] == 0) newId[n] = static_cast<int>(mesh.coords.size()), mesh.coords.push_back(fine.coords[n]);
  for (int& n : mesh.connectivity) n = newId[n];
  return mesh;
}

}  // namespace

Mesh boxMesh(const BoxSpec& spec) {
  if (isSecondOrder(spec.type)) {
    Mesh mesh = secondOrderBoxMesh(spec);
    collectBoundaryFaces(mesh, spec);
    return mesh;
  }
  const int nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  Mesh mesh;
  mesh.type = spec.type;
  auto nodeId = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  mesh.coords.resize(static_cast<size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.coords[nodeId(i, j, k)] = {spec.x[0] + (spec.x[1] - spec.x[0]) * i / nx,
                                        spec.y[0] + (spec.y[1] - spec.y[0]) * j / ny,
                                        spec.z[0] + (spec.z[1] - spec.z[0]) * k / nz};
  // The six Kuhn tetrahedra: paths from corner (0,0,0) to (1,1,1) along the
  // axes in each order.
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (spec.type == CellType::Hex8) {
          const int hex[8] = {nodeId(i, j, k),         nodeId(i + 1, j, k),     nodeId(i + 1, j + 1, k),
                              nodeId(i, j + 1, k),     nodeId(i, j, k + 1),     nodeId(i + 1, j, k + 1),
                              nodeId(i + 1, j + 1, k + 1), nodeId(i, j + 1, k + 1)};
          mesh.connectivity.insert(mesh.connectivity.end(), hex, hex + 8);
          continue;
        }
        for (const auto& p : perms) {
          int ijk[3] = {i, j, k};
          int tet[4];
          tet[0] = nodeId(ijk[0], ijk[1], ijk[2]);
          for (int s = 0; s < 3; ++s) {
            ++ijk[p[s]];
            tet[s + 1] = nodeId(ijk[0], ijk[1], ijk[2]);
          }
          if (detail::triple(mesh.coords[tet[0]], mesh.coords[tet[1]], mesh.coords[tet[2]], mesh.coords[tet[3]]) < 0)
            std::swap(tet[2], tet[3]);
          mesh.connectivity.insert(mesh.connectivity.end(), tet, tet + 4);
        }
      }
  collectBoundaryFaces(mesh, spec);
  return mesh;
}

}  // namespace detail

std::array<int, 3> prismLevelCells(int L) {
  TRIBOS_REQUIRE(L >= 1, "the prism level must be >= 1, got " << L);
  const double nx = std::ceil(std::pow(2.0, (L + 4) / 2.0) - 1e-12);
  const double ny = std::ceil(std::pow(2.0, (L + 2) / 2.0) - 1e-12);
  TRIBOS_REQUIRE(nx <= kMaxCellsPerAxis, "the prism level " << L << " gives " << nx << " cells along x; at most "
                                                                        << kMaxCellsPerAxis << " are allowed");
  return {static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(ny)};
}

}  // namespace Mesh
}  // namespace Tribos
