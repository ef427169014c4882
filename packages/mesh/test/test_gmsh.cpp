// The Gmsh reader: the shipped block (.msh, ASCII and binary made at test
// time), a .geo meshed at run time (Hex8; allowed explicitly, meshed by the
// gmsh program in a child process), and the files it must refuse: broken,
// inverted, mixed, coordinates the geometry cannot use, node tags given twice.
#include <Teuchos_UnitTestHarness.hpp>

#include <gmsh.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

#include "Tribos_GmshReader.hpp"
#include "MeshTestGeometry.hpp"

#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos::Mesh;
using namespace Tribos::Mesh::Test;

std::string dataFile(const std::string& name) { return sourceDir() + "/packages/mesh/test/data/" + name; }
std::string blockMsh() { return sourceDir() + "/input/gmsh_block.msh"; }

std::string scratch(const std::string& name) {
  return "/tmp/tribos_gmsh_test_" + std::to_string(getpid()) + "_" + name;
}

P centroid(const Mesh& m, int c) {
  P s{0, 0, 0};
  for (int a = 0; a < m.nodesPerCell(); ++a)
    for (int d = 0; d < 3; ++d) s[d] += m.coords[m.cell(c)[a]][d] / m.nodesPerCell();
  return s;
}

// Checks a face: its total area, that every facet's area vector is the
// given outward normal times its area, and belongs to its cell.
void checkFace(const Mesh& m, const std::string& name, double area, const std::vector<P>& normals,
               Teuchos::FancyOStream& out, bool& success) {
  double total = 0;
  bool outward = true, ofCell = true;
  for (const Facet& f : m.face(name)) {
    const P a = areaVector(m, f);
    const double len = std::sqrt(dot(a, a));
    total += len;
    bool match = false;
    for (const P& n : normals) match = match || std::abs(dot(a, n) - len) < 1e-12 * std::max(len, 1e-300);
    // The facet lies on the far side of its cell's centroid.
    outward = outward && match && dot(a, sub(m.coords[f.nodes[0]], centroid(m, f.cell))) > 0;
    const std::set<int> cellNodes(m.cell(f.cell), m.cell(f.cell) + m.nodesPerCell());
    for (int n : f.nodes) ofCell = ofCell && cellNodes.count(n) == 1;
  }
  out << name << ": area " << total << "\n";
  TEST_FLOATING_EQUALITY(total, area, 1e-12);
  TEST_ASSERT(outward);  // counter-clockwise seen from outside
  TEST_ASSERT(ofCell);
}

void checkBlock(const Mesh& m, Teuchos::FancyOStream& out, bool& success) {
  TEST_ASSERT(m.type == CellType::Tet4);
  TEST_COMPARE(m.numCells(), >, 100);
  double vol = 0;
  bool positive = true;
  for (int c = 0; c < m.numCells(); ++c) positive = positive && cellVolume(m, c) > 0, vol += cellVolume(m, c);
  TEST_ASSERT(positive);
  TEST_FLOATING_EQUALITY(vol, 1.0, 1e-12);
  TEST_ASSERT(m.faceNames() == (std::vector<std::string>{"bottom", "sides", "symmetry_x", "symmetry_y", "top"}));
  checkFace(m, "bottom", 1.0, {{0, 0, -1}}, out, success);
  checkFace(m, "top", 1.0, {{0, 0, 1}}, out, success);
  checkFace(m, "symmetry_x", 1.0, {{-1, 0, 0}}, out, success);
  checkFace(m, "symmetry_y", 1.0, {{0, -1, 0}}, out, success);
  checkFace(m, "sides", 2.0, {{1, 0, 0}, {0, 1, 0}}, out, success);
  // Every node is a cell node (Gmsh's geometry points are dropped or used).
  std::vector<char> used(m.numNodes(), 0);
  for (int n : m.connectivity) used[n] = 1;
  TEST_EQUALITY(std::count(used.begin(), used.end(), 0), 0);
}

// A .geo is a program: the tests that mesh one say so.
MeshFileOptions allowGeo() {
  MeshFileOptions options;
  options.runGeoScript = true;
  return options;
}

