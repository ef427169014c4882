// Several bodies in one mesh: the accessors on box meshes and hand-made
// meshes, node sets, bodies read from Gmsh .geo files written here (two
// boxes one above the other: separate volumes, and a conformal variant that
// shares the interface nodes), and the METIS decomposition body by body.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <unistd.h>

#include "Tribos_Decomposition.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_GmshReader.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_MeshFile.hpp"

#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos::Mesh;

using Tribos::Test::contains;
using Tribos::Test::errorOf;

std::string scratch(const std::string& name) {
  return "/tmp/tribos_bodies_test_" + std::to_string(getpid()) + "_" + name;
}

// Writes a .geo script, reads it (a program: allowed here, meshed by Gmsh
// in a child process), removes it.
Mesh readGeo(const std::string& name, const std::string& text) {
  const std::string path = scratch(name);
  std::ofstream(path) << text;
  struct Remove {
    std::string p;
    ~Remove() { std::remove(p.c_str()); }
  } remove{path};
  MeshFileOptions options;
  options.runGeoScript = true;
  return readGmsh(path, nullptr, options);
}
std::string geoError(const std::string& name, const std::string& text) { return errorOf([&] { readGeo(name, text); }); }

double cellVolume(const Mesh& m, int c) {
  const int* n = m.cell(c);
  auto tet = [&](int a, int b, int d, int e) {
    const auto &p = m.coords[n[a]], &q = m.coords[n[b]], &r = m.coords[n[d]], &s = m.coords[n[e]];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]},
                 w[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
  };
  if (m.type == CellType::Tet4) return tet(0, 1, 2, 3);
  return tet(0, 1, 2, 6) + tet(0, 2, 3, 6) + tet(0, 3, 7, 6) + tet(0, 7, 4, 6) + tet(0, 4, 5, 6) + tet(0, 5, 1, 6);
}

std::vector<double> bodyVolumes(const Mesh& m) {
  std::vector<double> v(m.numBodies(), 0);
  for (int c = 0; c < m.numCells(); ++c) v[m.bodyOf(c)] += cellVolume(m, c);
  return v;
}

std::vector<int> bodyCellCounts(const Mesh& m) {
  std::vector<int> n(m.numBodies(), 0);
  for (int c = 0; c < m.numCells(); ++c) ++n[m.bodyOf(c)];
  return n;
}

// Box 2x1x1 (hexahedra 2x2x2) under box 1x1x1 (3x3x3) on top of it, two
// OpenCASCADE volumes not fragmented together: distinct nodes on z = 1. The
// physical volumes are declared upper first, ordered by tag: lower, upper.
const char* kSeparate = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
Transfinite Curve{Unique(Abs(Boundary{Boundary{Volume{1};}}))} = 3;
Transfinite Curve{Unique(Abs(Boundary{Boundary{Volume{2};}}))} = 4;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
s1[] = Abs(Boundary{Volume{1};});
s2[] = Abs(Boundary{Volume{2};});
Physical Surface("lower_top") = {s1[5]};
Physical Surface("upper_bottom") = {s2[4]};
Physical Surface("x0") = {s1[0], s2[0]};
)";

std::string separate(const std::string& volumes) { return std::string(kSeparate) + volumes; }
const std::string kTwoBodies = "Physical Volume(\"upper\", 2) = {2};\nPhysical Volume(\"lower\", 1) = {1};\n";

// The same boxes fragmented: one mesh with shared nodes on the interface;
// tetrahedra; the upper body's physical volume has no name (tag 5).
const char* kConformal = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
eps = 1e-6;
Physical Volume(5) = Volume In BoundingBox{-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 2 + eps};
Physical Volume("lower", 3) = Volume In BoundingBox{-eps, -eps, -eps, 2 + eps, 1 + eps, 1 + eps};
Mesh.MeshSizeMax = 0.5;
)";

