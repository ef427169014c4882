#include "Tribos_Discretization.hpp"

#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>

#include <algorithm>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_MeshBroadcast.hpp"

namespace Tribos {
namespace Mesh {

// The decomposition of the whole mesh, from which every part is cut.
struct WholeDecomposition {
  std::vector<int> cellPart, subdomainBody;
  std::vector<Subdomain> subdomains;   // mesh numbers
  std::vector<long long> nodeIndex;     // per mesh node
  std::vector<int> copyStart;           // per mesh node: its copies, ascending subdomains
  std::vector<NodeCopy> copy;
  std::map<std::string, std::vector<int>> faceNodes;  // every named face's nodes
  RankLayout layout;
};

struct DiscretizationAccess {
  static WholeDecomposition decompose(const Mesh& mesh, const BoxSpec& spec, const DecompositionSpec& dec, int numRanks);
  static Discretization cut(const Mesh& mesh, const WholeDecomposition& whole, const BoxSpec& spec, int rank,
                            std::vector<int>& partOfNode, std::vector<int>& partOfCell);
  static void pack(const Discretization& d, ByteBuffer& b);
  static Discretization unpack(ByteBuffer& b);
  static void finish(Discretization& d);
  // The fields of a part besides its mesh, in the one order that pack and
  // unpack share.
  template <class D, class F>
  static void forEachField(D& d, F&& f) {
    f(d.spec), f(d.cellPart), f(d.subdomainBody), f(d.layout), f(d.myRank), f(d.numMeshNodes_), f(d.numMeshCells_);
    f(d.meshNodes_), f(d.meshCells_), f(d.nodeIndex_), f(d.copyStart_), f(d.copy_);
  }
};

WholeDecomposition DiscretizationAccess::decompose(const Mesh& mesh, const BoxSpec& spec, const DecompositionSpec& dec,
                                                   int numRanks) {
  mesh.checkBodies();
  WholeDecomposition w;
  int S = 0;
  if (dec.partitioner == "Structured") {
    TRIBOS_REQUIRE(mesh.numBodies() == 1, "the Structured partitioner splits one box, but the mesh has "
                                              << mesh.numBodies() << " bodies; use METIS");
    w.cellPart = partitionStructured(mesh, spec, dec.grid);
    S = dec.grid[0] * dec.grid[1] * dec.grid[2];
    w.subdomainBody.assign(S, 0);
  } else if (dec.partitioner == "METIS") {
    w.cellPart = partitionMetisByBody(mesh, dec.subdomains, &w.subdomainBody);
    S = dec.subdomains;
  } else {
    throw Error("partitioner \"" + dec.partitioner + "\" unknown; valid: Structured, METIS");
  }
  w.subdomains = extractSubdomains(mesh, w.cellPart, S);
  w.layout = makeRankLayout(S, numRanks);
  const int N = mesh.numNodes();
  // Copies of every node, ascending subdomains: the first is the owner's.
  w.copyStart.assign(N + 1, 0);
  for (const Subdomain& sd : w.subdomains)
    for (int n : sd.nodes) ++w.copyStart[n + 1];
  for (int n = 0; n < N; ++n) {
    TRIBOS_REQUIRE(w.copyStart[n + 1] > 0, "mesh node " << n << " belongs to no cell");
    w.copyStart[n + 1] += w.copyStart[n];
  }
  w.copy.resize(w.copyStart[N]);
  std::vector<int> at(w.copyStart.begin(), w.copyStart.end() - 1);
  for (const Subdomain& sd : w.subdomains)
    for (size_t l = 0; l < sd.nodes.size(); ++l) w.copy[at[sd.nodes[l]]++] = {sd.id, static_cast<int>(l)};
  auto owner = [&](int n) { return w.layout.owner(w.copy[w.copyStart[n]].subdomain); };
  std::vector<long long> count(numRanks + 1, 0);
  for (int n = 0; n < N; ++n) ++count[owner(n) + 1];
  for (int r = 0; r < numRanks; ++r) count[r + 1] += count[r];
  w.nodeIndex.resize(N);
  for (int n = 0; n < N; ++n) w.nodeIndex[n] = count[owner(n)]++;
  for (const auto& name : mesh.faceNames()) w.faceNodes[name] = mesh.faceNodes(name);
  return w;
}

// The part of `rank`. partOfNode and partOfCell are scratch of the whole
// mesh's sizes, all -1 on entry and on return.
Discretization DiscretizationAccess::cut(const Mesh& mesh, const WholeDecomposition& w, const BoxSpec& spec, int rank,
                                         std::vector<int>& partOfNode, std::vector<int>& partOfCell) {
  Discretization d;
  d.spec = spec;
  d.layout = w.layout;
  d.myRank = rank;
  d.subdomainBody = w.subdomainBody;
  d.numMeshNodes_ = mesh.numNodes();
  d.numMeshCells_ = mesh.numCells();
  const int first = w.layout.firstSubdomain(rank), end = w.layout.firstSubdomain(rank + 1);
  for (int s = first; s < end; ++s) {
    const Subdomain& sd = w.subdomains[s];
    d.meshCells_.insert(d.meshCells_.end(), sd.cells.begin(), sd.cells.end());
    d.meshNodes_.insert(d.meshNodes_.end(), sd.nodes.begin(), sd.nodes.end());
    d.cellPart.insert(d.cellPart.end(), sd.cells.size(), s);
  }
  std::sort(d.meshNodes_.begin(), d.meshNodes_.end());
  d.meshNodes_.erase(std::unique(d.meshNodes_.begin(), d.meshNodes_.end()), d.meshNodes_.end());
  for (size_t n = 0; n < d.meshNodes_.size(); ++n) partOfNode[d.meshNodes_[n]] = static_cast<int>(n);
  for (size_t c = 0; c < d.meshCells_.size(); ++c) partOfCell[d.meshCells_[c]] = static_cast<int>(c);

  Mesh& part = d.part;
  part.type = mesh.type;
  part.bodyNames = mesh.bodyNames;
  for (int n : d.meshNodes_) part.coords.push_back(mesh.coords[n]);
  std::vector<int> nodes;
  for (int c : d.meshCells_) {
    nodes.clear();
    for (int a = 0; a < mesh.cellSize(c); ++a) nodes.push_back(partOfNode[mesh.cell(c)[a]]);
    part.addCell(mesh.cellType(c), nodes.data());
    if (!mesh.cellBody.empty()) part.cellBody.push_back(mesh.cellBody[c]);
  }
  for (const auto& [name, facets] : mesh.faces) {
    auto& mine = part.faces[name];
    for (const Facet& f : facets) {
      if (partOfCell[f.cell] < 0) continue;
      Facet g{{}, partOfCell[f.cell]};
      for (int n : f.nodes) g.nodes.push_back(partOfNode[n]);
      mine.push_back(g);
    }
    auto& nodes = part.partFaceNodes[name];
    for (int n : w.faceNodes.at(name))
      if (partOfNode[n] >= 0) nodes.push_back(partOfNode[n]);
  }
  for (const auto& [name, set] : mesh.nodeSets) {
    auto& mine = part.nodeSets[name];
    for (int n : set)
      if (partOfNode[n] >= 0) mine.push_back(partOfNode[n]);
  }
  d.copyStart_.push_back(0);
  for (int n : d.meshNodes_) {
    d.nodeIndex_.push_back(w.nodeIndex[n]);
    d.copy_.insert(d.copy_.end(), w.copy.begin() + w.copyStart[n], w.copy.begin() + w.copyStart[n + 1]);
    d.copyStart_.push_back(static_cast<int>(d.copy_.size()));
  }
  for (int n : d.meshNodes_) partOfNode[n] = -1;
  for (int c : d.meshCells_) partOfCell[c] = -1;
  finish(d);
  return d;
}

// What a part derives from the rest: its subdomains, and the owner of each
// node (the rank of its first copy's subdomain).
void DiscretizationAccess::finish(Discretization& d) {
  const int first = d.firstLocalSubdomain();
  d.localSubdomains = extractSubdomains(d.part, d.cellPart, d.endLocalSubdomain() - first, first);
  d.nodeOwner_.clear();
  d.ownedNodes_.clear();
  for (int n = 0; n < d.part.numNodes(); ++n) {
    d.nodeOwner_.push_back(d.layout.owner(d.copy_[d.copyStart_[n]].subdomain));
    if (d.nodeOwner_[n] == d.myRank) d.ownedNodes_.push_back(n);
  }
}

void DiscretizationAccess::pack(const Discretization& d, ByteBuffer& b) {
  packMesh(d.part, b);
  forEachField(d, [&](const auto& field) { b.put(field); });
}

Discretization DiscretizationAccess::unpack(ByteBuffer& b) {
  Discretization d;
  d.part = unpackMesh(b);
  forEachField(d, [&](auto& field) { b.read(field); });
  TRIBOS_REQUIRE(b.consumed(), "Discretization: the packed part has bytes left over");
  finish(d);
  return d;
}

Discretization::Discretization(const Mesh& m, const BoxSpec& s, const DecompositionSpec& dec, int numRanks, int rank) {
  const WholeDecomposition whole = DiscretizationAccess::decompose(m, s, dec, numRanks);
  std::vector<int> partOfNode(m.numNodes(), -1), partOfCell(m.numCells(), -1);
  *this = DiscretizationAccess::cut(m, whole, s, rank, partOfNode, partOfCell);
}

Discretization Discretization::scatter(const Mesh& meshOnRoot, const BoxSpec& spec, const DecompositionSpec& dec,
                                       const Comm& comm, int root) {
  const int rank = comm.getRank(), size = comm.getSize();
  if (rank != root) {
    // The root's refusal (or nothing), then the part.
    const std::string error = agreeOnError(comm, "");
    if (!error.empty()) throw CollectiveError(error);
    ByteBuffer b = receiveBuffer(root, comm);
    return DiscretizationAccess::unpack(b);
  }
  std::string error;
  WholeDecomposition whole;
  try {
    whole = DiscretizationAccess::decompose(meshOnRoot, spec, dec, size);
  } catch (const Error& e) {
    error = e.what();
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError(error);
  std::vector<int> partOfNode(meshOnRoot.numNodes(), -1), partOfCell(meshOnRoot.numCells(), -1);
  for (int r = 0; r < size; ++r) {
    if (r == root) continue;
    ByteBuffer b;
    DiscretizationAccess::pack(DiscretizationAccess::cut(meshOnRoot, whole, spec, r, partOfNode, partOfCell), b);
    sendBuffer(b, r, comm);
  }
  return DiscretizationAccess::cut(meshOnRoot, whole, spec, root, partOfNode, partOfCell);
}

const Subdomain& Discretization::subdomain(int s) const {
  TRIBOS_REQUIRE(s >= firstLocalSubdomain() && s < endLocalSubdomain(),
                 "subdomain " << s << " is not on rank " << myRank);
  return localSubdomains[s - firstLocalSubdomain()];
}

int Discretization::partNode(int meshNode) const {
  auto it = std::lower_bound(meshNodes_.begin(), meshNodes_.end(), meshNode);
  return (it != meshNodes_.end() && *it == meshNode) ? static_cast<int>(it - meshNodes_.begin()) : -1;
}

std::vector<double> Discretization::askOwners(const std::vector<int>& asked, int width,
                                              const std::function<void(int, double*)>& answer,
                                              const Comm& commRef) const {
  // The owned nodes as a one-to-one map; the asked ones (each once) import
  // from it: Tpetra's directory finds their owners.
  const auto comm = Teuchos::rcpFromRef(commRef);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  std::vector<GO> owned;
  for (int n : ownedNodes_) owned.push_back(meshNodes_[n]);
  auto source = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(owned), 0, comm));
  std::vector<GO> wanted(asked.begin(), asked.end());
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  auto target = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(wanted), 0, comm));
  MultiVector values(source, static_cast<size_t>(width)), received(target, static_cast<size_t>(width));
  std::vector<double> row(width);
  for (size_t i = 0; i < ownedNodes_.size(); ++i) {
    answer(ownedNodes_[i], row.data());
    for (int k = 0; k < width; ++k) values.replaceLocalValue(static_cast<LO>(i), k, row[k]);
  }
  received.doImport(values, Import(source, target), Tpetra::INSERT);
  const auto columns = received.get2dView();
  std::vector<double> out(asked.size() * static_cast<size_t>(width));
  for (size_t i = 0; i < asked.size(); ++i) {
    const LO l = target->getLocalElement(asked[i]);
    for (int k = 0; k < width; ++k) out[i * width + k] = columns[k][l];
  }
  return out;
}

}  // namespace Mesh
}  // namespace Tribos
