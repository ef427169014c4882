// The Exodus II reader: files written here with the Exodus C API (no file
// is shipped), read back and compared; the sides of the Exodus reference
// cells against the Exodus II manual; the files it must refuse.
#include <Teuchos_UnitTestHarness.hpp>

#include <exodusII.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <unistd.h>

#include "Tribos_ExodusReader.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_MeshFile.hpp"
#include "MeshTestGeometry.hpp"

#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos::Mesh;
using namespace Tribos::Mesh::Test;

using Tribos::Test::contains;

std::string scratch(const std::string& name) {
  return "/tmp/tribos_exodus_test_" + std::to_string(getpid()) + "_" + name;
}

// Exodus sides (1-based local nodes) of the manual's tables: written
// independently of the reader's, so that a wrong table there fails here.
const std::vector<std::vector<int>>& sidesOf(CellType type) {
  static const std::vector<std::vector<int>> tet = {{1, 2, 4}, {2, 3, 4}, {1, 4, 3}, {1, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7},
                                                    {1, 5, 8, 4}, {1, 4, 3, 2}, {5, 6, 7, 8}};
  return type == CellType::Tet4 ? tet : hex;
}

// The Exodus side of cell c whose nodes are the facet's.
int sideOf(const Mesh& m, int c, const std::vector<int>& nodes) {
  const std::set<int> want(nodes.begin(), nodes.end());
  const auto& sides = sidesOf(m.type);
  for (size_t s = 0; s < sides.size(); ++s) {
    std::set<int> have;
    for (int ln : sides[s]) have.insert(m.cell(c)[ln - 1]);
    if (have == want) return static_cast<int>(s) + 1;
  }
  return -1;
}

struct ExtraSide {  // a side set entry given directly (1-based element, side)
  std::string set;
  int element, side;
};

// Writes a Mesh as Exodus II: one element block per body (id 10 (b + 1),
// named by bodyNames unless the name is empty), the cells in body order;
// faces as side sets (ids 1, 2, ...), node sets (ids 101, ...); node ids
// 1001 + n, element ids 501 + e. `typeName` overrides the element type and
// `extraNodes` adds unused nodes at the end.
void writeExodus(const std::string& path, const Mesh& m, const std::string& typeName = "",
                 int extraNodes = 0, const std::vector<ExtraSide>& extraSides = {}) {
  int cpu = 8, io = 8;
  const int exo = ex_create(path.c_str(), EX_CLOBBER, &cpu, &io);
  if (exo < 0) throw std::runtime_error("ex_create failed for " + path);
  const int numNodes = m.numNodes() + extraNodes;
  std::map<std::string, std::vector<std::pair<int, int>>> sideSets;
  // Cells in body order: the element of each cell.
  std::vector<int> order, elementOf(m.numCells());
  for (int b = 0; b < m.numBodies(); ++b)
    for (int c = 0; c < m.numCells(); ++c)
      if (m.bodyOf(c) == b) elementOf[c] = static_cast<int>(order.size()) + 1, order.push_back(c);
  for (const auto& [name, facets] : m.faces)
    for (const Facet& f : facets) sideSets[name].push_back({elementOf[f.cell], sideOf(m, f.cell, f.nodes)});
  for (const auto& s : extraSides) sideSets[s.set].push_back({s.element, s.side});
  ex_put_init(exo, "tribos test", 3, numNodes, m.numCells(), m.numBodies(), m.nodeSets.size(), sideSets.size());
  std::vector<double> x, y, z;
  for (const auto& p : m.coords) x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
  for (int k = 0; k < extraNodes; ++k) x.push_back(9), y.push_back(9), z.push_back(9 + k);
  ex_put_coord(exo, x.data(), y.data(), z.data());
  std::vector<int> nodeIds(numNodes), elemIds(m.numCells());
  for (int n = 0; n < numNodes; ++n) nodeIds[n] = 1001 + n;
  for (int e = 0; e < m.numCells(); ++e) elemIds[e] = 501 + e;
  ex_put_id_map(exo, EX_NODE_MAP, nodeIds.data());
  ex_put_id_map(exo, EX_ELEM_MAP, elemIds.data());
  const std::string type = !typeName.empty() ? typeName : m.type == CellType::Tet4 ? "TETRA" : "HEX8";
  for (int b = 0; b < m.numBodies(); ++b) {
    std::vector<int> conn;
    for (int c : order)
      if (m.bodyOf(c) == b)
        for (int a = 0; a < m.nodesPerCell(); ++a) conn.push_back(m.cell(c)[a] + 1);
    const int count = static_cast<int>(conn.size()) / m.nodesPerCell();
    ex_put_block(exo, EX_ELEM_BLOCK, 10 * (b + 1), type.c_str(), count, m.nodesPerCell(), 0, 0, 0);
    ex_put_conn(exo, EX_ELEM_BLOCK, 10 * (b + 1), conn.data(), nullptr, nullptr);
    if (!m.bodyNames.empty() && !m.bodyNames[b].empty()) ex_put_name(exo, EX_ELEM_BLOCK, 10 * (b + 1), m.bodyNames[b].c_str());
  }
  int id = 1;
  for (const auto& [name, sides] : sideSets) {
    std::vector<int> elements, numbers;
    for (const auto& [e, s] : sides) elements.push_back(e), numbers.push_back(s);
    ex_put_set_param(exo, EX_SIDE_SET, id, sides.size(), 0);
    ex_put_set(exo, EX_SIDE_SET, id, elements.data(), numbers.data());
    ex_put_name(exo, EX_SIDE_SET, id, name.c_str());
    ++id;
  }
  id = 101;
  for (const auto& [name, nodes] : m.nodeSets) {
    std::vector<int> oneBased;
    for (int n : nodes) oneBased.push_back(n + 1);
    ex_put_set_param(exo, EX_NODE_SET, id, nodes.size(), 0);
    ex_put_set(exo, EX_NODE_SET, id, oneBased.data(), nullptr);
    if (name.rfind("unnamed", 0) != 0) ex_put_name(exo, EX_NODE_SET, id, name.c_str());
    ++id;
  }
  ex_close(exo);
}