// The message of what readGmsh throws, "" when it does not.
std::string readError(const std::string& path, const MeshFileOptions& options = MeshFileOptions()) {
  try {
    readGmsh(path, nullptr, options);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

using Tribos::Test::contains;

TEUCHOS_UNIT_TEST(Gmsh, ShippedBlock) {
  std::vector<std::string> warnings;
  const Mesh m = readGmsh(blockMsh(), &warnings);
  out << m.numNodes() << " nodes, " << m.numCells() << " cells\n";
  checkBlock(m, out, success);
  TEST_EQUALITY(m.numCells(), 1125);  // the shipped file's tetrahedra
  TEST_EQUALITY(warnings.size(), 0u);
  // The counts of the file itself: its $Nodes and $Elements of the volume.
  std::ifstream in(blockMsh());
  std::string line;
  while (std::getline(in, line) && line != "$Nodes") {}
  long long blocks = 0, nodes = 0;
  in >> blocks >> nodes;
  TEST_EQUALITY(static_cast<long long>(m.numNodes()), nodes);
}

TEUCHOS_UNIT_TEST(Gmsh, BinaryAndReadersInSequence) {
  // The same mesh written in binary by Gmsh; two readers in sequence, each
  // initializing and finalizing Gmsh, agree.
  const std::string bin = scratch("block_bin.msh");
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(blockMsh());
  gmsh::option::setNumber("Mesh.Binary", 1);
  gmsh::write(bin);
  gmsh::finalize();
  const Mesh a = readGmsh(blockMsh()), b = readGmsh(bin);
  std::remove(bin.c_str());
  checkBlock(b, out, success);
  TEST_ASSERT(a.connectivity == b.connectivity);
  TEST_ASSERT(a.coords == b.coords);
}

TEUCHOS_UNIT_TEST(Gmsh, GeoMeshedAtRunTimeHex8) {
  const Mesh m = readGmsh(dataFile("hex_block.geo"), nullptr, allowGeo());
  TEST_ASSERT(m.type == CellType::Hex8);
  TEST_EQUALITY(m.numCells(), 4 * 2 * 2);
  TEST_EQUALITY(m.numNodes(), 5 * 3 * 3);
  double vol = 0;
  for (int c = 0; c < m.numCells(); ++c) vol += cellVolume(m, c);
  TEST_FLOATING_EQUALITY(vol, 2.0, 1e-12);
  TEST_ASSERT(m.faceNames() == (std::vector<std::string>{"bottom", "clamp", "front", "top"}));
  checkFace(m, "bottom", 2.0, {{0, 0, -1}}, out, success);
  checkFace(m, "top", 2.0, {{0, 0, 1}}, out, success);
  checkFace(m, "clamp", 1.0, {{-1, 0, 0}}, out, success);
  checkFace(m, "front", 2.0, {{0, -1, 0}}, out, success);
  const BoxSpec box = boundingBox(m);
  TEST_ASSERT(box.x == (std::array<double, 2>{0, 2}) && box.y == (std::array<double, 2>{0, 1}) &&
              box.z == (std::array<double, 2>{0, 1}));
}

TEUCHOS_UNIT_TEST(Gmsh, GeoTetBlock) {
  // The shipped .geo itself, meshed here.
  const Mesh m = readGmsh(sourceDir() + "/input/gmsh_block.geo", nullptr, allowGeo());
  checkBlock(m, out, success);
}

TEUCHOS_UNIT_TEST(Gmsh, RefusedFiles) {
  std::string e = readError(scratch("no_such.msh"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "cannot open mesh file") && contains(e, "no_such.msh") && contains(e, "No such file"));

  // Truncated: the first 3000 bytes of the block.
  const std::string truncated = scratch("truncated.msh");
  {
    std::ifstream in(blockMsh(), std::ios::binary);
    std::string head(3000, '\0');
    in.read(&head[0], 3000);
    std::ofstream(truncated, std::ios::binary) << head;
  }
  e = readError(truncated);
  out << e << "\n";
  TEST_ASSERT(contains(e, "truncated.msh") && contains(e, "is not a mesh Gmsh can read"));
  std::remove(truncated.c_str());

  const std::string garbage = scratch("garbage.msh");
  std::ofstream(garbage) << "this is not a mesh\n";
  e = readError(garbage);
  out << e << "\n";
  TEST_ASSERT(contains(e, "garbage.msh") && contains(e, "is not a Gmsh mesh"));
  std::remove(garbage.c_str());

  // Second order is read (test_quadratic_read.cpp); an element of order 3 is not.
  TEST_ASSERT(readGmsh(dataFile("second_order.geo"), nullptr, allowGeo()).type == CellType::Tet10);
  e = readError(dataFile("third_order.geo"), allowGeo());
  out << e << "\n";
  TEST_ASSERT(contains(e, "third_order.geo") && contains(e, "(Tet20) in physical volume 'shaft' is not supported (elements "
                                                           "of order 3 or more are not supported"));

  e = readError(dataFile("interior_surface.geo"), allowGeo());
  out << e << "\n";
  TEST_ASSERT(contains(e, "interior_surface.geo") && contains(e, "surface 'middle' is not on the boundary (facet "));
}

// A hand-written file: tetrahedron 1 is inverted, node 5 belongs to no element.
const char* kInverted =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
    "$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 5 5\n$EndNodes\n"
    "$Elements\n1 2 1 2\n3 1 4 2\n1 1 3 2 4\n2 1 2 3 4\n$EndElements\n";

TEUCHOS_UNIT_TEST(Gmsh, InvertedElementsAndUnusedNodes) {
  const std::string file = scratch("inverted.msh");
  std::ofstream(file) << kInverted;
  const std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "inverted.msh") && contains(e, "1 inverted or degenerate element (non-positive volume): element 1"));
  // The same with the element turned right: read, node 5 dropped with a warning.
  std::string fixed = kInverted;
  fixed.replace(fixed.find("1 1 3 2 4"), 9, "1 1 2 3 4");
  std::ofstream(file) << fixed;
  std::vector<std::string> warnings;
  const Mesh m = readGmsh(file, &warnings);
  TEST_EQUALITY(m.numNodes(), 4);
  TEST_EQUALITY(m.numCells(), 2);
  TEST_EQUALITY(warnings.size(), 1u);
  if (!warnings.empty()) {
    out << warnings[0] << "\n";
    TEST_ASSERT(contains(warnings[0], "1 of its 5 nodes belong to no 3D element and are dropped (the first: node 5)"));
  }
  std::remove(file.c_str());
}

