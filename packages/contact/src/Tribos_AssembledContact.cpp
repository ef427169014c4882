#include "Tribos_AssembledContact.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_RowMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_AllGather.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Exchange.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_TpetraSubdomain.hpp"

namespace Tribos {
namespace Assembled {

// ---------------------------------------------------------------------------
// ContactProblem

ContactProblem::ContactProblem(const RCP<const RowMatrix>& K, const RCP<const Map>& ownedMap,
                               const RCP<const MultiVector>& coordinates)
    : K_(K), ownedMap_(ownedMap), coordinates_(coordinates) {
  TRIBOS_REQUIRE(!K.is_null(), "Assembled::ContactProblem: K is null");
  TRIBOS_REQUIRE(!ownedMap.is_null(), "Assembled::ContactProblem: ownedMap is null");
  TRIBOS_REQUIRE(!coordinates.is_null(), "Assembled::ContactProblem: the coordinates are null");
}

ContactProblem::ContactProblem(ElementMatrices elements, const RCP<const Map>& ownedMap,
                               const RCP<const MultiVector>& coordinates)
    : elements_(rcp(new ElementMatrices(std::move(elements)))), ownedMap_(ownedMap), coordinates_(coordinates) {
  TRIBOS_REQUIRE(!ownedMap.is_null(), "Assembled::ContactProblem: ownedMap is null");
  TRIBOS_REQUIRE(!coordinates.is_null(), "Assembled::ContactProblem: the coordinates are null");
}

void ContactProblem::setStiffness(const RCP<const RowMatrix>& K) {
  TRIBOS_REQUIRE(!K.is_null(), "Assembled::ContactProblem::setStiffness: K is null");
  TRIBOS_REQUIRE(elements_.is_null(), "Assembled::ContactProblem::setStiffness: the problem was given element "
                                      "matrices; give new ones (setElementMatrices)");
  K_ = K;
  ++stiffnessVersion_;
}

void ContactProblem::setElementMatrices(ElementMatrices elements) {
  TRIBOS_REQUIRE(K_.is_null(), "Assembled::ContactProblem::setElementMatrices: the problem was given K; give a new K");
  elements_ = rcp(new ElementMatrices(std::move(elements)));
  ++stiffnessVersion_;
}

void ContactProblem::setLoad(const RCP<const Vector>& f) {
  f_ = f;
  ++loadVersion_;
}

void ContactProblem::setDirichlet(std::vector<std::pair<GO, double>> dofValues) {
  dirichlet_ = std::move(dofValues);
  ++loadVersion_;
}

int ContactProblem::addContactPair(ContactPair pair) {
  pairs_.push_back(std::move(pair));
  return static_cast<int>(pairs_.size()) - 1;
}

// ---------------------------------------------------------------------------
// AssembledFeti: the FETI problem of a ContactProblem.
//
// Nodes get Tribos numbers ("ids"): the owned nodes of rank 0 (ascending by
// the application's node id), then those of rank 1, ...; the owner of an id
// is then known from the ranks' counts. Each connected piece of a rank's
// elements (of the nonzero pattern of its rows of K) is a subdomain. The
// owner of a node is its directory: it learns the copies of the node and
// its Dirichlet values, and tells every rank holding a copy. The contact
// surfaces are small beside the bodies: their facets and nodes are gathered
// on every rank, where the contact search runs.

namespace {

struct CopyMessage {
  int node, subdomain, localNode;
};
struct DofMessage {
  long long dof;  // 3 id + c
  double value;
};

// The nodes of a dof map (dof 3 node + c), ascending; each must come with
// its three dofs.
std::vector<GO> nodesOfDofMap(const Map& map, const std::string& what, int rank) {
  std::map<GO, int> components;
  for (GO dof : map.getNodeElementList()) {
    TRIBOS_REQUIRE(dof >= 0, "Assembled::ContactProblem: " << what << " holds the negative dof " << dof);
    components[dof / 3] |= 1 << (dof % 3);
  }
  std::vector<GO> nodes;
  for (const auto& [node, mask] : components) {
    TRIBOS_REQUIRE(mask == 7, "Assembled::ContactProblem: "
                                  << what << " on rank " << rank << " holds some but not all of the dofs 3n, 3n+1, 3n+2 of node "
                                  << node << ": Tribos numbers the dofs of node n as 3n + c (c = x, y, z)");
    nodes.push_back(node);
  }
  return nodes;
}

int ownerOf(const std::vector<int>& offsets, int id) {
  return static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), id) - offsets.begin()) - 1;
}

// Union-find over the nodes of a rank's rows.
struct Pieces {
  std::vector<int> parent;
  explicit Pieces(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) { parent[root(a)] = root(b); }
};

}  // namespace

// A message with "node <k>" in a numbering of Tribos' own, with the
// application's node ids instead (names[k]).
static std::string withApplicationNodes(const std::string& message, const std::map<int, GO>& names) {
  // "node <id>" -> "node <application id>"
  std::string out;
  size_t at = 0;
  const std::string word = "node ";
  for (size_t k = message.find(word); k != std::string::npos; k = message.find(word, at)) {
    size_t end = k + word.size();
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    out += message.substr(at, k + word.size() - at);
    at = end;
    if (end == k + word.size()) continue;
    const auto it = names.find(std::stoi(message.substr(k + word.size(), end - k - word.size())));
    out += it != names.end() ? std::to_string(it->second) : message.substr(k + word.size(), end - k - word.size());
  }
  return out + message.substr(at);
}

class AssembledFeti {
 public:
  AssembledFeti(const ContactProblem& p, const Teuchos::ParameterList& fetiParams, const RCP<const Comm>& comm);

  // The problem's current load and Dirichlet values into the FETI problem;
  // false (on every rank) when the Dirichlet conditions fix other dofs than
  // the problem was built with (then it must be built again). Collective.
  bool setRightHandSides(const ContactProblem& p);
  // The problem's new K into the FETI problem by a numeric refactorization;
  // false (on every rank) when its rows, pieces or pattern differ from the
  // ones factored (then it must be built again). Collective.
  bool setStiffness(const ContactProblem& p);

  RCP<Vector> displacement(const Fem::NodalVector& u) const;
  RCP<Vector> reaction(const Fem::NodalVector& u, const Contact::ContactNodeResults& contact) const;
  RCP<MultiVector> contactState(const Contact::ContactNodeResults& c) const;

  // A message of Tribos' own numbering, with the application's node ids.
  std::string withApplicationNodes(const std::string& message) const {
    return Assembled::withApplicationNodes(message, application_);
  }

  RCP<Feti::FetiProblem> problem;
  RCP<const Map> nodeMap;  // the owned nodes, application ids

