// Tribos_Decomposition.hpp: splitting a mesh into subdomains (METIS or a
// structured grid of boxes) and distributing the subdomains over MPI ranks.
#pragma once

#include <array>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Element-to-subdomain map from METIS (k-way partition of the dual graph in
// which two cells are adjacent when they share a face). Deterministic.
std::vector<int> partitionMetis(const Mesh& mesh, int numSubdomains);

// Element-to-subdomain map splitting the box into sx x sy x sz boxes by cell
// centroid; subdomain index = ix + sx (iy + sy iz). Requires each box to own
// whole cells (sx divides nx ...), so the seed brick's 3 unit cubes come out exactly.
std::vector<int> partitionStructured(const Mesh& mesh, const BoxSpec& spec, const std::array<int, 3>& split);

// One subdomain: its cells and a local numbering of its nodes.
struct Subdomain {
  int id = -1;
  std::vector<int> cells;          // global cell ids
  std::vector<int> nodes;          // local node -> global node (sorted)
  std::vector<int> connectivity;   // local node ids, nodesPerCell per cell
  int localNode(int globalNode) const;  // -1 if absent
};

std::vector<Subdomain> extractSubdomains(const Mesh& mesh, const std::vector<int>& cellPart, int numSubdomains);

// Subdomains are given to ranks in contiguous blocks as even as possible:
// rank r owns [firstSubdomain(r), firstSubdomain(r+1)).
struct RankLayout {
  int numSubdomains = 0, numRanks = 1;
  int firstSubdomain(int rank) const { return static_cast<int>((static_cast<long long>(numSubdomains) * rank) / numRanks); }
  int owner(int subdomain) const;
};
RankLayout makeRankLayout(int numSubdomains, int numRanks);

}  // namespace Mesh
}  // namespace Tribos
