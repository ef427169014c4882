// Nodal vectors spread over the ranks (Tribos_NodalVector.hpp):
//  - a node is owned by the lowest rank that holds it, which for a
//    decomposed mesh is Discretization::nodeOwner();
//  - sumOverHolders gives every holder the sum of all holders' values,
//    gathered() every node's value;
//  - norms count each node once;
//  - a node a rank does not hold is refused, naming it.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <set>
#include <string>

#include "Tribos_Discretization.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_NodalVector.hpp"

namespace {

using namespace Tribos;

// A 4 x 2 x 2 box in subdomains along x, one or more per rank; each rank
// holds the nodes of its subdomains.
struct Box {
  Mesh::Discretization disc;
  RCP<const Fem::NodalLayout> layout;
  explicit Box(const RCP<const Comm>& comm) : disc(make(*comm)) {
    std::vector<int> held;
    for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s)
      held.insert(held.end(), disc.subdomains[s].nodes.begin(), disc.subdomains[s].nodes.end());
    layout = rcp(new Fem::NodalLayout(held, comm));
  }
  static Mesh::Discretization make(const Comm& comm) {
    Mesh::BoxSpec spec;
    spec.cells = {4, 2, 2};
    Mesh::DecompositionSpec dec;
    dec.grid = {4, 1, 1};
    return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
  }
};

TEUCHOS_UNIT_TEST(NodalVector, OwnerIsTheLowestHoldingRank) {
  const auto comm = Tpetra::getDefaultComm();
  const Box b(comm);
  const auto& L = *b.layout;
  TEST_EQUALITY(L.numNodes(), b.disc.mesh.numNodes());
  std::vector<int> owned(L.nodes().begin(), L.nodes().begin() + L.numOwned());
  TEST_ASSERT(owned == b.disc.ownedNodes());
  // Every node owned exactly once over the ranks.
  long long mine = L.numOwned(), total = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, mine, Teuchos::outArg(total));
  TEST_EQUALITY(total, static_cast<long long>(b.disc.mesh.numNodes()));
  for (int i = 0; i < L.numHeld(); ++i) TEST_EQUALITY(L.index(L.nodes()[i]), i);
  TEST_EQUALITY(L.index(-5), -1);
  TEST_EQUALITY(L.index(b.disc.mesh.numNodes()), -1);
}

TEUCHOS_UNIT_TEST(NodalVector, SumsCopiesAndGathers) {
  const auto comm = Tpetra::getDefaultComm();
  const Box b(comm);
  const auto& L = *b.layout;
  const int me = comm->getRank();
  // Each holder adds (rank + 1) (node + c + 1): the sum over holders is
  // (node + c + 1) times the sum of (r + 1) over the ranks r holding node.
  std::vector<int> holders(b.disc.mesh.numNodes(), 0), ranksPlus1(holders.size(), 0);
  for (int s = 0; s < b.disc.numSubdomains(); ++s)
    for (int n : b.disc.subdomains[s].nodes) {
      const int r = b.disc.layout.owner(s);
      if (!(holders[n] & (1 << r))) holders[n] |= 1 << r, ranksPlus1[n] += r + 1;
    }
  Fem::NodalVector v(b.layout);
  for (int n : L.nodes())
    for (int c = 0; c < 3; ++c) v.at(n)[c] = (me + 1.0) * (n + c + 1);
  L.sumOverHolders(v.values());
  double err = 0;
  for (int n : L.nodes())
    for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(v.at(n)[c] - ranksPlus1[n] * (n + c + 1.0)));
  TEST_EQUALITY(err, 0.0);
  // gathered: every node's value on every rank; norms count a node once.
  const auto all = v.gathered();
  TEST_EQUALITY(all.size(), 3 * static_cast<size_t>(b.disc.mesh.numNodes()));
  double maxAbs = 0, sum2 = 0;
  for (int n = 0; n < b.disc.mesh.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      const double x = ranksPlus1[n] * (n + c + 1.0);
      TEST_EQUALITY(all[3 * n + c], x);
      maxAbs = std::max(maxAbs, x), sum2 += x * x;
    }
  TEST_EQUALITY(v.normInf(), maxAbs);
  TEST_FLOATING_EQUALITY(v.norm2(), std::sqrt(sum2), 1e-14);
}

TEUCHOS_UNIT_TEST(NodalVector, EveryNodeAndRefusals) {
  const auto comm = Tpetra::getDefaultComm();
  const auto L = Fem::NodalLayout::everyNode(7, comm);
  TEST_EQUALITY(L->numHeld(), 7);
  TEST_EQUALITY(L->numOwned(), comm->getRank() == 0 ? 7 : 0);
  std::vector<double> all(21);
  for (int i = 0; i < 21; ++i) all[i] = i;
  Fem::NodalVector v(L, all);
  TEST_EQUALITY(v.at(6)[2], 20.0);
  TEST_ASSERT(v.gathered() == all);
  // A node this rank does not hold.
  const Box b(comm);
  Fem::NodalVector u(b.layout);
  int missing = -1;
  for (int n = 0; n < b.disc.mesh.numNodes() && missing < 0; ++n)
    if (b.layout->index(n) < 0) missing = n;
  if (comm->getSize() == 1) TEST_EQUALITY(missing, -1);
  if (missing >= 0) {
    std::string message;
    try {
      u.at(missing);
    } catch (const Error& e) {
      message = e.what();
    }
    out << message << "\n";
    TEST_ASSERT(message.find("node " + std::to_string(missing) + " is not held") != std::string::npos);
  }
}

}  // namespace