 private:
  RCP<const Comm> comm_;
  int rank_ = 0, size_ = 1;
  RCP<const Map> ownedMap_, rowMap_;
  std::vector<int> offsets_;          // ids [offsets_[r], offsets_[r+1]) are owned by rank r
  std::vector<GO> ownedNodes_;        // application ids of the owned nodes, ascending (id offsets_[rank] + i)
  std::vector<GO> rowNodes_;          // application ids of the nodes of K's rows, ascending
  std::vector<int> rowIds_;           // their ids
  std::map<int, GO> application_;     // id -> application id (K's rows and the contact surfaces)
  std::vector<std::vector<int>> pieces_;  // per local subdomain: the row-node index of each local node
  int firstSubdomain_ = 0;
  std::vector<int> subdomainOwner_;   // every subdomain's rank
  std::map<int, std::vector<CopyMessage>> ownedCopies_;  // directory: owned id -> its copies
  std::map<int, std::vector<Mesh::NodeCopy>> copies_;   // id of a local subdomain's node -> its copies
  std::vector<int> surfaceNodes_;     // ids of every contact surface node (every rank)
  std::map<int, Mesh::NodeCopy> surfaceFirstCopy_;
  std::map<long long, double> dirichlet_;  // 3 id + c -> value, at the local and surface nodes

  int rowNode(GO node) const;  // index in rowNodes_, -1 when absent
  void numberNodes(const ContactProblem& p);
  // The rank's rows of K (entries per row dof, in row-node dofs) and its
  // connected pieces (row-node indices, ascending ids); checks them.
  struct RankRows {
    std::vector<std::vector<std::pair<int, double>>> entries;  // K given: its rows
    std::vector<std::vector<int>> pieces;
    const ElementMatrices* elements = nullptr;  // elements given: them,
    std::vector<std::vector<int>> pieceElements;  // and each piece's
  };
  RankRows readRows(const RowMatrix& K) const;
  RankRows readElements(const ElementMatrices& E) const;
  RankRows readRows(const ContactProblem& p) const;
  std::vector<GO> elementNodes(const ElementMatrices& E) const;
  std::vector<LocalCsr> pieceMatrices(const RankRows& rows) const;
  std::vector<Fem::SubdomainSystem> subdomains(const ContactProblem& p);
  // FETI's K+ and the Cholesky factorization assume K = K' on every rank's
  // rows; throws naming the two entries (application dofs) that differ.
  void requireSymmetric(std::vector<std::vector<std::pair<int, double>>>& entries) const;
  void buildDirectory();
  std::map<long long, double> distributeDirichlet(const std::vector<std::pair<GO, double>>& dofValues);
  std::vector<std::vector<double>> subdomainLoads(const RCP<const Vector>& f) const;
  std::vector<Feti::ContactConstraint> contactConstraints(const ContactProblem& p);
  std::vector<Fem::Point> rowCoordinates(const MultiVector& coordinates) const;
  std::vector<Fem::Point> rowCoords_;
};

int AssembledFeti::rowNode(GO node) const {
  const auto it = std::lower_bound(rowNodes_.begin(), rowNodes_.end(), node);
  return it != rowNodes_.end() && *it == node ? static_cast<int>(it - rowNodes_.begin()) : -1;
}

void AssembledFeti::numberNodes(const ContactProblem& p) {
  ownedMap_ = p.ownedMap();
  ownedNodes_ = nodesOfDofMap(*ownedMap_, "ownedMap", rank_);
  if (!p.elements().is_null()) {
    rowNodes_ = elementNodes(*p.elements());
    std::vector<GO> dofs;
    for (GO n : rowNodes_)
      for (int c = 0; c < 3; ++c) dofs.push_back(3 * n + c);
    rowMap_ = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                          Teuchos::ArrayView<const GO>(dofs), 0, comm_));
  } else {
    rowMap_ = p.stiffness()->getRowMap();
    TRIBOS_REQUIRE(!rowMap_.is_null(), "Assembled::ContactProblem: K has no row map");
    rowNodes_ = nodesOfDofMap(*rowMap_, "K's row map", rank_);
  }
  // The ranks' owned node counts give the ids.
  const int mine = static_cast<int>(ownedNodes_.size());
  std::vector<int> counts(size_);
  Teuchos::gatherAll<int, int>(*comm_, 1, &mine, size_, counts.data());
  offsets_.assign(size_ + 1, 0);
  for (int r = 0; r < size_; ++r) offsets_[r + 1] = offsets_[r] + counts[r];
  // The ids of the nodes of K's rows, from their owners (Tpetra's
  // directory finds them); a node no rank owns keeps -1.
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  nodeMap = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(ownedNodes_), 0, comm_));
  auto rowNodeMap = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(rowNodes_), 0, comm_));
  Vector ownedIds(nodeMap), ids(rowNodeMap);
  {
    auto v = ownedIds.getDataNonConst();
    for (int i = 0; i < mine; ++i) v[i] = offsets_[rank_] + i + 1;
  }
  ids.doImport(ownedIds, Import(nodeMap, rowNodeMap), Tpetra::INSERT);
  const auto v = ids.getData();
  rowIds_.resize(rowNodes_.size());
  for (size_t i = 0; i < rowNodes_.size(); ++i) {
    TRIBOS_REQUIRE(v[i] > 0, "Assembled::ContactProblem: node " << rowNodes_[i] << " of rank " << rank_
                                                                << "'s rows of K is in no rank's ownedMap");
    rowIds_[i] = static_cast<int>(v[i]) - 1;
    application_[rowIds_[i]] = rowNodes_[i];
  }
}

std::vector<Fem::Point> AssembledFeti::rowCoordinates(const MultiVector& X) const {
  TRIBOS_REQUIRE(X.getNumVectors() == 3, "Assembled::ContactProblem: the coordinates have " << X.getNumVectors()
                                                                                          << " columns, expected 3 (x, y, z)");
  const Map& map = *X.getMap();
  std::vector<Fem::Point> out(rowNodes_.size());
  bool local = true;
  for (GO n : rowNodes_) local = local && map.isNodeGlobalElement(n);
  int everywhere = 0;
  Teuchos::reduceAll<int, int>(*comm_, Teuchos::REDUCE_MIN, local ? 1 : 0, Teuchos::outArg(everywhere));
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto rowNodeMap = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(rowNodes_), 0, comm_));
  MultiVector Y(rowNodeMap, 3);
  if (everywhere) {
    for (int d = 0; d < 3; ++d) {
      const auto x = X.getData(d);
      for (size_t i = 0; i < rowNodes_.size(); ++i)
        Y.replaceLocalValue(static_cast<LO>(i), d, x[map.getLocalElement(rowNodes_[i])]);
    }
  } else {
    // Some rank lacks coordinates of its nodes: the map must be one-to-one
    // (each node's coordinates given once), and they are imported.
    TRIBOS_REQUIRE(map.isOneToOne(), "Assembled::ContactProblem: the coordinates' map holds neither every node of "
                                     "the rank's rows of K nor each node once (give them on the owned node map or "
                                     "on the owned+shared one)");
    Y.putScalar(std::numeric_limits<double>::quiet_NaN());
    Y.doImport(X, Import(X.getMap(), rowNodeMap), Tpetra::INSERT);
  }
  const auto columns = Y.get2dView();
  for (size_t i = 0; i < rowNodes_.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      out[i][d] = columns[d][i];
      TRIBOS_REQUIRE(std::isfinite(out[i][d]), "Assembled::ContactProblem: node " << rowNodes_[i]
                                                  << " has no finite coordinates on rank " << rank_);
    }
  return out;
}