// The message of what readExodus throws, "" when it does not.
std::string readError(const std::string& path) {
  try {
    readExodus(path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// Two boxes, [0,2]x[0,1]x[0,1] of 4x2x2 cells ("lower") and
// [0,1]x[0,1]x[1.5,2.5] of 2x2x2 ("" : unnamed) above it, distinct nodes;
// faces: the lower box's zmin and zmax, the upper one's zmin; node sets.
Mesh twoBodies(CellType type) {
  BoxSpec a, b;
  a.type = b.type = type;
  a.x = {0, 2};
  a.cells = {4, 2, 2};
  b.z = {1.5, 2.5};
  b.cells = {2, 2, 2};
  Mesh m = generateBox(a);
  const Mesh mb = generateBox(b);
  const int nodeOffset = m.numNodes(), cellOffset = m.numCells();
  m.coords.insert(m.coords.end(), mb.coords.begin(), mb.coords.end());
  for (int n : mb.connectivity) m.connectivity.push_back(n + nodeOffset);
  m.cellBody.assign(m.numCells(), 0);
  std::fill(m.cellBody.begin() + cellOffset, m.cellBody.end(), 1);
  m.bodyNames = {"lower", ""};
  std::map<std::string, std::vector<Facet>> faces = {{"base", m.faces["zmin"]}, {"lower_top", m.faces["zmax"]}};
  for (Facet f : mb.face("zmin")) {
    for (int& n : f.nodes) n += nodeOffset;
    f.cell += cellOffset;
    faces["upper_bottom"].push_back(f);
  }
  m.faces = faces;
  m.nodeSets["corner"] = {0, nodeOffset};
  m.nodeSets["unnamed"] = {nodeOffset + 1, 3, 2};
  return m;
}

void roundTrip(CellType type, Teuchos::FancyOStream& out, bool& success) {
  const Mesh m = twoBodies(type);
  const std::string file = scratch(type == CellType::Tet4 ? "tet.exo" : "hex.exo");
  writeExodus(file, m);
  std::vector<std::string> warnings;
  const Mesh r = readExodus(file, &warnings);
  std::remove(file.c_str());
  TEST_EQUALITY(warnings.size(), 0u);
  TEST_ASSERT(r.type == type);
  TEST_ASSERT(r.coords == m.coords);
  TEST_ASSERT(r.connectivity == m.connectivity);
  TEST_ASSERT(r.cellBody == m.cellBody);
  TEST_ASSERT(r.bodyNames == (std::vector<std::string>{"lower", "block_20"}));
  TEST_ASSERT(r.faceNames() == (std::vector<std::string>{"base", "lower_top", "upper_bottom"}));
  for (const auto& name : r.faceNames()) {
    const auto &got = r.face(name), &want = m.face(name);
    bool same = got.size() == want.size();
    for (size_t k = 0; same && k < got.size(); ++k) same = got[k].cell == want[k].cell && got[k].nodes == want[k].nodes;
    out << name << ": " << got.size() << " facets\n";
    TEST_ASSERT(same);
  }
  TEST_EQUALITY(r.faceBody("lower_top"), 0);
  TEST_EQUALITY(r.faceBody("upper_bottom"), 1);
  TEST_ASSERT(r.nodeSetNames() == (std::vector<std::string>{"corner", "nodeset_102"}));
  TEST_ASSERT(r.nodeSets.at("corner") == (std::vector<int>{0, 45}));
  TEST_ASSERT(r.nodeSets.at("nodeset_102") == (std::vector<int>{2, 3, 46}));
  TEST_ASSERT(r.faceNodes("nodeset_102") == (std::vector<int>{2, 3, 46}));
  double volume = 0, upper = 0;
  for (int c = 0; c < r.numCells(); ++c) {
    volume += cellVolume(r, c);
    if (r.bodyOf(c) == 1) upper += cellVolume(r, c);
  }
  TEST_FLOATING_EQUALITY(volume, 3.0, 1e-12);
  TEST_FLOATING_EQUALITY(upper, 1.0, 1e-12);
  // Facets counter-clockwise seen from outside: base down, the tops up, the
  // upper body's bottom down.
  for (const auto& [name, nz] : std::map<std::string, double>{{"base", -1}, {"lower_top", 1}, {"upper_bottom", -1}}) {
    double area = 0;
    bool outward = true;
    for (const Facet& f : r.face(name)) {
      const P a = areaVector(r, f);
      area += a[2] * nz;
      outward = outward && a[2] * nz > 0 && std::abs(a[0]) + std::abs(a[1]) < 1e-12;
    }
    out << name << " area " << area << "\n";
    TEST_ASSERT(outward);
    TEST_FLOATING_EQUALITY(area, name == "upper_bottom" ? 1.0 : 2.0, 1e-12);
  }
}

// One unit cell, Exodus order, with every side in its own side set: the
// manual's sides land on the planes they name.
void referenceSides(CellType type, Teuchos::FancyOStream& out, bool& success) {
  BoxSpec spec;
  spec.type = CellType::Hex8;
  Mesh m = generateBox(spec);
  if (type == CellType::Tet4) {
    m.type = CellType::Tet4;
    m.coords = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.connectivity = {0, 1, 2, 3};
  }
  m.faces.clear();
  const int numSides = type == CellType::Tet4 ? 4 : 6;
  std::vector<ExtraSide> sides;
  for (int s = 1; s <= numSides; ++s) sides.push_back({"side" + std::to_string(s), 1, s});
  const std::string file = scratch("reference.exo");
  writeExodus(file, m, "", 0, sides);
  const Mesh r = readExodus(file);
  std::remove(file.c_str());
  // Outward normal of each Exodus side (tet: y = 0, the slanted face, x = 0, z = 0;
  // hex: y = 0, x = 1, y = 1, x = 0, z = 0, z = 1).
  const double k = 1 / std::sqrt(3.0);
  const std::vector<P> normals = type == CellType::Tet4
                                     ? std::vector<P>{{0, -1, 0}, {k, k, k}, {-1, 0, 0}, {0, 0, -1}}
                                     : std::vector<P>{{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int s = 1; s <= numSides; ++s) {
    const auto& face = r.face("side" + std::to_string(s));
    TEST_EQUALITY(face.size(), 1u);
    if (face.size() != 1) continue;
    const P a = areaVector(r, face[0]);
    const double len = std::sqrt(dot(a, a));
    out << "side " << s << ": normal " << a[0] / len << " " << a[1] / len << " " << a[2] / len << "\n";
    TEST_FLOATING_EQUALITY(dot(a, normals[s - 1]), len, 1e-12);
  }
}

}  // namespace

TEUCHOS_UNIT_TEST(Exodus, RoundTripHex8) { roundTrip(CellType::Hex8, out, success); }

TEUCHOS_UNIT_TEST(Exodus, RoundTripTet4) { roundTrip(CellType::Tet4, out, success); }

TEUCHOS_UNIT_TEST(Exodus, ReferenceSidesHex8) { referenceSides(CellType::Hex8, out, success); }

TEUCHOS_UNIT_TEST(Exodus, ReferenceSidesTet4) { referenceSides(CellType::Tet4, out, success); }

TEUCHOS_UNIT_TEST(Exodus, ReadMeshFileByExtension) {
  const Mesh m = twoBodies(CellType::Hex8);
  for (const std::string ext : {".e", ".EXO", ".g", ".ex2"}) {
    const std::string file = scratch("dispatch" + ext);
    writeExodus(file, m);
    const Mesh r = readMeshFile(file);
    std::remove(file.c_str());
    TEST_EQUALITY(r.numCells(), m.numCells());
    TEST_EQUALITY(r.numBodies(), 2);
  }
}

TEUCHOS_UNIT_TEST(Exodus, UnusedNodesDropped) {
  const Mesh m = twoBodies(CellType::Tet4);
  const std::string file = scratch("unused.exo");
  writeExodus(file, m, "", 2);
  std::vector<std::string> warnings;
  const Mesh r = readExodus(file, &warnings);
  std::remove(file.c_str());
  TEST_EQUALITY(r.numNodes(), m.numNodes());
  TEST_EQUALITY(warnings.size(), 1u);
  if (!warnings.empty()) {
    out << warnings[0] << "\n";
    TEST_ASSERT(contains(warnings[0], "unused.exo") &&
                contains(warnings[0], "2 of its 74 nodes belong to no 3D element and are dropped (the first: node 1073)"));
  }
}

TEUCHOS_UNIT_TEST(Exodus, RefusedElements) {
  Mesh m = twoBodies(CellType::Tet4);
  const std::string file = scratch("refused.exo");
  // Quadratic tetrahedra (10 nodes a cell) whose mid-edge nodes are corners.
  {
    Mesh tet10 = m;
    std::vector<int> conn;
    for (int c = 0; c < m.numCells(); ++c) {
      conn.insert(conn.end(), m.cell(c), m.cell(c) + 4);
      for (int k = 0; k < 6; ++k) conn.push_back(m.cell(c)[k % 4]);
    }
    int cpu = 8, io = 8;
    const int exo = ex_create(file.c_str(), EX_CLOBBER, &cpu, &io);
    ex_put_init(exo, "tet10", 3, m.numNodes(), m.numCells(), 1, 0, 0);
    std::vector<double> x, y, z;
    for (const auto& p : m.coords) x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
    ex_put_coord(exo, x.data(), y.data(), z.data());
    ex_put_block(exo, EX_ELEM_BLOCK, 7, "TETRA", m.numCells(), 10, 0, 0, 0);
    for (int& n : conn) ++n;
    ex_put_conn(exo, EX_ELEM_BLOCK, 7, conn.data(), nullptr, nullptr);
    ex_put_name(exo, EX_ELEM_BLOCK, 7, "shaft");
    ex_close(exo);
  }
  std::string e = readError(file);
  out << e << "\n";
  // (read as Tet10 cells, whose mid-edge nodes here are corners: refused,
  // named with the block)
  TEST_ASSERT(contains(e, "refused.exo") && contains(e, "(Tet10) of block 'shaft'"));
  // Inverted: cell 5 (element id 506) turned inside out.
  std::swap(m.connectivity[5 * 4 + 1], m.connectivity[5 * 4 + 2]);
  writeExodus(file, m);
  e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "refused.exo") && contains(e, "1 inverted or degenerate element (non-positive volume): element 506"));
  std::swap(m.connectivity[5 * 4 + 1], m.connectivity[5 * 4 + 2]);
  // Two blocks of one name.
  m.bodyNames = {"part", "part"};
  writeExodus(file, m);
  e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "two element blocks are named 'part' (ids 10 and 20)"));
  std::remove(file.c_str());
}

