// Mesh generation, METIS and structured decomposition, rank layout.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "Tribos_Decomposition.hpp"
#include "Tribos_Mesh.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace {

using namespace Tribos::Mesh;

double cellVolume(const Mesh& m, int c) {
  // Volume from the divergence theorem would need faces; for tets use the
  // determinant, for box hexes the bounding box.
  const int* n = m.cell(c);
  if (m.type == CellType::Tet4) {
    const auto &a = m.coords[n[0]], &b = m.coords[n[1]], &cc = m.coords[n[2]], &d = m.coords[n[3]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]},
                 w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
  }
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], m.coords[n[k]][d]), hi[d] = std::max(hi[d], m.coords[n[k]][d]);
  return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}

void checkBox(CellType type, Teuchos::FancyOStream& out, bool& success) {
  BoxSpec spec;
  spec.type = type;
  spec.x = {0, 3};
  spec.cells = {6, 2, 3};
  const Mesh m = generateBox(spec);
  TEST_EQUALITY(m.numNodes(), 7 * 3 * 4);
  TEST_EQUALITY(m.numCells(), 36 * (type == CellType::Tet4 ? 6 : 1));
  double vol = 0;
  bool positive = true;
  for (int c = 0; c < m.numCells(); ++c) {
    const double v = cellVolume(m, c);
    positive = positive && v > 0;
    vol += v;
  }
  TEST_ASSERT(positive);  // every cell has positive orientation
  TEST_COMPARE(std::abs(vol - 3.0), <, 1e-12);  // the cells tile the box
  // Face areas by facet count: zmin has 6x2 quads (or twice as many triangles).
  TEST_EQUALITY(m.face("zmin").size(), static_cast<size_t>(12 * (type == CellType::Tet4 ? 2 : 1)));
  TEST_EQUALITY(m.faceNodes("xmax").size(), static_cast<size_t>(3 * 4));
  for (const auto& f : m.face("zmin"))
    for (int n : f.nodes) TEST_COMPARE(std::abs(m.coords[n][2]), <, 1e-14);  // zmin facet node on the plane
  bool threw = false;
  try {
    m.face("top");
  } catch (const std::exception& e) {
    threw = std::string(e.what()).find("xmin") != std::string::npos;
  }
  TEST_ASSERT(threw);  // an unknown face name throws and lists the valid names
  // Conformity: every interior triangle is shared by exactly two tets.
  if (type == CellType::Tet4) {
    std::map<std::array<int, 3>, int> count;
    for (int c = 0; c < m.numCells(); ++c) {
      const int* n = m.cell(c);
      const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
      for (const auto& f : faces) {
        std::array<int, 3> key = {n[f[0]], n[f[1]], n[f[2]]};
        std::sort(key.begin(), key.end());
        ++count[key];
      }
    }
    size_t boundary = 0;
    bool ok = true;
    for (const auto& kv : count) {
      ok = ok && kv.second <= 2;
      boundary += kv.second == 1;
    }
    size_t expected = 0;
    for (const auto& name : m.faceNames()) expected += m.face(name).size();
    // The Kuhn split is conforming: no triangle in more than two tets, and
    // the boundary triangles are those of the named faces.
    TEST_ASSERT(ok);
    TEST_EQUALITY(boundary, expected);
  }
}

// A box of second-order cells: the node count boxNodeCount gives, every
// node of a cell where its first-order cell's shape functions put it (the
// corners of the first-order box, each mid-edge node the middle of its
// edge), every node used, the cells tiling the box, and faces whose facets
// carry their mid-edge nodes on the face's plane.
void checkSecondOrderBox(CellType type, Teuchos::FancyOStream& out, bool& success) {
  BoxSpec spec;
  spec.type = type;
  spec.x = {0, 3};
  spec.cells = {3, 2, 2};
  const Mesh m = generateBox(spec);
  BoxSpec linear = spec;
  linear.type = type == CellType::Tet10 ? CellType::Tet4 : CellType::Hex8;
  const Mesh l = generateBox(linear);
  TEST_EQUALITY(static_cast<double>(m.numNodes()), boxNodeCount(spec));
  TEST_EQUALITY(m.numNodes(), type == CellType::Tet10 ? 7 * 5 * 5 : 4 * 3 * 3 + 3 * 3 * 3 + 4 * 2 * 3 + 4 * 3 * 2);
  TEST_EQUALITY(m.numCells(), l.numCells());
  TEST_EQUALITY(static_cast<double>(m.numCells()), boxCellCount(spec));
  std::vector<int> used(m.numNodes(), 0);
  double worst = 0, vol = 0;
  for (int c = 0; c < m.numCells(); ++c) {
    const int* n = m.cell(c);
    for (int a = 0; a < m.nodesPerCell(); ++a) used[n[a]] = 1;
    for (int a = 0; a < l.nodesPerCell(); ++a)
      for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(m.coords[n[a]][d] - l.coords[l.cell(c)[a]][d]));
    for (const auto& e : Tribos::Mesh::detail::edgeNodes(type))
      for (int d = 0; d < 3; ++d)
        worst = std::max(worst, std::abs(m.coords[n[e[0]]][d] - 0.5 * (m.coords[n[e[1]]][d] + m.coords[n[e[2]]][d])));
    vol += cellVolume(l, c);
  }
  TEST_COMPARE(worst, <, 1e-15);
  TEST_EQUALITY(std::count(used.begin(), used.end(), 0), 0);
  TEST_COMPARE(std::abs(vol - 3.0), <, 1e-12);
  const size_t facetNodes = type == CellType::Tet10 ? 6 : 8;
  for (const auto& name : m.faceNames()) {
    TEST_EQUALITY(m.face(name).size(), l.face(name).size());
    for (const auto& f : m.face(name)) TEST_EQUALITY(f.nodes.size(), facetNodes);
  }
  for (const auto& f : m.face("zmin"))
    for (int n : f.nodes) TEST_COMPARE(std::abs(m.coords[n][2]), <, 1e-14);
}

