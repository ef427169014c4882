// The readers on second-order cells: Gmsh's Tet10 and Hex20 blocks of
// test/data/quadratic (their faces of 6- and 8-node facets, outward, with the
// mid-edge nodes of their cells), the same cells written as Exodus II
// TETRA10 and HEX20 blocks (Exodus' node order) read back alike, bodies of
// different orders, and the files refused: a body of mixed orders, bonded
// bodies of different orders, order 3, Hex27, inverted and folded cells, a
// mid-edge node far from its edge's midpoint (a warning).
#include <Teuchos_UnitTestHarness.hpp>

#include <exodusII.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <unistd.h>

#include "Tribos_BodyShape.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_ExodusReader.hpp"
#include "Tribos_GmshReader.hpp"
#include "Tribos_MeshBroadcast.hpp"
#include "MeshTestGeometry.hpp"

#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos::Mesh;
using namespace Tribos::Mesh::Test;

std::string dataFile(const std::string& name) { return sourceDir() + "/test/data/quadratic/" + name; }

std::string readError(const std::string& path, std::vector<std::string>* warnings = nullptr) {
  try {
    path.size() > 4 && path.substr(path.size() - 4) == ".exo" ? readExodus(path, warnings) : readGmsh(path, warnings);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

P midpoint(const Mesh& m, int a, int b) {
  P p;
  for (int d = 0; d < 3; ++d) p[d] = 0.5 * (m.coords[a][d] + m.coords[b][d]);
  return p;
}

double distance(const P& a, const P& b) { return std::sqrt(dot(sub(a, b), sub(a, b))); }

// A block of 2 x 1 x 1 with faces symmetry_x (x = 0), side_x (x = 2),
// symmetry_y (y = 0), bottom (z = 0), top (z = 1): every facet of a face has
// the facet's node count, its mid-edge nodes at the midpoints of its edges
// (Gmsh's facet order), is a face of its cell, points outward, and the faces
// have their areas.
void checkBlock(const Mesh& m, CellType type, Teuchos::FancyOStream& out, bool& success) {
  TEST_ASSERT(m.type == type);
  const int corners = type == CellType::Tet10 ? 3 : 4, nodes = 2 * corners;
  struct Face {
    const char* name;
    P normal;
    double area;
  };
  for (const Face& f : {Face{"symmetry_x", {-1, 0, 0}, 1}, Face{"side_x", {1, 0, 0}, 1}, Face{"symmetry_y", {0, -1, 0}, 2},
                        Face{"bottom", {0, 0, -1}, 2}, Face{"top", {0, 0, 1}, 2}}) {
    double area = 0, worstMid = 0;
    bool sized = true, outward = true, ofCell = true;
    for (const Facet& facet : m.face(f.name)) {
      sized = sized && static_cast<int>(facet.nodes.size()) == nodes;
      if (!sized) break;
      Facet cornersOnly{std::vector<int>(facet.nodes.begin(), facet.nodes.begin() + corners), facet.cell};
      const P a = areaVector(m, cornersOnly);
      const double len = std::sqrt(dot(a, a));
      area += len;
      outward = outward && std::abs(dot(a, f.normal) - len) < 1e-12;
      for (int k = 0; k < corners; ++k)
        worstMid = std::max(worstMid, distance(m.coords[facet.nodes[corners + k]],
                                               midpoint(m, facet.nodes[k], facet.nodes[(k + 1) % corners])));
      const std::set<int> cellNodes(m.cell(facet.cell), m.cell(facet.cell) + m.nodesPerCell());
      for (int n : facet.nodes) ofCell = ofCell && cellNodes.count(n) == 1;
    }
    out << f.name << ": " << m.face(f.name).size() << " facets, area " << area << ", mid-edge offset " << worstMid << "\n";
    TEST_ASSERT(sized && outward && ofCell);
    TEST_FLOATING_EQUALITY(area, f.area, 1e-12);
    TEST_ASSERT(worstMid < 1e-12);
  }
  // The body's shape from its cells' corners: volume 2, boundary area 10.
  const auto shapes = bodyShapes(m);
  TEST_FLOATING_EQUALITY(shapes.at(0).volume, 2.0, 1e-12);
  TEST_FLOATING_EQUALITY(shapes.at(0).boundaryArea, 10.0, 1e-12);
  requireSolvableBodies(m, "block");
}

TEUCHOS_UNIT_TEST(QuadraticRead, GmshTet10Block) {
  std::vector<std::string> warnings;
  const Mesh m = readGmsh(dataFile("block_tet10.msh"), &warnings);
  TEST_EQUALITY(warnings.size(), 0u);
  TEST_EQUALITY(m.numNodes(), 325);
  checkBlock(m, CellType::Tet10, out, success);
}

TEUCHOS_UNIT_TEST(QuadraticRead, GmshHex20Block) {
  std::vector<std::string> warnings;
  const Mesh m = readGmsh(dataFile("block_hex20.msh"), &warnings);
  TEST_EQUALITY(warnings.size(), 0u);
  TEST_EQUALITY(m.numCells(), 12);
  TEST_EQUALITY(m.numNodes(), 111);  // 4 x 3 x 3 corners and 75 mid-edge nodes
  checkBlock(m, CellType::Hex20, out, success);
}

// Exodus II numbers the mid-edge nodes of TETRA10 0-1, 1-2, 2-0, 0-3, 1-3,
// 2-3 and of HEX20 the bottom edges, the vertical edges, the top edges.
void writeExodus(const std::string& file, const Mesh& m) {
  static const std::vector<int> tet10 = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};  // Exodus node k = Gmsh node tet10[k]
  static const std::vector<int> hex20 = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 10, 12, 14, 15, 16, 18, 19, 17};
  const auto& order = m.type == CellType::Tet10 ? tet10 : hex20;
  int cpu = 8, io = 8;
  const int exo = ex_create(file.c_str(), EX_CLOBBER, &cpu, &io);
  ex_put_init(exo, "quadratic", 3, m.numNodes(), m.numCells(), 1, 0, 0);
  std::vector<double> x, y, z;
  for (const auto& p : m.coords) x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
  ex_put_coord(exo, x.data(), y.data(), z.data());
  std::vector<int> conn;
  for (int c = 0; c < m.numCells(); ++c)
    for (int k : order) conn.push_back(m.cell(c)[k] + 1);
  ex_put_block(exo, EX_ELEM_BLOCK, 1, m.type == CellType::Tet10 ? "TETRA10" : "HEX20", m.numCells(), m.nodesPerCell(), 0,
               0, 0);
  ex_put_conn(exo, EX_ELEM_BLOCK, 1, conn.data(), nullptr, nullptr);
  ex_put_name(exo, EX_ELEM_BLOCK, 1, "block");
  ex_close(exo);
}

