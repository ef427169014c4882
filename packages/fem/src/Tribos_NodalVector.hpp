// Tribos_NodalVector.hpp: nodal vectors (3 values per mesh node) spread over
// the ranks. Each rank holds the nodes it reads: those of its subdomains or
// cells and the partners of its contact nodes. Each node is owned by the
// lowest rank that holds it. Sums over the ranks go to the owner (Tpetra
// Export) and come back from it (Import), so no rank needs a vector of
// every node of the mesh.
#pragma once

#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace Fem {

class NodalLayout {
 public:
  // held: the nodes this rank reads (any order; repeats are merged). Collective.
  NodalLayout(const std::vector<int>& held, const RCP<const Comm>& comm);
  // Every node 0..numNodes-1 held on every rank, all owned by rank 0: for a
  // result that every rank computes alike. Collective.
  static RCP<const NodalLayout> everyNode(int numNodes, const RCP<const Comm>& comm);

  // The held nodes: the owned ones first, ascending, then the others, ascending.
  const std::vector<int>& nodes() const { return nodes_; }
  int numHeld() const { return static_cast<int>(nodes_.size()); }
  int numOwned() const { return numOwned_; }
  // The position of a node in nodes(), -1 when this rank does not hold it.
  int index(int node) const;
  // 1 + the largest node number held by any rank.
  int numNodes() const { return numNodes_; }
  const RCP<const Comm>& comm() const { return comm_; }

  // values: 3 per held node. Each node's values summed over the ranks that
  // hold it, the sum then on every one of them. Collective.
  void sumOverHolders(std::vector<double>& values) const;

 private:
  RCP<const Comm> comm_;
  std::vector<int> nodes_;
  int numOwned_ = 0, numNodes_ = 0;
  RCP<const Map> heldMap_, ownedMap_;  // dofs 3 node + c
  RCP<const Import> import_;           // owned -> held
};

class NodalVector {
 public:
  NodalVector() = default;
  // Zero at every held node.
  explicit NodalVector(RCP<const NodalLayout> layout);
  // The held part of a vector of every node (3 numNodes values, the same on
  // every rank).
  NodalVector(RCP<const NodalLayout> layout, const std::vector<double>& everyNode);

  const NodalLayout& layout() const { return *layout_; }
  const RCP<const NodalLayout>& layoutPtr() const { return layout_; }
  bool empty() const { return layout_.is_null(); }
  // The 3 values of a held node; throws naming the node when it is not held.
  const double* at(int node) const { return &values_[3 * static_cast<size_t>(checkedIndex(node))]; }
  double* at(int node) { return &values_[3 * static_cast<size_t>(checkedIndex(node))]; }
  // 3 per held node, in the order of layout().nodes().
  const std::vector<double>& values() const { return values_; }
  std::vector<double>& values() { return values_; }

  // Over all nodes of all ranks (each node counted once, at its owner). Collective.
  double normInf() const;
  double norm2() const;
  // The whole vector, 3 numNodes values, on every rank: for writers of a
  // global file (the FCLIB export) and for tests, not for the solution path.
  // Collective.
  std::vector<double> gathered() const;

 private:
  int checkedIndex(int node) const;
  RCP<const NodalLayout> layout_;
  std::vector<double> values_;
};

}  // namespace Fem
}  // namespace Tribos
