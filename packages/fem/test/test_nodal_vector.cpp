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
    for (const auto& sd : disc.localSubdomains)
      for (int n : sd.nodes) held.push_back(disc.meshNode(n));
    layout = rcp(new Fem::NodalLayout(held, comm));
  }
  static Mesh::Discretization make(const Comm& comm, int rank = -1) {
    Mesh::BoxSpec spec;
    spec.cells = {4, 2, 2};
    Mesh::DecompositionSpec dec;
    dec.grid = {4, 1, 1};
    return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), rank < 0 ? comm.getRank() : rank);
  }
};

TEUCHOS_UNIT_TEST(NodalVector, OwnerIsTheLowestHoldingRank) {
  const auto comm = Tpetra::getDefaultComm();
  const Box b(comm);
  const auto& L = *b.layout;
  TEST_EQUALITY(L.numNodes(), b.disc.numMeshNodes());
  std::vector<int> owned(L.nodes().begin(), L.nodes().begin() + L.numOwned()), partOwned;
  for (int n : b.disc.ownedNodes()) partOwned.push_back(b.disc.meshNode(n));
  TEST_ASSERT(owned == partOwned);
  // Every node owned exactly once over the ranks.
  long long mine = L.numOwned(), total = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, mine, Teuchos::outArg(total));
  TEST_EQUALITY(total, static_cast<long long>(b.disc.numMeshNodes()));
  for (int i = 0; i < L.numHeld(); ++i) TEST_EQUALITY(L.index(L.nodes()[i]), i);
  TEST_EQUALITY(L.index(-5), -1);
  TEST_EQUALITY(L.index(b.disc.numMeshNodes()), -1);
}

TEUCHOS_UNIT_TEST(NodalVector, SumsCopiesAndGathers) {
  const auto comm = Tpetra::getDefaultComm();
  const Box b(comm);
  const auto& L = *b.layout;
  const int me = comm->getRank();
  // Each holder adds (rank + 1) (node + c + 1): the sum over holders is
  // (node + c + 1) times the sum of (r + 1) over the ranks r holding node.
  // Rank r holds the nodes of its part, cut here again for every r.
  std::vector<int> ranksPlus1(b.disc.numMeshNodes(), 0);
  for (int r = 0; r < comm->getSize(); ++r) {
    const auto other = Box::make(*comm, r);
    for (int n : other.meshNodes()) ranksPlus1[n] += r + 1;
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
  TEST_EQUALITY(all.size(), 3 * static_cast<size_t>(b.disc.numMeshNodes()));
  double maxAbs = 0, sum2 = 0;
  for (int n = 0; n < b.disc.numMeshNodes(); ++n)
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
  for (int n = 0; n < b.disc.numMeshNodes() && missing < 0; ++n)
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