TEUCHOS_UNIT_TEST(QuadraticRead, ExodusTet10AndHex20) {
  for (const char* name : {"block_tet10.msh", "block_hex20.msh"}) {
    const Mesh g = readGmsh(dataFile(name));
    const std::string file = "/tmp/tribos_quadratic_" + std::to_string(getpid()) + ".exo";
    writeExodus(file, g);
    std::vector<std::string> warnings;
    const Mesh e = readExodus(file, &warnings);
    std::remove(file.c_str());
    TEST_ASSERT(e.type == g.type);
    TEST_EQUALITY(e.numCells(), g.numCells());
    // Cell by cell, node by node: the same points (both keep the file's node order).
    double worst = 0;
    for (int c = 0; c < std::min(e.numCells(), g.numCells()); ++c)
      for (int a = 0; a < g.nodesPerCell(); ++a)
        worst = std::max(worst, distance(e.coords[e.cell(c)[a]], g.coords[g.cell(c)[a]]));
    out << name << " as Exodus II: worst node distance " << worst << "\n";
    TEST_ASSERT(worst == 0);
  }
}

// Bodies of different orders: a Tet4 body beside a Tet10 one is read (each
// cell with its type and nodes), travels through pack/unpack, and is cut
// into one subdomain per body; the same cells in one body, and a Tet10
// body bonded to a Tet4 one through shared nodes, are refused.
TEUCHOS_UNIT_TEST(QuadraticRead, MixedOrderBodies) {
  const Mesh m = readGmsh(dataFile("mixed_order.msh"));
  TEST_ASSERT(m.mixed());
  TEST_EQUALITY(m.numCells(), 2);
  TEST_EQUALITY(m.numNodes(), 14);
  TEST_ASSERT(m.cellType(0) == CellType::Tet4 && m.cellType(1) == CellType::Tet10);
  TEST_EQUALITY(m.cellSize(0), 4);
  TEST_EQUALITY(m.cellSize(1), 10);
  TEST_ASSERT(m.bodyName(m.bodyOf(1)) == "quadratic");
  TEST_ASSERT(m.hasSecondOrderCells());
  // The Tet10's mid-edge node 4 (edge 0-1) at its edge's midpoint, its corner 0 at (2, 0, 0).
  TEST_EQUALITY(distance(m.coords[m.cell(1)[4]], midpoint(m, m.cell(1)[0], m.cell(1)[1])), 0.0);
  TEST_EQUALITY(distance(m.coords[m.cell(1)[0]], P{2, 0, 0}), 0.0);
  std::string e;
  try {
    m.nodesPerCell();
  } catch (const std::exception& x) {
    e = x.what();
  }
  TEST_ASSERT(contains(e, "several types (Tet4, Tet10)"));

  Tribos::ByteBuffer buffer;
  packMesh(m, buffer);
  const Mesh back = unpackMesh(buffer);
  TEST_ASSERT(back.mixed() && back.cellType(0) == CellType::Tet4 && back.cellType(1) == CellType::Tet10);
  TEST_ASSERT(back.connectivity == m.connectivity);

  const Discretization d(m, boundingBox(m), DecompositionSpec{"METIS", {1, 1, 1}, 2}, 1, 0);
  TEST_EQUALITY(d.localSubdomains.size(), 2u);
  for (const Subdomain& s : d.localSubdomains) {
    TEST_EQUALITY(s.cells.size(), 1u);
    TEST_EQUALITY(s.connectivity.size(), static_cast<size_t>(d.part.cellSize(s.cells[0])));
    for (int a = 0; a < d.part.cellSize(s.cells[0]); ++a)
      TEST_EQUALITY(s.nodes[s.connectivity[a]], d.part.cell(s.cells[0])[a]);
  }
  TEST_ASSERT(d.part.mixed());

  e = readError(dataFile("mixed_order_in_body.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "mixed_order_in_body.msh\": physical volume 'part' mixes Tet4 (volume 1) and Tet10 (volume 2, "
                          "element 2 (Tet10)); a body of first- and second-order cells is not supported"));
  e = readError(dataFile("bonded_mixed_order.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "bonded_mixed_order.msh\": node 2 is shared by body \"linear\" (Tet4 cells) and body "
                          "\"quadratic\" (Tet10 cells): bodies bonded through shared nodes need one cell type"));
}