void AssembledFeti::requireSymmetric(std::vector<std::vector<std::pair<int, double>>>& entries) const {
  double largest = 0;
  for (size_t a = 0; a < entries.size(); ++a) {
    std::sort(entries[a].begin(), entries[a].end());
    for (const auto& [b, v] : entries[a])
      if (b == static_cast<int>(a)) largest = std::max(largest, std::abs(v));
  }
  auto dof = [&](int a) { return 3 * rowNodes_[a / 3] + a % 3; };
  // Entries of one row may repeat a column (summed, as Tpetra sums them).
  auto value = [&](int a, int b) {
    double sum = 0;
    auto it = std::lower_bound(entries[a].begin(), entries[a].end(), std::make_pair(b, -HUGE_VAL));
    for (; it != entries[a].end() && it->first == b; ++it) sum += it->second;
    return sum;
  };
  for (size_t a = 0; a < entries.size(); ++a)
    for (const auto& e : entries[a]) {
      const int b = e.first;
      const double kab = value(static_cast<int>(a), b), kba = value(b, static_cast<int>(a));
      TRIBOS_REQUIRE(std::abs(kab - kba) <= 1e-10 * largest,
                     "Assembled::ContactProblem: K is not symmetric on rank "
                         << rank_ << ": K(" << dof(static_cast<int>(a)) << ", " << dof(b) << ") = " << kab << " but K("
                         << dof(b) << ", " << dof(static_cast<int>(a)) << ") = " << kba);
    }
}

// The rank's rows of K cut into its connected pieces, each a subdomain in
// the ids of its nodes.
// The nodes of the rank's elements, ascending; checks the sizes.
std::vector<GO> AssembledFeti::elementNodes(const ElementMatrices& E) const {
  const int m = E.nodesPerElement;
  TRIBOS_REQUIRE(m >= 1 && E.nodes.size() % m == 0,
                 "Assembled::ContactProblem: rank " << rank_ << "'s element matrices: " << E.nodes.size()
                                                    << " node ids, not a multiple of nodesPerElement = " << m);
  const size_t width = static_cast<size_t>(3 * m) * (3 * m);
  TRIBOS_REQUIRE(E.values.size() == E.numElements() * width,
                 "Assembled::ContactProblem: rank " << rank_ << "'s element matrices: " << E.values.size()
                                                    << " values for " << E.numElements() << " elements of " << m
                                                    << " nodes, expected " << E.numElements() * width);
  TRIBOS_REQUIRE(E.subdomainSize >= 0 && E.subdomainSize <= 1000,
                 "Assembled::ContactProblem: ElementMatrices::subdomainSize = " << E.subdomainSize
                                                                                << " (0: Auto, or 1 to 1000)");
  std::set<GO> nodes;
  for (GO n : E.nodes) {
    TRIBOS_REQUIRE(n >= 0, "Assembled::ContactProblem: rank " << rank_ << " has an element with the node id " << n);
    nodes.insert(n);
  }
  return {nodes.begin(), nodes.end()};
}

AssembledFeti::RankRows AssembledFeti::readRows(const ContactProblem& p) const {
  return p.elements().is_null() ? readRows(*p.stiffness()) : readElements(*p.elements());
}

// The rank's elements split into subdomains: each connected part of them
// (elements sharing nodes) apart, cut by METIS into parts of about
// (H + 1)^3 nodes.
AssembledFeti::RankRows AssembledFeti::readElements(const ElementMatrices& E) const {
  const int m = E.nodesPerElement, w = 3 * m;
  const size_t ne = E.numElements();
  RankRows out;
  out.elements = &E;
  std::vector<int> local(E.nodes.size());
  Pieces parts(static_cast<int>(rowNodes_.size()));
  for (size_t e = 0; e < ne; ++e) {
    const double* K = &E.values[e * w * w];
    double largest = 0;
    for (int i = 0; i < w; ++i) largest = std::max(largest, std::abs(K[i * w + i]));
    for (int i = 0; i < w; ++i)
      for (int j = 0; j < w; ++j) {
        TRIBOS_REQUIRE(std::isfinite(K[i * w + j]), "Assembled::ContactProblem: rank "
                                                        << rank_ << "'s element " << e << " has the entry ("
                                                        << i << ", " << j << ") = " << K[i * w + j]);
        TRIBOS_REQUIRE(std::abs(K[i * w + j] - K[j * w + i]) <= 1e-10 * largest,
                       "Assembled::ContactProblem: rank " << rank_ << "'s element " << e
                                                          << " matrix is not symmetric: (" << i << ", " << j
                                                          << ") = " << K[i * w + j] << " but (" << j << ", " << i
                                                          << ") = " << K[j * w + i]);
      }
    for (int a = 0; a < m; ++a) {
      local[e * m + a] = rowNode(E.nodes[e * m + a]);
      if (a > 0) parts.join(local[e * m], local[e * m + a]);
    }
  }
  // Connected parts in the order of their smallest node id.
  std::map<int, int> smallest;  // root -> smallest id
  for (size_t e = 0; e < ne; ++e)
    for (int a = 0; a < m; ++a) {
      const int r = parts.root(local[e * m + a]), id = rowIds_[local[e * m + a]];
      const auto it = smallest.insert({r, id});
      if (!it.second) it.first->second = std::min(it.first->second, id);
    }
  std::vector<std::pair<int, int>> order;  // (smallest id, root)
  for (const auto& [r, id] : smallest) order.push_back({id, r});
  std::sort(order.begin(), order.end());
  const int H = E.subdomainSize > 0 ? E.subdomainSize : 4;
  const double nodesPerSubdomain = std::pow(H + 1.0, 3);
  for (const auto& [id, root] : order) {
    std::vector<int> elements;
    std::map<int, int> partNode;  // row node -> node of the part's mesh
    for (size_t e = 0; e < ne; ++e)
      if (parts.root(local[e * m]) == root) elements.push_back(static_cast<int>(e));
    Mesh::Mesh mesh;
    mesh.type = m == 4 ? Mesh::CellType::Tet4 : Mesh::CellType::Hex8;
    for (int e : elements)
      for (int a = 0; a < m; ++a) {
        const auto it = partNode.insert({local[e * m + a], static_cast<int>(partNode.size())});
        mesh.connectivity.push_back(it.first->second);
      }
    int count = static_cast<int>(std::lround(partNode.size() / nodesPerSubdomain));
    count = std::max(1, std::min(count, static_cast<int>(elements.size())));
    if (m != 4 && m != 8) count = 1;
    mesh.coords.assign(partNode.size(), {0, 0, 0});
    const std::vector<int> cut = count > 1 ? Mesh::partitionMetis(mesh, count) : std::vector<int>(elements.size(), 0);
    std::vector<std::vector<int>> pieceElements(count);
    for (size_t k = 0; k < elements.size(); ++k) pieceElements[cut[k]].push_back(elements[k]);
    for (auto& list : pieceElements) {
      if (list.empty()) continue;
      std::set<int> nodes;
      for (int e : list)
        for (int a = 0; a < m; ++a) nodes.insert(local[e * m + a]);
      std::vector<int> piece(nodes.begin(), nodes.end());
      std::sort(piece.begin(), piece.end(), [&](int x, int y) { return rowIds_[x] < rowIds_[y]; });
      out.pieces.push_back(std::move(piece));
      out.pieceElements.push_back(std::move(list));
    }
  }
  return out;
}

