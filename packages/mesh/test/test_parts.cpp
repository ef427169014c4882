// Discretization: each rank's part of a decomposed mesh, cut on every rank
// from a mesh all hold or sent by the root that alone holds it (run on 1, 2
// and 3 ranks). The part's facts are checked against the whole mesh.
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <set>

#include "Tribos_Discretization.hpp"
#include "Tribos_Error.hpp"

namespace {

using Tribos::CollectiveError;
using namespace Tribos::Mesh;

// Two bodies (cells below and above z = 1) with a node set, cut by METIS:
// subdomains meet at edges and corners as well as faces.
Mesh sample() {
  BoxSpec spec;
  spec.type = CellType::Tet4;
  spec.z = {0, 2};
  spec.cells = {4, 3, 4};
  Mesh m = generateBox(spec);
  m.bodyNames = {"lower", "upper"};
  m.cellBody.assign(m.numCells(), 0);
  for (int c = 0; c < m.numCells(); ++c)
    if (m.coords[m.cell(c)[0]][2] + m.coords[m.cell(c)[1]][2] + m.coords[m.cell(c)[2]][2] + m.coords[m.cell(c)[3]][2] > 4)
      m.cellBody[c] = 1;
  m.nodeSets["pins"] = {1, 7, 30, 60};
  return m;
}

const DecompositionSpec kMetis{"METIS", {1, 1, 1}, 7};

bool samePart(const Discretization& a, const Discretization& b) {
  bool same = a.meshNodes() == b.meshNodes() && a.part.coords == b.part.coords &&
              a.part.connectivity == b.part.connectivity && a.part.cellBody == b.part.cellBody &&
              a.part.nodeSets == b.part.nodeSets && a.part.partFaceNodes == b.part.partFaceNodes &&
              a.cellPart == b.cellPart && a.nodeOwner() == b.nodeOwner() && a.nodeIndex() == b.nodeIndex() &&
              a.ownedNodes() == b.ownedNodes() && a.numMeshNodes() == b.numMeshNodes();
  for (int n = 0; same && n < a.part.numNodes(); ++n) {
    const auto ca = a.copies(n), cb = b.copies(n);
    same = ca.size() == cb.size();
    for (size_t k = 0; same && k < ca.size(); ++k)
      same = ca[k].subdomain == cb[k].subdomain && ca[k].localNode == cb[k].localNode;
  }
  for (const auto& name : a.part.faceNames()) {
    const auto &fa = a.part.face(name), &fb = b.part.face(name);
    same = same && fa.size() == fb.size();
    for (size_t k = 0; same && k < fa.size(); ++k) same = fa[k].nodes == fb[k].nodes && fa[k].cell == fb[k].cell;
  }
  return same;
}

TEUCHOS_UNIT_TEST(Parts, ScatterEqualsCut) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const Mesh m = sample();
  const BoxSpec spec;  // not read by METIS
  const Discretization cut(m, spec, kMetis, comm->getSize(), comm->getRank());
  const Mesh onRoot = comm->getRank() == 0 ? m : Mesh();
  const Discretization sent = Discretization::scatter(onRoot, spec, kMetis, *comm);
  TEST_ASSERT(samePart(cut, sent));
  TEST_EQUALITY(sent.myRank, comm->getRank());
  TEST_EQUALITY(sent.numMeshCells(), m.numCells());
}