TEUCHOS_UNIT_TEST(Exodus, RefusedSets) {
  // Hexahedra: element 1's side 6 (top) is inside the lower box.
  const Mesh m = twoBodies(CellType::Hex8);
  const std::string file = scratch("sets.exo");
  writeExodus(file, m, "", 0, {{"inner", 1, 6}});
  std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "sets.exo") && contains(e, "side set 'inner' is not on the boundary (element 501 side 6)"));
  writeExodus(file, m, "", 0, {{"bad", 1, 7}});
  e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "side set 'bad' names side 7 of element 501; a Hex8 has sides 1 to 6"));
  // A node set of a node no element uses.
  Mesh extra = m;
  extra.nodeSets["far"] = {extra.numNodes()};
  writeExodus(file, extra, "", 1);
  e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "node set 'far' holds node 1073, which belongs to no element"));
  std::remove(file.c_str());
}

TEUCHOS_UNIT_TEST(Exodus, BrokenFiles) {
  std::string e = readError(scratch("no_such.exo"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "cannot open mesh file") && contains(e, "no_such.exo") && contains(e, "No such file"));

  const std::string garbage = scratch("garbage.exo");
  std::ofstream(garbage) << "this is not a mesh\n";
  e = readError(garbage);
  out << e << "\n";
  TEST_ASSERT(contains(e, "garbage.exo") && contains(e, "is not an Exodus II file the Exodus library can read"));
  std::remove(garbage.c_str());

  // Truncated: the first half of a good file.
  const std::string good = scratch("good.exo"), truncated = scratch("truncated.exo");
  writeExodus(good, twoBodies(CellType::Hex8));
  {
    std::ifstream in(good, std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << all.substr(0, all.size() / 2);
  }
  e = readError(truncated);
  out << e << "\n";
  // NetCDF reads what is missing as zeros (Debian 12's: the node numbers are
  // refused) or fails.
  TEST_ASSERT(contains(e, "truncated.exo") && (contains(e, "names node 0; the file's nodes are 1 to 72") ||
                                               contains(e, "cannot read") || contains(e, "is not an Exodus II file")));
  std::remove(good.c_str());
  std::remove(truncated.c_str());

  e = readError("/tmp");
  out << e << "\n";
  TEST_ASSERT(contains(e, "mesh file \"/tmp\" is a directory"));
}

TEUCHOS_UNIT_TEST(Exodus, UnusableCoordinates) {
  // Node 1004 (the fourth) at a coordinate the geometry cannot compute
  // with: named with its value before any cell is checked.
  const Mesh good = twoBodies(CellType::Hex8);
  const std::string file = scratch("coordinates.exo");
  const std::vector<std::pair<double, std::string>> bad = {
      {std::nan(""), "node 1004 has coordinate y = nan; coordinates must be finite numbers"},
      {1e300, "node 1004 has coordinate y = 1e+300, beyond the 1e+50 a coordinate may have"},
      {-1e100, "node 1004 has coordinate y = -1e+100, beyond the 1e+50"}};
  for (const auto& [value, message] : bad) {
    Mesh m = good;
    m.coords[3][1] = value;
    writeExodus(file, m);
    const std::string e = readError(file);
    out << e << "\n";
    TEST_ASSERT(contains(e, "coordinates.exo") && contains(e, message));
  }
  // A mesh 2.5e-60 across: its volumes (1e-180) and squared areas would
  // vanish in round-off.
  Mesh tiny = good;
  for (auto& p : tiny.coords)
    for (double& x : p) x *= 1e-60;
  writeExodus(file, tiny);
  std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "the mesh spans 2.5e-60 (the largest side of its bounding box), less than the 1e-50"));
  // The same mesh at 1e-40 and at 1e40 is read.
  for (double scale : {1e-40, 1e40}) {
    Mesh scaled = good;
    for (auto& p : scaled.coords)
      for (double& x : p) x *= scale;
    writeExodus(file, scaled);
    TEST_EQUALITY(readError(file), "");
  }
  std::remove(file.c_str());
}

TEUCHOS_UNIT_TEST(Exodus, HeaderCountsBeyondTheMemoryLimit) {
  // A header is believed only as far as the memory the read may use: the
  // arrays it sizes are not allocated beyond it.
  const std::string file = scratch("counts.exo");
  writeExodus(file, twoBodies(CellType::Hex8));
  MeshFileOptions options;
  options.memoryLimit = 1000;  // bytes: less than 72 nodes and 24 elements need
  std::string e;
  try {
    readExodus(file, nullptr, options);
  } catch (const std::exception& ex) {
    e = ex.what();
  }
  out << e << "\n";
  TEST_ASSERT(contains(e, "counts.exo") && contains(e, "declares 72 nodes and 24 elements, whose arrays need about") &&
              contains(e, "the read may use"));
  options.memoryLimit = 1e6;
  TEST_EQUALITY(readExodus(file, nullptr, options).numNodes(), 72);
  std::remove(file.c_str());
}