AssembledFeti::RankRows AssembledFeti::readRows(const RowMatrix& K) const {
  TRIBOS_REQUIRE(K.isFillComplete() || K.getColMap() != Teuchos::null,
                 "Assembled::ContactProblem: K has no column map (fill it, as Tpetra's FECrsMatrix does between "
                 "beginAssembly() and endAssembly(), or call fillComplete())");
  const Map& rows = *K.getRowMap();
  const Map& cols = *K.getColMap();
  const int n = static_cast<int>(rowNodes_.size());
  // Per row dof: (row node, component); entries as (row dof, column dof).
  auto dofOf = [&](GO gid) { return 3 * rowNode(gid / 3) + static_cast<int>(gid % 3); };
  RankRows out;
  out.entries.resize(3 * n);
  Pieces pieces(n);
  std::vector<char> used(n, 0);
  RowMatrix::nonconst_local_inds_host_view_type index("index", K.getNodeMaxNumRowEntries());
  RowMatrix::nonconst_values_host_view_type value("value", K.getNodeMaxNumRowEntries());
  for (LO i = 0; i < static_cast<LO>(K.getNodeNumRows()); ++i) {
    const int a = dofOf(rows.getGlobalElement(i));
    size_t count = 0;
    K.getLocalRowCopy(i, index, value, count);
    for (size_t k = 0; k < count; ++k) {
      const double kij = value(k);
      if (kij == 0.0) continue;  // the pattern of other ranks' elements (an FECrsGraph's owned rows)
      TRIBOS_REQUIRE(std::isfinite(kij), "Assembled::ContactProblem: K(" << rows.getGlobalElement(i) << ", "
                                                                          << cols.getGlobalElement(index(k))
                                                                          << ") = " << kij << " is not finite");
      const GO column = cols.getGlobalElement(index(k));
      TRIBOS_REQUIRE(rows.isNodeGlobalElement(column),
                     "Assembled::ContactProblem: rank " << rank_ << "'s row " << rows.getGlobalElement(i)
                         << " of K couples dof " << column << ", which is not among its rows: K's rows have been "
                            "summed over the ranks. Give K as the rank's elements sum it, an FECrsMatrix before "
                            "endAssembly() (or the overlap CrsMatrix of the rank's elements)");
      const int b = dofOf(column);
      out.entries[a].push_back({b, kij});
      pieces.join(a / 3, b / 3);
      used[a / 3] = used[b / 3] = 1;
    }
  }
  requireSymmetric(out.entries);
  // Pieces in the order of their smallest node id; nodes by ascending id.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return rowIds_[x] < rowIds_[y]; });
  std::map<int, int> pieceOfRoot;
  for (int a : order) {
    if (!used[a]) continue;
    const auto inserted = pieceOfRoot.insert({pieces.root(a), static_cast<int>(out.pieces.size())});
    if (inserted.second) out.pieces.emplace_back();
    out.pieces[inserted.first->second].push_back(a);
  }
  return out;
}

// K of each piece in its local dofs (3 local node + c), columns ascending.
std::vector<LocalCsr> AssembledFeti::pieceMatrices(const RankRows& rows) const {
  std::vector<LocalCsr> out;
  std::vector<int> local(rowNodes_.size(), -1);
  if (rows.elements) {
    // The sum of each piece's element matrices.
    const ElementMatrices& E = *rows.elements;
    const int m = E.nodesPerElement, w = 3 * m;
    for (size_t s = 0; s < rows.pieces.size(); ++s) {
      const auto& nodes = rows.pieces[s];
      for (size_t l = 0; l < nodes.size(); ++l) local[nodes[l]] = static_cast<int>(l);
      std::vector<std::vector<std::pair<int, double>>> entries(3 * nodes.size());
      for (int e : rows.pieceElements[s]) {
        std::vector<int> dofs(w);
        for (int a = 0; a < m; ++a)
          for (int c = 0; c < 3; ++c) dofs[3 * a + c] = 3 * local[rowNode(E.nodes[e * m + a])] + c;
        const double* K = &E.values[static_cast<size_t>(e) * w * w];
        for (int i = 0; i < w; ++i)
          for (int j = 0; j < w; ++j)
            if (K[i * w + j] != 0.0) entries[dofs[i]].push_back({dofs[j], K[i * w + j]});
      }
      out.push_back(LocalCsr::fromRows(std::move(entries)));
    }
    return out;
  }
  for (const auto& nodes : rows.pieces) {
    for (size_t l = 0; l < nodes.size(); ++l) local[nodes[l]] = static_cast<int>(l);
    std::vector<std::vector<std::pair<int, double>>> entries;
    for (int a : nodes)
      for (int c = 0; c < 3; ++c) {
        entries.push_back(rows.entries[3 * a + c]);
        for (auto& e : entries.back()) e.first = 3 * local[e.first / 3] + e.first % 3;
      }
    out.push_back(LocalCsr::fromRows(std::move(entries)));
  }
  return out;
}

// The rank's rows of K cut into its connected pieces, each a subdomain in
// the ids of its nodes.
std::vector<Fem::SubdomainSystem> AssembledFeti::subdomains(const ContactProblem& p) {
  RankRows rows = readRows(p);
  pieces_ = rows.pieces;
  const int mine = static_cast<int>(pieces_.size());
  std::vector<int> counts(size_);
  Teuchos::gatherAll<int, int>(*comm_, 1, &mine, size_, counts.data());
  subdomainOwner_.clear();
  for (int r = 0; r < size_; ++r) {
    if (r == rank_) firstSubdomain_ = static_cast<int>(subdomainOwner_.size());
    subdomainOwner_.insert(subdomainOwner_.end(), counts[r], r);
  }
  std::vector<LocalCsr> K = pieceMatrices(rows);
  std::vector<Fem::SubdomainSystem> systems;
  for (int s = 0; s < mine; ++s) {
    Fem::SubdomainSystem sys;
    sys.id = firstSubdomain_ + s;
    for (int a : pieces_[s]) {
      sys.nodes.push_back(rowIds_[a]);
      sys.coords.push_back(rowCoords_[a]);
    }
    sys.K = std::move(K[s]);
    sys.f.assign(sys.numDofs(), 0.0);
    systems.push_back(std::move(sys));
  }
  return systems;
}