TEUCHOS_UNIT_TEST(QuadraticRead, Refused) {
  std::string e = readError(dataFile("order3.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "(Tet20) in physical volume 'cube' is not supported (elements of order 3 or more are not "
                          "supported"));
  e = readError(dataFile("hex27.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "(Hex27) in physical volume 'cube' is not supported (Hex27 is not supported; mesh with -order "
                          "2 and Mesh.SecondOrderIncomplete=1 for Hex20)"));
  e = readError(dataFile("inverted_tet10.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "1 inverted or folded Tet10 element (det J <= 0 at a node or quadrature point): element 1 "
                          "(Tet10) of physical volume 'part': det J = -1 at its node 0"));
  // Folded: the mid-edge node stays on its edge, 0.35 of it from the middle:
  // every corner volume is positive, det J at corner 1 is not.
  std::vector<std::string> warnings;
  e = readError(dataFile("folded_tet10.msh"), &warnings);
  out << e << "\n";
  TEST_ASSERT(contains(e, "1 inverted or folded Tet10 element") && contains(e, "element 1 (Tet10) of physical volume 'part'") &&
              contains(e, "at its node 1 (1, 0, 0)"));
  TEST_EQUALITY(warnings.size(), 1u);
  // Curved: read, with one warning naming the element and the ratio.
  warnings.clear();
  e = readError(dataFile("curved_tet10.msh"), &warnings);
  TEST_EQUALITY(e, "");
  TEST_EQUALITY(warnings.size(), 1u);
  if (!warnings.empty()) {
    out << warnings[0] << "\n";
    TEST_ASSERT(contains(warnings[0], "element 1 (Tet10) of physical volume 'part' has its mid-edge node 4 at (0.5, -0.3, 0), "
                                      "0.3 of its edge's length from the edge's midpoint"));
  }
}

}  // namespace
