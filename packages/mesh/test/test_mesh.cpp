// Mesh generation, METIS and structured decomposition, rank layout.
#include <Tpetra_Core.hpp>

#include <cmath>
#include <iostream>
#include <algorithm>
#include <map>
#include <set>

#include "Tribos_TestSupport.hpp"
#include "Tribos_Decomposition.hpp"
#include "Tribos_Mesh.hpp"

using namespace Tribos::Mesh;


static double cellVolume(const Mesh& m, int c) {
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

static void testBox(CellType type) {
  BoxSpec spec;
  spec.type = type;
  spec.x = {0, 3};
  spec.cells = {6, 2, 3};
  const Mesh m = generateBox(spec);
  CHECK(m.numNodes() == 7 * 3 * 4, "node count");
  CHECK(m.numCells() == 36 * (type == CellType::Tet4 ? 6 : 1), "cell count");
  double vol = 0;
  bool positive = true;
  for (int c = 0; c < m.numCells(); ++c) {
    const double v = cellVolume(m, c);
    positive = positive && v > 0;
    vol += v;
  }
  CHECK(positive, "every cell has positive orientation");
  CHECK(std::abs(vol - 3.0) < 1e-12, "cells tile the box, volume " << vol);
  // Face areas by facet count: zmin has 6x2 quads (or twice as many triangles).
  CHECK(m.face("zmin").size() == static_cast<size_t>(12 * (type == CellType::Tet4 ? 2 : 1)), "zmin facets");
  CHECK(m.faceNodes("xmax").size() == 3 * 4, "xmax nodes");
  for (const auto& f : m.face("zmin"))
    for (int n : f.nodes) CHECK(std::abs(m.coords[n][2]) < 1e-14, "zmin facet node off the plane");
  bool threw = false;
  try {
    m.face("top");
  } catch (const std::exception& e) {
    threw = std::string(e.what()).find("xmin") != std::string::npos;
  }
  CHECK(threw, "an unknown face name throws and lists the valid names");
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
    CHECK(ok && boundary == expected, "Kuhn split is conforming: " << boundary << " boundary triangles, " << expected
                                                                 << " on named faces");
  }
}

static void testPartitions(CellType type) {
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
    CHECK(once, "METIS partition into " << S << " covers every cell exactly once");
    for (const auto& s : subs) {
      CHECK(!s.cells.empty(), "subdomain " << s.id << " is not empty");
      for (size_t k = 0; k < s.cells.size(); ++k)
        for (int a = 0; a < m.nodesPerCell(); ++a)
          CHECK(s.nodes[s.connectivity[k * m.nodesPerCell() + a]] == m.cell(s.cells[k])[a], "local numbering");
    }
  }
  // The seed brick: three unit cubes.
  const auto part = partitionStructured(m, spec, {3, 1, 1});
  const auto subs = extractSubdomains(m, part, 3);
  for (const auto& s : subs) {
    double lo = 1e300, hi = -1e300;
    for (int n : s.nodes) lo = std::min(lo, m.coords[n][0]), hi = std::max(hi, m.coords[n][0]);
    CHECK(std::abs(lo - s.id) < 1e-14 && std::abs(hi - s.id - 1) < 1e-14,
          "structured subdomain " << s.id << " is the cube [" << s.id << "," << s.id + 1 << "], got [" << lo << "," << hi << "]");
  }
}

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  testBox(CellType::Tet4);
  testBox(CellType::Hex8);
  testPartitions(CellType::Tet4);
  testPartitions(CellType::Hex8);
  // Rank layout: contiguous blocks covering all subdomains.
  for (int S : {3, 7, 64})
    for (int P : {1, 2, 3}) {
      const auto layout = makeRankLayout(S, P);
      int prev = 0;
      for (int s = 0; s < S; ++s) {
        const int r = layout.owner(s);
        CHECK(r >= prev && layout.firstSubdomain(r) <= s && s < layout.firstSubdomain(r + 1), "owner of " << s);
        prev = r;
      }
    }
  if (Tribos::Test::failures()) std::cerr << Tribos::Test::failures() << " checks failed" << std::endl;
  else std::cout << "all mesh checks passed" << std::endl;
  return Tribos::Test::failures() ? 1 : 0;
}