bool AssembledFeti::setStiffness(const ContactProblem& p) {
  // The same rows (K's row map, or the elements' nodes), pieces and pattern.
  int same = p.elements().is_null() ? p.stiffness()->getRowMap()->isSameAs(*rowMap_) : 1;
  if (!same) return false;  // isSameAs agrees on every rank
  std::vector<LocalCsr> pieceK;
  checkOnEveryRank(*comm_, [&] {
    if (!p.elements().is_null()) same = elementNodes(*p.elements()) == rowNodes_;
    if (!same) return;
    const RankRows rows = readRows(p);
    same = rows.pieces == pieces_;
    if (same) pieceK = pieceMatrices(rows);
    for (size_t s = 0; same && s < pieceK.size(); ++s) {
      const LocalCsr& old = problem->subdomain(static_cast<int>(s)).K;
      same = pieceK[s].rowptr == old.rowptr && pieceK[s].col == old.col;
    }
  });
  int everywhere = 0;
  Teuchos::reduceAll<int, int>(*comm_, Teuchos::REDUCE_MIN, same, Teuchos::outArg(everywhere));
  if (everywhere) problem->setStiffness(pieceK);
  return everywhere != 0;
}

// Every copy of a node goes to its owner, which tells every rank holding a
// copy all of them (ascending subdomains).
void AssembledFeti::buildDirectory() {
  std::vector<std::vector<CopyMessage>> out(size_);
  for (size_t s = 0; s < pieces_.size(); ++s)
    for (size_t l = 0; l < pieces_[s].size(); ++l) {
      const int id = rowIds_[pieces_[s][l]];
      out[ownerOf(offsets_, id)].push_back({id, firstSubdomain_ + static_cast<int>(s), static_cast<int>(l)});
    }
  const auto in = exchangeWithRanks(out, *comm_);
  ownedCopies_.clear();
  for (const auto& list : in)
    for (const auto& m : list) ownedCopies_[m.node].push_back(m);
  for (auto& [id, list] : ownedCopies_)
    std::sort(list.begin(), list.end(), [](const CopyMessage& a, const CopyMessage& b) { return a.subdomain < b.subdomain; });
  std::vector<std::vector<CopyMessage>> answer(size_);
  for (const auto& [id, list] : ownedCopies_) {
    std::set<int> holders;
    for (const auto& m : list) holders.insert(subdomainOwner_[m.subdomain]);
    for (int r : holders) answer[r].insert(answer[r].end(), list.begin(), list.end());
  }
  copies_.clear();
  for (const auto& list : exchangeWithRanks(answer, *comm_))
    for (const auto& m : list) copies_[m.node].push_back({m.subdomain, m.localNode});
}

// The Dirichlet values of the problem's list at the nodes this rank holds
// and at every contact surface node: each value goes to its node's owner,
// which merges them and tells the ranks holding a copy. Collective.
std::map<long long, double> AssembledFeti::distributeDirichlet(const std::vector<std::pair<GO, double>>& dofValues) {
  std::vector<std::vector<DofMessage>> out(size_);
  checkOnEveryRank(*comm_, [&] {
    for (const auto& [dof, value] : dofValues) {
      TRIBOS_REQUIRE(dof >= 0 && std::isfinite(value), "Assembled::ContactProblem: the Dirichlet condition of dof "
                                                           << dof << " = " << value << " on rank " << rank_
                                                           << " (dofs are 3 node + c >= 0, values finite)");
      const int a = rowNode(dof / 3);
      TRIBOS_REQUIRE(a >= 0, "Assembled::ContactProblem: rank " << rank_ << " gives a Dirichlet condition on dof " << dof
                                                               << " (node " << dof / 3
                                                               << "), which is not among its rows of K");
      const int id = rowIds_[a];
      out[ownerOf(offsets_, id)].push_back({3LL * id + dof % 3, value});
    }
  });
  const auto in = exchangeWithRanks(out, *comm_);
  std::map<long long, double> owned;
  checkOnEveryRank(*comm_, [&] {
    for (const auto& list : in)
      for (const auto& m : list) {
        const int id = static_cast<int>(m.dof / 3);
        const GO dof = 3 * ownedNodes_[id - offsets_[rank_]] + m.dof % 3;
        TRIBOS_REQUIRE(ownedCopies_.count(id) > 0, "Assembled::ContactProblem: a Dirichlet condition on dof "
                                                       << dof << ", whose node no element of K touches");
        const auto it = owned.insert({m.dof, m.value});
        TRIBOS_REQUIRE(it.first->second == m.value, "Assembled::ContactProblem: dof "
                                                        << dof << " is given two Dirichlet values, " << it.first->second
                                                        << " and " << m.value);
      }
  });
  // To the ranks holding a copy of the node.
  std::vector<std::vector<DofMessage>> answer(size_);
  for (const auto& [dof, value] : owned) {
    std::set<int> holders;
    for (const auto& m : ownedCopies_.at(static_cast<int>(dof / 3))) holders.insert(subdomainOwner_[m.subdomain]);
    for (int r : holders) answer[r].push_back({dof, value});
  }
  std::map<long long, double> values;
  for (const auto& list : exchangeWithRanks(answer, *comm_))
    for (const auto& m : list) values[m.dof] = m.value;
  // The surface nodes' values on every rank (contact rows leave out fixed
  // directions at their master nodes too).
  std::vector<double> surface;
  for (int id : surfaceNodes_)
    if (ownerOf(offsets_, id) == rank_)
      for (int c = 0; c < 3; ++c) {
        const auto it = owned.find(3LL * id + c);
        if (it != owned.end()) surface.push_back(static_cast<double>(it->first)), surface.push_back(it->second);
      }
  const auto all = allGatherv(surface, *comm_);
  for (size_t k = 0; k + 1 < all.size(); k += 2) values[static_cast<long long>(all[k])] = all[k + 1];
  return values;
}

