// Tribos_Discretization.hpp: a rank's part of a mesh decomposed into
// subdomains, the subdomains distributed over the ranks.
//
// The whole mesh is decomposed once (METIS or a structured grid), then each
// rank keeps its part: the cells of its subdomains and their nodes, as a
// Mesh in a numbering of its own ("part nodes", "part cells"), with the
// mesh numbers of both. Nothing that grows with the whole mesh is kept on
// every rank. What a rank needs to know about its nodes from the other
// ranks comes with its part: the owner of each node, its row in the output
// files, and every subdomain that holds it (with its number there), which
// is what the rows of B gluing the copies of a node name.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "Tribos_Decomposition.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Mesh {

struct DecompositionSpec {
  std::string partitioner = "Structured";  // "Structured" | "METIS"
  std::array<int, 3> grid{1, 1, 1};         // for Structured
  int subdomains = 1;                       // for METIS
  int size = 0;                             // H, when chosen by a subdomain size (cells per edge); else 0
};

// The copy of a node in one subdomain: the subdomain and the node's number
// in it (its place in Subdomain::nodes).
struct NodeCopy {
  int subdomain = -1;
  int localNode = -1;
};

// METIS partitions each body of the mesh on its own (partitionMetisByBody):
// a subdomain never holds cells of two bodies, and every body must be
// connected. The Structured partitioner splits a box: one body only.
class Discretization {
 public:
  // This rank's part, cut from a mesh every rank holds (tests, applications
  // that build the mesh on every rank).
  Discretization(const Mesh& mesh, const BoxSpec& spec, const DecompositionSpec& dec, int numRanks, int myRank);
  // The root decomposes the mesh it holds and sends every rank its part, one
  // at a time; the other ranks' `meshOnRoot` is not read. A refusal of the
  // decomposition is a CollectiveError on every rank. Collective.
  static Discretization scatter(const Mesh& meshOnRoot, const BoxSpec& spec, const DecompositionSpec& dec,
                                const Comm& comm, int root = 0);

  Mesh part;                           // the rank's part of the mesh: its cells in subdomain order, its nodes ascending by mesh number
  BoxSpec spec;
  std::vector<int> cellPart;           // part cell -> subdomain
  std::vector<int> subdomainBody;      // every subdomain -> body (mesh.bodyName); contiguous per body
  std::vector<Subdomain> localSubdomains;  // this rank's subdomains in order; nodes and cells are part numbers
  RankLayout layout;
  int myRank = 0;

  int numSubdomains() const { return layout.numSubdomains; }
  int firstLocalSubdomain() const { return layout.firstSubdomain(myRank); }
  int endLocalSubdomain() const { return layout.firstSubdomain(myRank + 1); }
  // A subdomain of this rank, by its number.
  const Subdomain& subdomain(int s) const;

  // The whole mesh's counts.
  int numMeshNodes() const { return numMeshNodes_; }
  int numMeshCells() const { return numMeshCells_; }
  // Part node -> mesh node (ascending), part cell -> mesh cell.
  const std::vector<int>& meshNodes() const { return meshNodes_; }
  int meshNode(int partNode) const { return meshNodes_[partNode]; }
  int meshCell(int partCell) const { return meshCells_[partCell]; }
  // The part node of a mesh node, -1 when the part does not hold it.
  int partNode(int meshNode) const;

  // Per part node: the owner, the rank of the lowest-numbered subdomain
  // holding the node (its first copy).
  const std::vector<int>& nodeOwner() const { return nodeOwner_; }
  // Part nodes owned by this rank, ascending.
  const std::vector<int>& ownedNodes() const { return ownedNodes_; }
  // Per part node, its row in the rank-contiguous node numbering: the nodes
  // owned by rank 0 first, ascending, then those of rank 1, ... (distributed
  // maps and output files).
  const std::vector<long long>& nodeIndex() const { return nodeIndex_; }
  // Every subdomain holding part node n, ascending, with n's number there.
  std::vector<NodeCopy> copies(int n) const {
    return {copy_.begin() + copyStart_[n], copy_.begin() + copyStart_[n + 1]};
  }

  // For each mesh node of `meshNodes` (any rank's), `width` numbers that its
  // owner writes by `answer(partNode, out)`. Collective: every rank asks
  // (possibly nothing) and answers for the nodes it owns.
  std::vector<double> askOwners(const std::vector<int>& meshNodes, int width,
                                const std::function<void(int partNode, double* out)>& answer, const Comm& comm) const;

 private:
  Discretization() = default;
  friend struct DiscretizationAccess;
  int numMeshNodes_ = 0, numMeshCells_ = 0;
  std::vector<int> meshNodes_, meshCells_;
  std::vector<int> nodeOwner_, ownedNodes_;
  std::vector<long long> nodeIndex_;
  std::vector<int> copyStart_;
  std::vector<NodeCopy> copy_;
};

}  // namespace Mesh
}  // namespace Tribos