// A hand-written file with a tetrahedron in volume 1 and a hexahedron in
// volume 2, without physical volumes: one body, which has one cell type.
const char* kMixed =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 0 0\n2 0 0 0 1 1 1 0 0\n$EndEntities\n"
    "$Nodes\n1 8 1 8\n3 1 0 8\n1\n2\n3\n4\n5\n6\n7\n8\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n$EndNodes\n"
    "$Elements\n2 2 1 2\n3 1 4 1\n1 1 2 4 5\n3 2 5 1\n2 1 2 3 4 5 6 7 8\n$EndElements\n";

TEUCHOS_UNIT_TEST(Gmsh, MixedCellTypes) {
  const std::string file = scratch("mixed.msh");
  std::ofstream(file) << kMixed;
  const std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "mixed.msh") && contains(e, "the mesh (one body: it names no physical volumes) mixes Tet4 "
                                                     "(volume 1) and Hex8 (volume 2, element 2 (Hex8)); a body holds "
                                                     "cells of one type"));
  std::remove(file.c_str());
}

// One tetrahedron of nodes 1-4 at `corners` and an unused node 5; with
// `again`, a sixth node record whose tag is 2 again, at `again`.
std::string oneTet(const std::vector<std::string>& corners, const std::string& again = "") {
  const std::string count = again.empty() ? "5" : "6";
  std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n";
  text += "$Nodes\n1 " + count + " 1 5\n3 1 0 " + count + "\n1\n2\n3\n4\n5\n" + (again.empty() ? "" : "2\n");
  for (const auto& c : corners) text += c + "\n";
  text += "5 5 5\n" + (again.empty() ? "" : again + "\n") + "$EndNodes\n";
  return text + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
}
std::string oneTet(const std::string& x2, const std::string& again = "") {
  return oneTet({"0 0 0", x2, "0 1 0", "0 0 1"}, again);
}

TEUCHOS_UNIT_TEST(Gmsh, UnusableCoordinates) {
  const std::string file = scratch("coordinates.msh");
  std::ofstream(file) << oneTet("1 0 0");
  TEST_EQUALITY(readError(file), "");  // the file itself is good
  // Named with the node and the value before any cell is checked (1e300 was
  // "inverted or degenerate", 1e100 a face "not planar").
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"1e300 0 0", "node 2 has coordinate x = 1e+300, beyond the 1e+50 a coordinate may have"},
      {"1 1e100 0", "node 2 has coordinate y = 1e+100, beyond the 1e+50"},
      {"1 0 -1e51", "node 2 has coordinate z = -1e+51, beyond the 1e+50"}};
  for (const auto& [x2, message] : bad) {
    std::ofstream(file) << oneTet(x2);
    const std::string e = readError(file);
    out << e << "\n";
    TEST_ASSERT(contains(e, "coordinates.msh") && contains(e, message));
  }
  // NaN: Gmsh's own parser may refuse it first; either way, by name.
  std::ofstream(file) << oneTet("nan 0 0");
  std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "coordinates.msh") && !contains(e, "degenerate"));
  // The tetrahedron 1e-51 across.
  std::ofstream(file) << oneTet({"0 0 0", "1e-51 0 0", "0 1e-51 0", "0 0 1e-51"});
  e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "the mesh spans 1e-51 (the largest side of its bounding box), less than the 1e-50"));
  std::remove(file.c_str());
}

TEUCHOS_UNIT_TEST(Gmsh, NodeTagTwice) {
  // Gmsh keeps both records of tag 2 and resolves the tag to one of them:
  // refused naming both coordinates.
  const std::string file = scratch("twice.msh");
  std::ofstream(file) << oneTet("1 0 0", "1 0 0.5");
  std::string e = readError(file);
  out << e << "\n";
  TEST_ASSERT(contains(e, "twice.msh") && contains(e, "node 2 is defined twice, at (1, 0, 0) and at (1, 0, 0.5)"));
  // The same node written twice is one node: read, no warning (node 5 is
  // the one unused node).
  std::ofstream(file) << oneTet("1 0 0", "1 0 0");
  std::vector<std::string> warnings;
  const Mesh m = readGmsh(file, &warnings);
  TEST_EQUALITY(m.numNodes(), 4);
  TEST_EQUALITY(warnings.size(), 1u);
  if (!warnings.empty()) TEST_ASSERT(contains(warnings[0], "1 of its 5 nodes belong to no 3D element"));
  std::remove(file.c_str());
}

}  // namespace