// Two tetrahedra in two volumes, physical volumes 1 and 2 both named "a".
const char* kSameName =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n2\n3 1 \"a\"\n3 2 \"a\"\n$EndPhysicalNames\n"
    "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 1 1 0\n2 0 0 0 1 1 1 1 2 0\n$EndEntities\n"
    "$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n"
    "$Elements\n2 2 1 2\n3 1 4 1\n1 1 2 3 4\n3 2 4 1\n2 2 3 4 5\n$EndElements\n";

// Two hexahedral boxes side by side along x as one mesh of two bodies with
// distinct nodes: n0 and n1 cells along x, 2 x 2 in y and z.
Mesh twoBoxes(int n0, int n1, int ny = 2) {
  BoxSpec a, b;
  a.cells = {n0, ny, ny};
  a.x = {0, 1};
  b.cells = {n1, ny, ny};
  b.x = {1.5, 2.5};
  Mesh m = generateBox(a);
  const Mesh mb = generateBox(b);
  const int offset = m.numNodes();
  m.coords.insert(m.coords.end(), mb.coords.begin(), mb.coords.end());
  for (int n : mb.connectivity) m.connectivity.push_back(n + offset);
  m.cellBody.assign(m.numCells(), 1);
  std::fill(m.cellBody.begin(), m.cellBody.begin() + a.cells[0] * ny * ny, 0);
  m.bodyNames = {"left", "right"};
  m.faces.clear();
  for (Facet f : mb.face("xmin")) {
    for (int& n : f.nodes) n += offset;
    f.cell += a.cells[0] * ny * ny;
    m.faces["right_xmin"].push_back(f);
  }
  m.faces["left_xmax"] = generateBox(a).face("xmax");
  return m;
}

}  // namespace