// f on ownedMap: each node's load on its first copy; on K's row map: the
// rank's contributions as they are.
std::vector<std::vector<double>> AssembledFeti::subdomainLoads(const RCP<const Vector>& f) const {
  std::vector<std::vector<double>> loads(pieces_.size());
  for (size_t s = 0; s < pieces_.size(); ++s) loads[s].assign(3 * pieces_[s].size(), 0.0);
  if (f.is_null()) return loads;
  const bool owned = f->getMap()->isSameAs(*ownedMap_);
  // The rank's rows in any order (an application's owned+shared map lists
  // its owned dofs first, the elements' nodes come ascending).
  int sameRows = 0, local = 0;
  if (!owned) {
    const Map& map = *f->getMap();
    local = map.getNodeNumElements() == rowMap_->getNodeNumElements();
    for (GO dof : rowMap_->getNodeElementList()) local = local && map.isNodeGlobalElement(dof);
    Teuchos::reduceAll<int, int>(*comm_, Teuchos::REDUCE_MIN, local, Teuchos::outArg(sameRows));
  }
  const bool overlap = sameRows != 0;
  checkOnEveryRank(*comm_, [&] {
    TRIBOS_REQUIRE(owned || overlap, "Assembled::ContactProblem: the load is on a map that is neither ownedMap nor K's "
                                     "row map (" << f->getMap()->getNodeNumElements() << " entries on rank " << rank_
                                                 << ")");
  });
  Vector onRows(rowMap_);
  if (owned) onRows.doImport(*f, Import(ownedMap_, rowMap_), Tpetra::INSERT);
  else {
    const auto x = f->getData();
    const Map& map = *f->getMap();
    for (LO i = 0; i < static_cast<LO>(rowMap_->getNodeNumElements()); ++i)
      onRows.replaceLocalValue(i, x[map.getLocalElement(rowMap_->getGlobalElement(i))]);
  }
  const auto v = onRows.getData();
  // A node's load goes to one copy: its first (owned), or this rank's first
  // (the rank's contributions).
  std::vector<char> given(rowNodes_.size(), 0);
  checkOnEveryRank(*comm_, [&] {
    for (size_t s = 0; s < pieces_.size(); ++s)
      for (size_t l = 0; l < pieces_[s].size(); ++l) {
        const int a = pieces_[s][l];
        const int id = rowIds_[a];
        if (owned && copies_.at(id).front().subdomain != firstSubdomain_ + static_cast<int>(s)) continue;
        if (given[a]++) continue;
        for (int c = 0; c < 3; ++c) {
          const double x = v[rowMap_->getLocalElement(3 * rowNodes_[a] + c)];
          TRIBOS_REQUIRE(std::isfinite(x), "Assembled::ContactProblem: the load at dof " << 3 * rowNodes_[a] + c
                                                                                        << " is not finite");
          loads[s][3 * l + c] = x;
        }
      }
  });
  return loads;
}

// The contact constraints of every pair (on every rank), from the search
// on the surfaces gathered from all ranks.
std::vector<Feti::ContactConstraint> AssembledFeti::contactConstraints(const ContactProblem& p) {
  const auto& pairs = p.contactPairs();
  // Facets: (pair, side, count, ids...), side 0 slave, 1 master.
  std::vector<int> facets;
  std::vector<double> nodes;  // (id, application id, x, y, z)
  std::set<int> sent;
  checkOnEveryRank(*comm_, [&] {
    for (size_t k = 0; k < pairs.size(); ++k)
      for (int side = 0; side < 2; ++side) {
        const Surface& s = side == 0 ? pairs[k].slave : pairs[k].master;
        const std::string what = "contact pair " + std::to_string(k) + " ('" + pairs[k].name + "'), its " +
                                 (side == 0 ? "slave" : "master") + " surface";
        TRIBOS_REQUIRE(s.nodesPerFacet == 3 || s.nodesPerFacet == 4,
                       "Assembled::ContactProblem: " << what << ": " << s.nodesPerFacet
                                                     << " nodes per facet (3: triangles, 4: quadrilaterals)");
        TRIBOS_REQUIRE(s.nodes.size() % s.nodesPerFacet == 0,
                       "Assembled::ContactProblem: " << what << ": " << s.nodes.size()
                                                     << " node ids, not a multiple of " << s.nodesPerFacet);
        for (size_t f = 0; f < s.numFacets(); ++f) {
          facets.push_back(static_cast<int>(k)), facets.push_back(side), facets.push_back(s.nodesPerFacet);
          for (int i = 0; i < s.nodesPerFacet; ++i) {
            const GO node = s.nodes[f * s.nodesPerFacet + i];
            const int a = rowNode(node);
            TRIBOS_REQUIRE(a >= 0, "Assembled::ContactProblem: " << what << " names node " << node << ", which rank "
                                                                  << rank_ << "'s rows of K do not hold");
            facets.push_back(rowIds_[a]);
            if (sent.insert(rowIds_[a]).second)
              nodes.insert(nodes.end(), {static_cast<double>(rowIds_[a]), static_cast<double>(node),
                                          rowCoords_[a][0], rowCoords_[a][1], rowCoords_[a][2]});
          }
        }
      }
  });
  const auto allFacets = allGatherv(facets, *comm_);
  const auto allNodes = allGatherv(nodes, *comm_);
  // The surface mesh: its nodes numbered by ascending id.
  std::map<int, std::array<double, 3>> position;
  for (size_t k = 0; k < allNodes.size(); k += 5) {
    const int id = static_cast<int>(allNodes[k]);
    application_[id] = static_cast<GO>(allNodes[k + 1]);
    position[id] = {allNodes[k + 2], allNodes[k + 3], allNodes[k + 4]};
  }
  surfaceNodes_.clear();
  Mesh::Mesh surface;
  std::map<int, int> meshNode;
  for (const auto& [id, x] : position) {
    meshNode[id] = static_cast<int>(surface.coords.size());
    surfaceNodes_.push_back(id);
    surface.coords.push_back(x);
  }
  auto faceName = [](size_t k, int side) { return "pair " + std::to_string(k) + (side == 0 ? " slave" : " master"); };
  std::set<std::vector<int>> seen;  // a facet given by several ranks counts once
  for (size_t k = 0; k < allFacets.size();) {
    const int pair = allFacets[k], side = allFacets[k + 1], count = allFacets[k + 2];
    Mesh::Facet f;
    for (int i = 0; i < count; ++i) f.nodes.push_back(meshNode.at(allFacets[k + 3 + i]));
    k += 3 + count;
    std::vector<int> key = f.nodes;
    std::sort(key.begin(), key.end());
    key.insert(key.begin(), {pair, side});
    if (seen.insert(key).second) surface.faces[faceName(pair, side)].push_back(f);
    if (count == 3) surface.type = Mesh::CellType::Tet4;
  }
  std::vector<Contact::ContactPair> search;
  for (size_t k = 0; k < pairs.size(); ++k) {
    Contact::ContactPair c;
    c.name = pairs[k].name.empty() ? "pair " + std::to_string(k) : pairs[k].name;
    c.slave = faceName(k, 0);
    c.master = pairs[k].master.nodes.empty() ? "" : faceName(k, 1);
    c.glued = pairs[k].glued;
    c.discretization = pairs[k].discretization;
    c.planePoint = pairs[k].planePoint;
    c.planeNormal = pairs[k].planeNormal;
    c.searchDistance = pairs[k].searchDistance;
    TRIBOS_REQUIRE(surface.faces.count(c.slave) > 0, "Assembled::ContactProblem: contact pair " << k << " ('" << c.name
                                                                                               << "') has no slave facets on any rank");
    search.push_back(c);
  }
  std::vector<Feti::ContactConstraint> constraints;
  checkOnEveryRank(*comm_, [&] {
    try {
      constraints = Contact::contactConstraints(surface, search);
    } catch (const Error& e) {
      // The search numbers the surface nodes 0, 1, ...: its messages get
      // the application's node ids.
      std::map<int, GO> names;
      for (size_t m = 0; m < surfaceNodes_.size(); ++m) names[static_cast<int>(m)] = application_.at(surfaceNodes_[m]);
      throw Error("Assembled::ContactProblem: " + Assembled::withApplicationNodes(e.what(), names));
    }
  });
  for (auto& cc : constraints) {
    cc.node = surfaceNodes_[cc.node];
    for (auto& m : cc.master) m.first = surfaceNodes_[m.first];
    for (auto& m : cc.slave) m.first = surfaceNodes_[m.first];
  }
  // The first copy of every surface node, from its owner.
  std::vector<int> first;
  for (int id : surfaceNodes_)
    if (ownerOf(offsets_, id) == rank_) {
      const auto& list = ownedCopies_.at(id);
      first.insert(first.end(), {id, list.front().subdomain, list.front().localNode});
    }
  const auto allFirst = allGatherv(first, *comm_);
  surfaceFirstCopy_.clear();
  for (size_t k = 0; k < allFirst.size(); k += 3) surfaceFirstCopy_[allFirst[k]] = {allFirst[k + 1], allFirst[k + 2]};
  return constraints;
}