TEUCHOS_UNIT_TEST(Parts, PartsAgreeWithTheWholeMesh) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const Mesh m = sample();
  const Discretization d(m, BoxSpec(), kMetis, comm->getSize(), comm->getRank());
  // The part's cells and nodes are the whole mesh's, renumbered.
  bool cellsOk = d.part.numCells() > 0;
  for (int c = 0; c < d.part.numCells(); ++c) {
    cellsOk = cellsOk && d.part.bodyOf(c) == m.bodyOf(d.meshCell(c));
    for (int a = 0; a < 4; ++a) cellsOk = cellsOk && d.meshNode(d.part.cell(c)[a]) == m.cell(d.meshCell(c))[a];
  }
  TEST_ASSERT(cellsOk);
  for (int n = 0; n < d.part.numNodes(); ++n) {
    TEST_ASSERT(d.part.coords[n] == m.coords[d.meshNode(n)]);
    TEST_EQUALITY(d.partNode(d.meshNode(n)), n);
  }
  // Every cell in exactly one part; every node owned once.
  long long mine[2] = {d.part.numCells(), static_cast<long long>(d.ownedNodes().size())}, total[2];
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 2, mine, total);
  TEST_EQUALITY(total[0], static_cast<long long>(m.numCells()));
  TEST_EQUALITY(total[1], static_cast<long long>(m.numNodes()));
  // The copies of a node: every subdomain with a cell holding it (from the
  // whole mesh and the part's cells of each rank), ascending; the local
  // number points back at the node in the rank's own subdomains.
  std::vector<std::set<int>> holders(m.numNodes());
  for (int r = 0; r < comm->getSize(); ++r) {
    const Discretization other(m, BoxSpec(), kMetis, comm->getSize(), r);
    for (int c = 0; c < other.part.numCells(); ++c)
      for (int a = 0; a < 4; ++a) holders[other.meshNode(other.part.cell(c)[a])].insert(other.cellPart[c]);
  }
  bool copiesOk = true;
  for (int n = 0; n < d.part.numNodes(); ++n) {
    const auto cp = d.copies(n);
    std::vector<int> subs;
    for (const auto& c : cp) subs.push_back(c.subdomain);
    copiesOk = copiesOk && subs == std::vector<int>(holders[d.meshNode(n)].begin(), holders[d.meshNode(n)].end());
    copiesOk = copiesOk && d.nodeOwner()[n] == d.layout.owner(subs.front());
    for (const auto& c : cp)
      if (c.subdomain >= d.firstLocalSubdomain() && c.subdomain < d.endLocalSubdomain())
        copiesOk = copiesOk && d.subdomain(c.subdomain).nodes.at(c.localNode) == n;
  }
  TEST_ASSERT(copiesOk);
  // Faces: the facets of the part's cells; the face's nodes, all those the part holds.
  for (const auto& name : m.faceNames()) {
    std::vector<int> expected;
    for (int n : m.faceNodes(name))
      if (d.partNode(n) >= 0) expected.push_back(d.partNode(n));
    TEST_ASSERT(d.part.faceNodes(name) == expected);
    for (const auto& f : d.part.face(name)) TEST_ASSERT(d.cellPart.at(f.cell) >= d.firstLocalSubdomain());
  }
  std::vector<int> pins;
  for (int n : m.nodeSets.at("pins"))
    if (d.partNode(n) >= 0) pins.push_back(d.partNode(n));
  TEST_ASSERT(d.part.nodeSets.at("pins") == pins);
}

TEUCHOS_UNIT_TEST(Parts, OwnersAnswerForAnyNode) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const Mesh m = sample();
  const Discretization d(m, BoxSpec(), kMetis, comm->getSize(), comm->getRank());
  // Each rank asks about every other node, from the last, with repeats.
  std::vector<int> asked;
  for (int n = m.numNodes() - 1 - comm->getRank(); n >= 0; n -= 2) asked.push_back(n), asked.push_back(n);
  const auto x = d.askOwners(asked, 3, [&](int n, double* out) { std::copy(d.part.coords[n].begin(), d.part.coords[n].end(), out); }, *comm);
  bool same = x.size() == 3 * asked.size();
  for (size_t i = 0; same && i < asked.size(); ++i)
    for (int k = 0; k < 3; ++k) same = x[3 * i + k] == m.coords[asked[i]][k];
  TEST_ASSERT(same);
  // First copies: the lowest subdomain with a cell at the node.
  const auto first = d.askOwners(asked, 1, [&](int n, double* out) { out[0] = d.copies(n).front().subdomain; }, *comm);
  std::vector<int> lowest(m.numNodes(), 1 << 30);
  for (int r = 0; r < comm->getSize(); ++r) {
    const Discretization other(m, BoxSpec(), kMetis, comm->getSize(), r);
    for (int c = 0; c < other.part.numCells(); ++c)
      for (int a = 0; a < 4; ++a) {
        int& l = lowest[other.meshNode(other.part.cell(c)[a])];
        l = std::min(l, other.cellPart[c]);
      }
  }
  bool firstOk = true;
  for (size_t i = 0; i < asked.size(); ++i) firstOk = firstOk && first[i] == lowest[asked[i]];
  TEST_ASSERT(firstOk);
}

TEUCHOS_UNIT_TEST(Parts, RootsRefusalReachesEveryRank) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const Mesh onRoot = comm->getRank() == 0 ? sample() : Mesh();
  std::string message;
  try {
    Discretization::scatter(onRoot, BoxSpec(), DecompositionSpec{"METIS", {1, 1, 1}, 100000}, *comm);
  } catch (const CollectiveError& e) {
    message = e.what();
  }
  out << message << "\n";
  TEST_ASSERT(message.find("subdomains") != std::string::npos);
}

}  // namespace
