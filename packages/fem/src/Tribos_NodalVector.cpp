#include "Tribos_NodalVector.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

namespace {

RCP<const Map> dofMap(const std::vector<int>& nodes, const RCP<const Comm>& comm) {
  std::vector<GO> gids;
  gids.reserve(3 * nodes.size());
  for (int n : nodes)
    for (int c = 0; c < 3; ++c) gids.push_back(3 * static_cast<GO>(n) + c);
  return rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), Teuchos::ArrayView<const GO>(gids), 0,
                     comm));
}

// Copies between a std::vector (3 per held node) and a Tpetra vector on the held map.
void toVector(const std::vector<double>& values, Vector& v) {
  auto d = v.getDataNonConst();
  std::copy(values.begin(), values.end(), d.getRawPtr());
}
void fromVector(const Vector& v, std::vector<double>& values) {
  auto d = v.getData();
  std::copy(d.getRawPtr(), d.getRawPtr() + values.size(), values.begin());
}

}  // namespace

NodalLayout::NodalLayout(const std::vector<int>& held, const RCP<const Comm>& comm) : comm_(comm) {
  std::vector<int> sorted(held);
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  TRIBOS_REQUIRE(sorted.empty() || sorted.front() >= 0, "NodalLayout: negative node number " << sorted.front());
  int largest = sorted.empty() ? -1 : sorted.back();
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, largest, Teuchos::outArg(numNodes_));
  ++numNodes_;
  // The owner of a node is the lowest rank holding it: the largest
  // (size - rank) over its holders, found through any one-to-one map.
  const int size = comm->getSize(), me = comm->getRank();
  auto nodeMap = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                             Teuchos::ArrayView<const GO>(std::vector<GO>(sorted.begin(), sorted.end())), 0, comm));
  auto unique = Tpetra::createOneToOne(nodeMap.getConst());
  Vector mark(nodeMap), best(unique);
  mark.putScalar(static_cast<double>(size - me));
  const Import toHolders(unique, nodeMap);
  best.doExport(mark, toHolders, Tpetra::ABSMAX);
  mark.doImport(best, toHolders, Tpetra::INSERT);
  auto m = mark.getData();
  std::vector<int> ghosts;
  for (size_t i = 0; i < sorted.size(); ++i)
    (m[i] == static_cast<double>(size - me) ? nodes_ : ghosts).push_back(sorted[i]);
  numOwned_ = static_cast<int>(nodes_.size());
  ownedMap_ = dofMap(nodes_, comm);
  nodes_.insert(nodes_.end(), ghosts.begin(), ghosts.end());
  heldMap_ = dofMap(nodes_, comm);
  import_ = rcp(new Import(ownedMap_, heldMap_));
}

RCP<const NodalLayout> NodalLayout::everyNode(int numNodes, const RCP<const Comm>& comm) {
  std::vector<int> all(static_cast<size_t>(std::max(numNodes, 0)));
  for (int n = 0; n < numNodes; ++n) all[n] = n;
  return rcp(new NodalLayout(all, comm));
}

int NodalLayout::index(int node) const {
  // Two ascending runs: the owned nodes, then the others.
  for (auto [first, last] : {std::pair{nodes_.begin(), nodes_.begin() + numOwned_},
                             std::pair{nodes_.begin() + numOwned_, nodes_.end()}}) {
    const auto it = std::lower_bound(first, last, node);
    if (it != last && *it == node) return static_cast<int>(it - nodes_.begin());
  }
  return -1;
}

void NodalLayout::sumOverHolders(std::vector<double>& values) const {
  TRIBOS_REQUIRE(values.size() == 3 * nodes_.size(),
                 "NodalLayout: " << values.size() << " values for " << nodes_.size() << " held nodes");
  Vector held(heldMap_), owned(ownedMap_);
  toVector(values, held);
  owned.doExport(held, *import_, Tpetra::ADD);
  held.doImport(owned, *import_, Tpetra::INSERT);
  fromVector(held, values);
}

NodalVector::NodalVector(RCP<const NodalLayout> layout)
    : layout_(std::move(layout)), values_(3 * static_cast<size_t>(layout_->numHeld()), 0.0) {}

NodalVector::NodalVector(RCP<const NodalLayout> layout, const std::vector<double>& everyNode)
    : NodalVector(std::move(layout)) {
  const auto& nodes = layout_->nodes();
  TRIBOS_REQUIRE(everyNode.size() >= 3 * static_cast<size_t>(layout_->numNodes()),
                 "NodalVector: " << everyNode.size() << " values for " << layout_->numNodes() << " nodes");
  for (size_t i = 0; i < nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) values_[3 * i + c] = everyNode[3 * static_cast<size_t>(nodes[i]) + c];
}

int NodalVector::checkedIndex(int node) const {
  const int i = layout_.is_null() ? -1 : layout_->index(node);
  TRIBOS_REQUIRE(i >= 0, "nodal vector: node " << node << " is not held on rank "
                                               << (layout_.is_null() ? 0 : layout_->comm()->getRank()));
  return i;
}

double NodalVector::normInf() const {
  double local = 0, global = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(layout_->numOwned()); ++i) local = std::max(local, std::abs(values_[i]));
  Teuchos::reduceAll(*layout_->comm(), Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  return global;
}

double NodalVector::norm2() const {
  double local = 0, global = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(layout_->numOwned()); ++i) local += values_[i] * values_[i];
  Teuchos::reduceAll(*layout_->comm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return std::sqrt(global);
}

std::vector<double> NodalVector::gathered() const {
  std::vector<double> mine(3 * static_cast<size_t>(layout_->numNodes()), 0.0), all(mine.size(), 0.0);
  const auto& nodes = layout_->nodes();
  for (int i = 0; i < layout_->numOwned(); ++i)
    for (int c = 0; c < 3; ++c) mine[3 * static_cast<size_t>(nodes[i]) + c] = values_[3 * static_cast<size_t>(i) + c];
  if (!mine.empty())
    Teuchos::reduceAll(*layout_->comm(), Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
  return all;
}

}  // namespace Fem
}  // namespace Tribos