AssembledFeti::AssembledFeti(const ContactProblem& p, const Teuchos::ParameterList& fetiParams,
                             const RCP<const Comm>& comm)
    : comm_(comm), rank_(comm->getRank()), size_(comm->getSize()) {
  checkOnEveryRank(*comm_, [&] { numberNodes(p); });
  rowCoords_ = rowCoordinates(*p.coordinates());
  std::vector<Fem::SubdomainSystem> systems;
  checkOnEveryRank(*comm_, [&] { systems = subdomains(p); });
  buildDirectory();
  std::vector<Feti::ContactConstraint> contact;
  if (!p.contactPairs().empty()) contact = contactConstraints(p);
  dirichlet_ = distributeDirichlet(p.dirichlet());
  const auto loads = subdomainLoads(p.load());
  for (size_t s = 0; s < systems.size(); ++s) systems[s].f = loads[s];
  // The rows of B: gluing and Dirichlet rows of the nodes whose first copy
  // is here, and the contact rows of the slave nodes whose first copy is.
  Feti::FetiConstraints fc;
  const std::string gluing =
      fetiParams.isParameter("Gluing") ? fetiParams.get<std::string>("Gluing") : std::string("Orthonormal");
  auto mine = [&](int subdomain) { return subdomainOwner_[subdomain] == rank_; };
  checkOnEveryRank(*comm_, [&] {
    // Every rank holding a node makes its rows; each keeps those whose
    // first copy is its own (orthonormal Dirichlet rows act on every copy).
    for (const auto& [id, list] : copies_)
      Feti::nodeRows(id, list, dirichlet_, gluing, false, [&](const Feti::DualRow& r) {
        if (mine(r.copies.front().subdomain)) fc.rows.push_back(r);
      });
    auto firstCopy = [&](int id) { return surfaceFirstCopy_.at(id); };
    for (const auto& cc : contact) {
      if (!mine(firstCopy(cc.node).subdomain)) continue;
      const GO node = application_.at(cc.node);
      const int a = rowNode(node);
      const std::array<double, 3> x{rowCoords_[a][0], rowCoords_[a][1], rowCoords_[a][2]};
      try {
        Feti::contactRows(cc, firstCopy, dirichlet_, x, false, fc.rows);
      } catch (const Error& e) {
        throw Error("Assembled::ContactProblem: " + withApplicationNodes(e.what()));
      }
      fc.contact.push_back(cc);
    }
  });
  fc.dirichlet = dirichlet_;
  problem = rcp(new Feti::FetiProblem(std::move(systems), std::move(fc), fetiParams, comm_));
}

bool AssembledFeti::setRightHandSides(const ContactProblem& p) {
  auto values = distributeDirichlet(p.dirichlet());
  int same = values.size() == dirichlet_.size() ? 1 : 0;
  for (auto a = values.begin(), b = dirichlet_.begin(); same && a != values.end(); ++a, ++b) same = a->first == b->first;
  int everywhere = 0;
  Teuchos::reduceAll<int, int>(*comm_, Teuchos::REDUCE_MIN, same, Teuchos::outArg(everywhere));
  if (!everywhere) return false;
  const auto loads = subdomainLoads(p.load());
  dirichlet_ = std::move(values);
  problem->setRightHandSides(loads, dirichlet_);
  return true;
}

RCP<Vector> AssembledFeti::displacement(const Fem::NodalVector& u) const {
  const Fem::NodalLayout& layout = u.layout();
  std::vector<GO> dofs;
  for (int i = 0; i < layout.numOwned(); ++i)
    for (int c = 0; c < 3; ++c) dofs.push_back(3 * application_.at(layout.nodes()[i]) + c);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto source = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(dofs), 0, comm_));
  Vector v(source);
  {
    auto x = v.getDataNonConst();
    for (size_t k = 0; k < dofs.size(); ++k) x[k] = u.values()[k];
  }
  auto out = rcp(new Vector(ownedMap_));
  out->doImport(v, Import(source, ownedMap_), Tpetra::INSERT);
  return out;
}

RCP<Vector> AssembledFeti::reaction(const Fem::NodalVector& u, const Contact::ContactNodeResults& contact) const {
  return displacement(
      Contact::supportReactions(problem->assembledProduct(u), problem->assembledLoad(), contact, problem->dirichlet()));
}

RCP<MultiVector> AssembledFeti::contactState(const Contact::ContactNodeResults& c) const {
  std::vector<GO> ids;
  for (int node : c.nodes) ids.push_back(application_.at(node));
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto source = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(ids), 0, comm_));
  MultiVector v(source, NumContactColumns);
  for (size_t k = 0; k < c.nodes.size(); ++k) {
    const LO i = static_cast<LO>(k);
    v.replaceLocalValue(i, NormalTraction, c.normalTraction(k));
    const auto tangential = c.tangentialTraction(k), increment = c.slipIncrement(k);
    for (int d = 0; d < 3; ++d) {
      v.replaceLocalValue(i, TangentialTractionX + d, tangential[d]);
      v.replaceLocalValue(i, SlipX + d, c.slip[3 * k + d]);
      v.replaceLocalValue(i, SlipIncrementX + d, increment[d]);
    }
    v.replaceLocalValue(i, Gap, c.gap[k]);
    v.replaceLocalValue(i, Status, k < c.status.size() ? c.status[k] : 0);
  }
  auto out = rcp(new MultiVector(nodeMap, NumContactColumns));
  out->getVectorNonConst(Status)->putScalar(-1.0);
  out->doImport(v, Import(source, nodeMap), Tpetra::INSERT);
  return out;
}

// ---------------------------------------------------------------------------
// ContactSolver

ContactSolver::ContactSolver() = default;
ContactSolver::~ContactSolver() = default;

ContactSolver::ContactSolver(const RCP<ContactProblem>& problem, const RCP<Teuchos::ParameterList>& params) {
  setParameterList(params);
  setProblem(problem);
}

