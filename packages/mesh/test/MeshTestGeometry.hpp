// MeshTestGeometry.hpp: the geometry the mesh readers' tests check a mesh
// with (cell volumes, facet area vectors), computed independently of the
// library.
#pragma once

#include <array>
#include <cstdlib>
#include <string>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {
namespace Test {

// The source tree (TRIBOS_SOURCE_DIR, set by ctest), where the tests' data
// files are.
inline std::string sourceDir() {
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  return dir ? dir : ".";
}

using P = std::array<double, 3>;
inline P sub(const P& a, const P& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline P cross(const P& a, const P& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const P& a, const P& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Volume of a cell: the tetrahedron, or the hexahedron as six Kuhn
// tetrahedra (exact for the affine hexahedra of a block).
inline double cellVolume(const Mesh& m, int c) {
  const int* n = m.cell(c);
  auto tet = [&](int a, int b, int d, int e) {
    return dot(sub(m.coords[n[b]], m.coords[n[a]]), cross(sub(m.coords[n[d]], m.coords[n[a]]), sub(m.coords[n[e]], m.coords[n[a]]))) / 6;
  };
  if (m.type == CellType::Tet4) return tet(0, 1, 2, 3);
  return tet(0, 1, 2, 6) + tet(0, 2, 3, 6) + tet(0, 3, 7, 6) + tet(0, 7, 4, 6) + tet(0, 4, 5, 6) + tet(0, 5, 1, 6);
}

// Area vector of a facet (planar facets), by the nodes' order: points
// outwards when the order is counter-clockwise seen from outside.
inline P areaVector(const Mesh& m, const Facet& f) {
  P s{0, 0, 0};
  const auto& x0 = m.coords[f.nodes[0]];
  for (size_t k = 1; k + 1 < f.nodes.size(); ++k) {
    const P c = cross(sub(m.coords[f.nodes[k]], x0), sub(m.coords[f.nodes[k + 1]], x0));
    for (int d = 0; d < 3; ++d) s[d] += c[d] / 2;
  }
  return s;
}

}  // namespace Test
}  // namespace Mesh
}  // namespace Tribos
