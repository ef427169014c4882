// Tribos_Discretization.hpp: a mesh together with its decomposition into
// subdomains and the distribution of subdomains over ranks. Replicated on
// every rank (cheap for structured meshes), so every rank can answer
// "who owns node n" without communication.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Decomposition.hpp"
#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

struct DecompositionSpec {
  std::string partitioner = "Structured";  // "Structured" | "METIS"
  std::array<int, 3> grid{1, 1, 1};         // for Structured
  int subdomains = 1;                       // for METIS
  int size = 0;                             // H, when chosen by a subdomain size (cells per edge); else 0
};

// METIS partitions each body of the mesh on its own (partitionMetisByBody):
// a subdomain never holds cells of two bodies, and every body must be
// connected. The Structured partitioner splits a box: one body only.
class Discretization {
 public:
  Discretization(Mesh mesh, const BoxSpec& spec, const DecompositionSpec& dec, int numRanks, int myRank);

  Mesh mesh;
  BoxSpec spec;
  std::vector<int> cellPart;             // cell -> subdomain
  std::vector<int> subdomainBody;        // subdomain -> body (mesh.bodyName); contiguous per body
  std::vector<Subdomain> subdomains;     // all subdomains (replicated)
  RankLayout layout;
  int myRank = 0;

  int numSubdomains() const { return static_cast<int>(subdomains.size()); }
  int firstLocalSubdomain() const { return layout.firstSubdomain(myRank); }
  int endLocalSubdomain() const { return layout.firstSubdomain(myRank + 1); }
  // The owner of a node is the rank of the lowest-numbered subdomain holding it.
  const std::vector<int>& nodeOwner() const { return nodeOwner_; }
  const std::vector<int>& nodeFirstSubdomain() const { return nodeFirstSubdomain_; }
  // Nodes owned by this rank, ascending.
  const std::vector<int>& ownedNodes() const { return ownedNodes_; }
  // Rank-contiguous node numbering: the nodes of rank 0 first, ascending,
  // then those of rank 1, ... Used for distributed maps and output files.
  const std::vector<long long>& nodeIndex() const { return nodeIndex_; }
  // Cells of the subdomains of this rank, in subdomain order.
  std::vector<int> localCells() const;

 private:
  std::vector<int> nodeOwner_, nodeFirstSubdomain_, ownedNodes_;
  std::vector<long long> nodeIndex_;
};

}  // namespace Mesh
}  // namespace Tribos