TEUCHOS_UNIT_TEST(Box, Tet10) { checkSecondOrderBox(CellType::Tet10, out, success); }
TEUCHOS_UNIT_TEST(Box, Hex20) { checkSecondOrderBox(CellType::Hex20, out, success); }

void checkPartitions(CellType type, Teuchos::FancyOStream& out, bool& success) {
  BoxSpec spec;
  spec.type = type;
  spec.x = {0, 3};
  spec.cells = {12, 4, 4};
  const Mesh m = generateBox(spec);
  for (int S : {2, 5, 8}) {
    const auto part = partitionMetis(m, S);
    const auto subs = extractSubdomains(m, part, S);
    std::vector<int> seen(m.numCells(), 0);
    for (const auto& s : subs)
      for (int c : s.cells) ++seen[c];
    bool once = true;
    for (int v : seen) once = once && v == 1;
    out << "METIS partition into " << S << " subdomains\n";
    TEST_ASSERT(once);  // covers every cell exactly once
    for (const auto& s : subs) {
      TEST_ASSERT(!s.cells.empty());
      // The local numbering maps back to the cell's nodes (counted, not
      // asserted one by one: thousands of entries).
      int wrong = 0;
      for (size_t k = 0; k < s.cells.size(); ++k)
        for (int a = 0; a < m.nodesPerCell(); ++a)
          wrong += s.nodes[s.connectivity[k * m.nodesPerCell() + a]] != m.cell(s.cells[k])[a];
      TEST_EQUALITY(wrong, 0);
    }
  }
  // The seed brick: three unit cubes.
  const auto part = partitionStructured(m, spec, {3, 1, 1});
  const auto subs = extractSubdomains(m, part, 3);
  for (const auto& s : subs) {
    double lo = 1e300, hi = -1e300;
    for (int n : s.nodes) lo = std::min(lo, m.coords[n][0]), hi = std::max(hi, m.coords[n][0]);
    // Structured subdomain s is the cube [s, s + 1].
    out << "structured subdomain " << s.id << ": [" << lo << "," << hi << "]\n";
    TEST_COMPARE(std::abs(lo - s.id), <, 1e-14);
    TEST_COMPARE(std::abs(hi - s.id - 1), <, 1e-14);
  }
}

}  // namespace

TEUCHOS_UNIT_TEST(Box, Tet4) { checkBox(CellType::Tet4, out, success); }

TEUCHOS_UNIT_TEST(Box, Hex8) { checkBox(CellType::Hex8, out, success); }

TEUCHOS_UNIT_TEST(Box, UnusableCoordinates) {
  // The readers' coordinate check, for the box: by its corners, named by
  // their node numbers, before a node is made.
  auto errorOf = [](const BoxSpec& spec) {
    try {
      requireUsableBox(spec, "the box");
      generateBox(spec);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  BoxSpec spec;
  spec.cells = {2, 3, 4};
  spec.x = {0, 1e300};
  std::string e = errorOf(spec);
  out << e << "\n";
  TEST_EQUALITY(e, "the box: node 2 has coordinate x = 1e+300, beyond the 1e+50 a coordinate may have (the geometry "
                   "forms products of up to four lengths, which must stay representable); express the mesh in other units");
  spec.x = {0, 1};
  spec.z = {-1e51, 0};
  e = errorOf(spec);
  TEST_ASSERT(e.find("the box: node 0 has coordinate z = -1e+51") == 0);
  // The first corner at y = 1e51 is node (0, 3, 0) of a 3 x 4 x 5 grid of nodes: 3 * 3.
  spec.z = {0, 1};
  spec.y = {0, 1e51};
  e = errorOf(spec);
  TEST_ASSERT(e.find("the box: node 9 has coordinate y = 1e+51") == 0);
  spec.x = spec.y = spec.z = {0, 1e-51};
  e = errorOf(spec);
  out << e << "\n";
  TEST_ASSERT(e.find("the box: the mesh spans 1e-51 (the largest side of its bounding box), less than the 1e-50") == 0);
  spec.x = spec.y = spec.z = {-1e49, 1e49};
  TEST_EQUALITY(errorOf(spec), "");
}

TEUCHOS_UNIT_TEST(Partition, Tet4) { checkPartitions(CellType::Tet4, out, success); }

TEUCHOS_UNIT_TEST(Partition, Hex8) { checkPartitions(CellType::Hex8, out, success); }

// Rank layout: contiguous blocks covering all subdomains.
TEUCHOS_UNIT_TEST(RankLayout, ContiguousBlocks) {
  for (int S : {3, 7, 64})
    for (int P : {1, 2, 3}) {
      const auto layout = makeRankLayout(S, P);
      int prev = 0;
      for (int s = 0; s < S; ++s) {
        const int r = layout.owner(s);
        TEST_COMPARE(r, >=, prev);
        TEST_COMPARE(layout.firstSubdomain(r), <=, s);
        TEST_COMPARE(s, <, layout.firstSubdomain(r + 1));
        prev = r;
      }
    }
}