void ContactSolver::setParameterList(const RCP<Teuchos::ParameterList>& params) {
  const RCP<Teuchos::ParameterList> p = params.is_null() ? Teuchos::parameterList("Tribos") : params;
  parameters_.setParameters(p);
  // The application's K holds no boundary conditions: Dirichlet conditions
  // are rows of B, which is Total FETI.
  const std::string formulation = p->sublist("FETI").get<std::string>("Formulation");
  TRIBOS_REQUIRE(formulation == "TFETI", "Assembled::ContactSolver: FETI/Formulation = "
                                             << formulation
                                             << " is not offered here: an application's K is solved by TFETI "
                                                "(Dirichlet conditions as rows of B)");
  setMyParamList(p);
  feti_.reset();  // the FETI list may have changed
  startAgain_ = true;
  refuseWhatTheSolveWould();
}

RCP<const Teuchos::ParameterList> ContactSolver::getValidParameters() const {
  return Contact::ContactSolver::validParameters();
}

void ContactSolver::setProblem(const RCP<ContactProblem>& problem) {
  problem_ = problem;
  feti_.reset();
  startAgain_ = true;
  solved_ = false;
  refuseWhatTheSolveWould();
}

Contact::PairFriction ContactSolver::pairFriction() const {
  // "Pair <k>" where the list names it, the list's own entries elsewhere
  // (a list of one entry without "Pair <k>" applies to every pair; one
  // with "Pair 0" alone must still give the other pairs the list's own).
  Contact::PairFriction friction = parameters_.getFriction();
  Teuchos::ParameterList own = getMyParamList()->sublist("Friction");
  bool perPair = false;
  for (auto it = own.begin(); it != own.end();) {
    const std::string name = own.name(it++);
    if (own.isSublist(name)) own.remove(name), perPair = true;
  }
  if (perPair && friction.size() < problem_->contactPairs().size())
    friction.resize(problem_->contactPairs().size(), Contact::readPairFriction(own).front());
  return friction;
}

void ContactSolver::refuseWhatTheSolveWould() const {
  if (problem_.is_null() || getMyParamList().is_null() || problem_->contactPairs().empty()) return;
  const Contact::PairFriction friction = pairFriction();
  FrictionLaw law = FrictionLaw::Frictionless;
  try {
    law = Contact::runLaw(friction);
  } catch (const Error& e) {
    throw Error(std::string("Assembled::ContactSolver: Friction: ") + e.what());
  }
  Contact::requireOuterAlgorithmSolves(getMyParamList()->get<std::string>("Outer Algorithm"), law);
}

void ContactSolver::resetHistory() {
  startAgain_ = true;
  previous_ = Fem::NodalVector();
}

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Contact::SolveStatus ContactSolver::solve() {
  TRIBOS_REQUIRE(!problem_.is_null(), "Assembled::ContactSolver::solve: no problem; call setProblem() first");
  if (getMyParamList().is_null()) setParameterList(Teuchos::null);
  refuseWhatTheSolveWould();  // pairs added since setProblem
  const auto comm = problem_->ownedMap()->getComm();
  Teuchos::ParameterList& params = *getMyNonconstParamList();
  const auto t0 = std::chrono::steady_clock::now();
  summary_ = SolveSummary();
  // What changed since the last solve decides what is built again.
  bool rebuild = !feti_ || problem_->pairsVersion() != pairsVersion_;
  bool refactored = false;
  if (!rebuild && problem_->stiffnessVersion() != stiffnessVersion_) {
    // Same rows and pattern: a numeric refactorization, the history goes on.
    rebuild = !feti_->setStiffness(*problem_);
    refactored = !rebuild;
    if (refactored && steps_) steps_->stiffnessChanged();
    stiffnessVersion_ = problem_->stiffnessVersion();
  }
  if (!rebuild && problem_->loadVersion() != loadVersion_)
    rebuild = !feti_->setRightHandSides(*problem_);
  if (rebuild) {
    feti_.reset();
    feti_ = std::make_unique<AssembledFeti>(*problem_, params.sublist("FETI"), comm);
    stiffnessVersion_ = problem_->stiffnessVersion();
    pairsVersion_ = problem_->pairsVersion();
  }
  loadVersion_ = problem_->loadVersion();
  const Contact::PairFriction friction = pairFriction();
  if (startAgain_ || rebuild) {
    stepsBefore_ = startAgain_ || !steps_ ? 0 : stepsBefore_ + steps_->completedSteps();
    steps_ = std::make_unique<Contact::FetiLoadSteps>(feti_->problem, friction, params, out_);
    // A new stiffness (or other conditions) in the middle of a history: the
    // next step's friction acts on the slip since the last one, when the
    // subdomains hold the same nodes.
    if (!startAgain_ && !previous_.empty() &&
        previous_.layout().nodes() == feti_->problem->nodalLayout()->nodes())
      steps_->resumeFrom(previous_);
  }
  startAgain_ = false;
  summary_.rebuilt = rebuild;
  summary_.refactored = refactored;
  summary_.setupSeconds = secondsSince(t0);
  const auto t1 = std::chrono::steady_clock::now();
  const Contact::FetiSolveResult r = steps_->solveNext();
  summary_.solveSeconds = secondsSince(t1);
  u_ = feti_->displacement(r.u);
  reaction_ = feti_->reaction(r.u, r.contact);
  contact_ = feti_->contactState(r.contact);
  summary_.converged = r.verdict.converged;
  summary_.reason = feti_->withApplicationNodes(r.verdict.converged ? r.solverReason : r.verdict.stopReason);
  previous_ = r.u;
  summary_.step = stepsBefore_ + steps_->completedSteps();
  summary_.outerAlgorithm = r.outerAlgorithm;
  summary_.iterations = r.iterations;
  summary_.n_A = r.n_A;
  summary_.rounds = r.rounds;
  summary_.kkt = r.kkt;
  summary_.limit = r.verdict.limit;
  summary_.counts = r.counts;
  summary_.subdomains = feti_->problem->numSubdomains();
  summary_.primalDofs = static_cast<long long>(feti_->problem->primalMap()->getGlobalNumElements());
  summary_.dualDofs = static_cast<long long>(feti_->problem->dualMap()->getGlobalNumElements());
  solved_ = true;
  return r.verdict.converged ? Contact::SolveStatus::Converged : Contact::SolveStatus::Unconverged;
}

RCP<const Vector> ContactSolver::getDisplacement() const {
  TRIBOS_REQUIRE(solved_, "Assembled::ContactSolver: no result; call solve() first");
  return u_;
}

RCP<const Vector> ContactSolver::getReaction() const {
  TRIBOS_REQUIRE(solved_, "Assembled::ContactSolver: no result; call solve() first");
  return reaction_;
}

RCP<const MultiVector> ContactSolver::getContactState() const {
  TRIBOS_REQUIRE(solved_, "Assembled::ContactSolver: no result; call solve() first");
  return contact_;
}

RCP<const Map> ContactSolver::getNodeMap() const {
  TRIBOS_REQUIRE(feti_ != nullptr, "Assembled::ContactSolver: no node map before the first solve()");
  return feti_->nodeMap;
}

const SolveSummary& ContactSolver::getSummary() const {
  TRIBOS_REQUIRE(solved_, "Assembled::ContactSolver: no result; call solve() first");
  return summary_;
}

}  // namespace Assembled
}  // namespace Tribos