TEUCHOS_UNIT_TEST(Bodies, BoxIsOneBody) {
  BoxSpec spec;
  spec.cells = {2, 2, 2};
  const Mesh m = generateBox(spec);
  TEST_EQUALITY(m.numBodies(), 1);
  TEST_EQUALITY(m.bodyOf(5), 0);
  TEST_EQUALITY(m.bodyName(0), "body");
  TEST_EQUALITY(m.bodyIndex("body"), 0);
  TEST_EQUALITY(m.faceBody("zmax"), 0);
  TEST_NOTHROW(m.checkBodies());
  const std::string e = errorOf([&] { m.bodyIndex("shaft"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "no body named \"shaft\"; valid bodies: body"));
  TEST_ASSERT(contains(errorOf([&] { m.bodyName(1); }), "body 1 out of range"));
}

TEUCHOS_UNIT_TEST(Bodies, NodeSets) {
  BoxSpec spec;
  spec.cells = {2, 2, 2};
  Mesh m = generateBox(spec);
  m.nodeSets["corner"] = {26, 0, 0};
  TEST_ASSERT(m.faceNodes("corner") == (std::vector<int>{0, 26}));  // sorted, unique
  TEST_ASSERT(m.nodeSetNames() == (std::vector<std::string>{"corner"}));
  TEST_EQUALITY(m.faceNames().size(), 6u);  // faces only
  TEST_EQUALITY(m.faceNodes("zmin").size(), 9u);
  std::string e = errorOf([&] { m.face("corner"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "\"corner\" is a node set without facets"));
  e = errorOf([&] { m.faceNodes("edge"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "no face named \"edge\"") && contains(e, "valid faces: xmax, xmin") && contains(e, "node sets: corner"));
  // A face and a node set of one name: the face's nodes.
  m.nodeSets["zmin"] = {1};
  TEST_EQUALITY(m.faceNodes("zmin").size(), 9u);
}

TEUCHOS_UNIT_TEST(Bodies, Accessors) {
  Mesh m = twoBoxes(4, 2);
  TEST_EQUALITY(m.numBodies(), 2);
  TEST_EQUALITY(m.bodyIndex("right"), 1);
  TEST_EQUALITY(m.bodyOf(15), 0);
  TEST_EQUALITY(m.bodyOf(16), 1);
  TEST_EQUALITY(m.faceBody("left_xmax"), 0);
  TEST_EQUALITY(m.faceBody("right_xmin"), 1);
  m.faces["both"] = m.faces["left_xmax"];
  m.faces["both"].push_back(m.faces["right_xmin"].front());
  std::string e = errorOf([&] { m.faceBody("both"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "face \"both\" has facets on bodies \"left\" and \"right\""));
  e = errorOf([&] { m.bodyIndex("middle"); });
  TEST_ASSERT(contains(e, "valid bodies: left, right"));
  m.cellBody[3] = 2;
  e = errorOf([&] { m.checkBodies(); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "cell 3 is in body 2 but the mesh has 2 bodies"));
  m.cellBody.assign(m.numCells(), 0);
  e = errorOf([&] { m.checkBodies(); });
  TEST_ASSERT(contains(e, "body \"right\" has no cells"));
}

TEUCHOS_UNIT_TEST(Bodies, GmshSeparateVolumes) {
  const Mesh m = readGeo("separate.geo", separate(kTwoBodies));
  TEST_ASSERT(m.type == CellType::Hex8);
  TEST_ASSERT(m.bodyNames == (std::vector<std::string>{"lower", "upper"}));  // by tag
  TEST_ASSERT(bodyCellCounts(m) == (std::vector<int>{8, 27}));
  TEST_EQUALITY(m.numNodes(), 27 + 64);  // nothing shared on z = 1
  const auto vol = bodyVolumes(m);
  TEST_FLOATING_EQUALITY(vol[0], 2.0, 1e-12);
  TEST_FLOATING_EQUALITY(vol[1], 1.0, 1e-12);
  // Every cell of "upper" lies above z = 1.
  bool above = true;
  for (int c = 0; c < m.numCells(); ++c)
    for (int a = 0; a < 8; ++a) above = above && (m.bodyOf(c) == 0 || m.coords[m.cell(c)[a]][2] > 1 - 1e-12);
  TEST_ASSERT(above);
  TEST_EQUALITY(m.faceBody("lower_top"), 0);
  TEST_EQUALITY(m.faceBody("upper_bottom"), 1);
  TEST_EQUALITY(m.face("lower_top").size(), 4u);
  TEST_EQUALITY(m.face("upper_bottom").size(), 9u);
  const std::string e = errorOf([&] { m.faceBody("x0"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "face \"x0\" has facets on bodies \"lower\" and \"upper\""));
  // The two contact faces have no node in common.
  const auto a = m.faceNodes("lower_top"), b = m.faceNodes("upper_bottom");
  std::vector<int> common;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  TEST_EQUALITY(common.size(), 0u);
}

TEUCHOS_UNIT_TEST(Bodies, GmshConformalSharesNodes) {
  const Mesh m = readGeo("conformal.geo", kConformal);
  TEST_ASSERT(m.type == CellType::Tet4);
  TEST_ASSERT(m.bodyNames == (std::vector<std::string>{"lower", "5"}));  // tag 3, then the unnamed tag 5
  const auto vol = bodyVolumes(m);
  TEST_FLOATING_EQUALITY(vol[0], 2.0, 1e-12);
  TEST_FLOATING_EQUALITY(vol[1], 1.0, 1e-12);
  // Nodes used by both bodies: on the interface z = 1, 0 <= x <= 1.
  std::vector<int> seen(m.numNodes(), 0);
  for (int c = 0; c < m.numCells(); ++c)
    for (int a = 0; a < 4; ++a) seen[m.cell(c)[a]] |= 1 << m.bodyOf(c);
  int shared = 0;
  bool onInterface = true;
  for (int n = 0; n < m.numNodes(); ++n) {
    if (seen[n] != 3) continue;
    ++shared;
    onInterface = onInterface && std::abs(m.coords[n][2] - 1) < 1e-12 && m.coords[n][0] < 1 + 1e-12;
  }
  out << shared << " shared nodes\n";
  TEST_COMPARE(shared, >=, 9);
  TEST_ASSERT(onInterface);
  // Bonded bodies: METIS still keeps each subdomain in one body.
  const Discretization d(m, boundingBox(m), DecompositionSpec{"METIS", {1, 1, 1}, 3}, 1, 0);
  TEST_ASSERT(d.subdomainBody == (std::vector<int>{0, 0, 1}));
}

TEUCHOS_UNIT_TEST(Bodies, GmshRefusals) {
  std::string e = geoError("twice.geo", separate("Physical Volume(\"a\", 1) = {1};\nPhysical Volume(\"b\", 2) = {1, 2};\n"));
  out << e << "\n";
  TEST_ASSERT(contains(e, "twice.geo") &&
              contains(e, "the elements of volume 1 are in physical volume 'a' and physical volume 'b'; a cell belongs to one body"));
  // Two physical volumes of one name (a .geo cannot say it: Gmsh takes the
  // second for the first).
  const std::string twoNames = scratch("samename.msh");
  std::ofstream(twoNames) << kSameName;
  e = errorOf([&] { readGmsh(twoNames); });
  std::remove(twoNames.c_str());
  out << e << "\n";
  TEST_ASSERT(contains(e, "samename.msh") && contains(e, "two physical volumes are named 'a'"));
  // Third-order elements in a body: named with the body.
  e = geoError("tet20.geo", std::string(kConformal) + "Mesh.ElementOrder = 3;\n");
  out << e << "\n";
  TEST_ASSERT(contains(e, "tet20.geo") && contains(e, "(Tet20) in physical volume 'lower' is not supported (elements of "
                                                      "order 3 or more are not supported"));
}

TEUCHOS_UNIT_TEST(Bodies, MetisPerBody) {
  const Mesh m = readGeo("separate.geo", separate(kTwoBodies));
  // 35 cells, 8 and 27: 7 subdomains are 1.6 and 5.4, so 2 and 5.
  TEST_ASSERT(subdomainsPerBody(m, 7) == (std::vector<int>{2, 5}));
  // The parts of both ranks of two: subdomains 0-2 and 3-6.
  for (int rank = 0; rank < 2; ++rank) {
    const Discretization d(m, boundingBox(m), DecompositionSpec{"METIS", {1, 1, 1}, 7}, 2, rank);
    TEST_EQUALITY(d.numSubdomains(), 7);
    TEST_ASSERT(d.subdomainBody == (std::vector<int>{0, 0, 1, 1, 1, 1, 1}));
    bool oneBody = true;
    for (const Subdomain& s : d.localSubdomains)
      for (int c : s.cells) oneBody = oneBody && m.bodyOf(d.meshCell(c)) == d.subdomainBody[s.id];
    TEST_ASSERT(oneBody);  // no subdomain spans two bodies
    for (const Subdomain& s : d.localSubdomains) TEST_ASSERT(!s.cells.empty());
  }

  // Proportions by hand: 48 and 16 cells.
  const Mesh two = twoBoxes(12, 4);
  TEST_ASSERT(subdomainsPerBody(two, 2) == (std::vector<int>{1, 1}));
  TEST_ASSERT(subdomainsPerBody(two, 4) == (std::vector<int>{3, 1}));
  TEST_ASSERT(subdomainsPerBody(two, 5) == (std::vector<int>{4, 1}));   // 3.75 and 1.25
  TEST_ASSERT(subdomainsPerBody(two, 10) == (std::vector<int>{8, 2}));  // 7.5 and 2.5: the tie to the first
  const auto part = partitionMetisByBody(two, 5);
  std::vector<std::set<int>> bodiesOf(5);
  for (int c = 0; c < two.numCells(); ++c) bodiesOf[part[c]].insert(two.bodyOf(c));
  bool ok = true;
  for (int s = 0; s < 5; ++s) ok = ok && bodiesOf[s] == std::set<int>{s < 4 ? 0 : 1};
  TEST_ASSERT(ok);

  std::string e = errorOf([&] { Discretization(m, boundingBox(m), DecompositionSpec{"METIS", {1, 1, 1}, 1}, 1, 0); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "the mesh has 2 bodies (lower, upper) but only 1 subdomain are asked for"));
  e = errorOf([&] { Discretization(m, boundingBox(m), DecompositionSpec{"Structured", {1, 1, 1}, 1}, 1, 0); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "the Structured partitioner splits one box, but the mesh has 2 bodies; use METIS"));
  // A body of 1 cell beside one of 2: 4 subdomains give it 3.
  const Mesh tiny = twoBoxes(1, 2, 1);
  e = errorOf([&] { subdomainsPerBody(tiny, 4); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "body \"right\" has 2 cells but gets 3 of the 4 subdomains"));
}

TEUCHOS_UNIT_TEST(Bodies, DisconnectedBodyRefused) {
  // Both volumes in one physical volume: one body of two pieces.
  const Mesh m = readGeo("pieces.geo", separate("Physical Volume(\"both\") = {1, 2};\n"));
  TEST_EQUALITY(m.numBodies(), 1);
  for (int S : {1, 4}) {
    const std::string e = errorOf([&] { Discretization(m, boundingBox(m), DecompositionSpec{"METIS", {1, 1, 1}, S}, 1, 0); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "body \"both\" is in several pieces that share no face (cells 0 and 8 of the mesh"));
  }
  // The same two pieces as two bodies are fine.
  Mesh two = m;
  two.bodyNames = {"lower", "upper"};
  two.cellBody.assign(m.numCells(), 0);
  for (int c = 8; c < m.numCells(); ++c) two.cellBody[c] = 1;
  TEST_NOTHROW(requireConnectedBodies(two));
}

TEUCHOS_UNIT_TEST(Bodies, OneBodyPartitionUnchanged) {
  // One body: the partition of partitionMetis itself (existing runs and
  // tests keep their subdomains).
  BoxSpec spec;
  spec.type = CellType::Tet4;
  spec.x = {0, 3};
  spec.cells = {6, 2, 2};
  const Mesh m = generateBox(spec);
  for (int S : {1, 3, 5}) {
    const Discretization d(m, spec, DecompositionSpec{"METIS", {1, 1, 1}, S}, 1, 0);
    const auto metis = partitionMetis(m, S);
    bool same = d.part.numCells() == m.numCells();  // the part's cells are in subdomain order
    for (int c = 0; same && c < d.part.numCells(); ++c) same = d.cellPart[c] == metis[d.meshCell(c)];
    TEST_ASSERT(same);
    TEST_ASSERT(d.subdomainBody == std::vector<int>(S, 0));
  }
  const Discretization s(m, spec, DecompositionSpec{"Structured", {3, 1, 1}, 1}, 1, 0);
  TEST_ASSERT(s.subdomainBody == (std::vector<int>{0, 0, 0}));
  // The old message for more subdomains than cells.
  const std::string e = errorOf([&] { Discretization(m, spec, DecompositionSpec{"METIS", {1, 1, 1}, 1000}, 1, 0); });
  TEST_ASSERT(contains(e, "METIS partition: need 1 <= subdomains <= cells"));
}

TEUCHOS_UNIT_TEST(Bodies, ReadMeshFileDispatch) {
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  const Mesh m = readMeshFile(std::string(dir ? dir : ".") + "/input/gmsh_block.msh");
  TEST_EQUALITY(m.numCells(), 1125);
  const std::string stl = scratch("model.stl");
  std::ofstream(stl) << "solid model\nendsolid model\n";
  const std::string e = errorOf([&] { readMeshFile(stl); });
  std::remove(stl.c_str());
  out << e << "\n";
  TEST_ASSERT(contains(e, "mesh file \"" + stl + "\": unknown extension \".stl\"; Tribos reads Gmsh (.msh, .geo) and Exodus II"));
}
