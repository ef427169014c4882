#include "Tribos_Mesh.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Mesh {

int nodesPerCell(CellType type) { return type == CellType::Tet4 ? 4 : 8; }

std::string cellTypeName(CellType type) { return type == CellType::Tet4 ? "Tet4" : "Hex8"; }

CellType cellTypeFromName(const std::string& name) {
  if (name == "Tet4") return CellType::Tet4;
  if (name == "Hex8") return CellType::Hex8;
  throw Error("element \"" + name + "\" unknown; valid: Tet4, Hex8");
}

const std::vector<Facet>& Mesh::face(const std::string& name) const {
  auto it = faces.find(name);
  if (it == faces.end()) {
    std::string valid;
    for (const auto& f : faces) valid += (valid.empty() ? "" : ", ") + f.first;
    throw Error("mesh has no face named \"" + name + "\"; valid faces: " + valid);
  }
  return it->second;
}

std::vector<int> Mesh::faceNodes(const std::string& name) const {
  std::vector<int> nodes;
  for (const Facet& f : face(name)) nodes.insert(nodes.end(), f.nodes.begin(), f.nodes.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<std::string> Mesh::faceNames() const {
  std::vector<std::string> names;
  for (const auto& f : faces) names.push_back(f.first);
  return names;
}

namespace {

// Local faces of the reference cells, ordered so the normal points outwards.
const std::vector<std::vector<int>>& referenceFaces(CellType type) {
  static const std::vector<std::vector<int>> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}};
  return type == CellType::Tet4 ? tet : hex;
}

double signedVolume6(const std::array<double, 3>& a, const std::array<double, 3>& b,
                     const std::array<double, 3>& c, const std::array<double, 3>& d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Collects the cell faces lying on the six planes of the box.
void collectBoundaryFaces(Mesh& mesh, const BoxSpec& spec) {
  const std::array<std::string, 6> names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  const double h = std::min({(spec.x[1] - spec.x[0]) / spec.cells[0], (spec.y[1] - spec.y[0]) / spec.cells[1],
                             (spec.z[1] - spec.z[0]) / spec.cells[2]});
  const double tol = 1e-8 * h;
  const std::array<double, 6> planes = {spec.x[0], spec.x[1], spec.y[0], spec.y[1], spec.z[0], spec.z[1]};
  for (const auto& n : names) mesh.faces[n];
  for (int c = 0; c < mesh.numCells(); ++c) {
    for (const auto& lf : referenceFaces(mesh.type)) {
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

Mesh generateBox(const BoxSpec& spec) {
  const int nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  TRIBOS_REQUIRE(nx > 0 && ny > 0 && nz > 0,
                 "box cells: need at least one cell per axis, got " << nx << "x" << ny << "x" << nz);
  TRIBOS_REQUIRE(spec.x[1] > spec.x[0] && spec.y[1] > spec.y[0] && spec.z[1] > spec.z[0],
                 "Mesh: box ranges must be increasing intervals");
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
          if (signedVolume6(mesh.coords[tet[0]], mesh.coords[tet[1]], mesh.coords[tet[2]], mesh.coords[tet[3]]) < 0)
            std::swap(tet[2], tet[3]);
          mesh.connectivity.insert(mesh.connectivity.end(), tet, tet + 4);
        }
      }
  collectBoundaryFaces(mesh, spec);
  return mesh;
}

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
