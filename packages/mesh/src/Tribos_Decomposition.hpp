// Tribos_Decomposition.hpp: splitting a mesh into subdomains (METIS or a
// structured grid of boxes) and distributing the subdomains over MPI ranks.
#pragma once

#include <array>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Element-to-subdomain map from METIS (k-way partition of the dual graph in
// which two cells are adjacent when they share a face). Deterministic. A
// mesh of one cell type (partitionMetisByBody splits the others).
std::vector<int> partitionMetis(const Mesh& mesh, int numSubdomains);

// Subdomains of each body when numSubdomains are spread over the bodies in
// proportion to their cell counts (largest remainders), at least one each.
// Refused when there are fewer subdomains than bodies, or when a body gets
// more subdomains than it has cells.
std::vector<int> subdomainsPerBody(const Mesh& mesh, int numSubdomains);

// Refuses a body whose cells form several pieces that share no face (cells
// adjacent as in METIS' dual graph), naming the body and a cell of two
// pieces: FETI's R_s holds the 6 rigid motions of one connected subdomain,
// and a subdomain of two pieces has 12.
void requireConnectedBodies(const Mesh& mesh);

// METIS body by body, so that no subdomain holds cells of two bodies:
// subdomainsPerBody() subdomains each, numbered contiguously in body order
// (subdomainBody[s] is the body of subdomain s). Bodies must be connected
// (requireConnectedBodies). A mesh of one body gets partitionMetis(mesh,
// numSubdomains) itself.
std::vector<int> partitionMetisByBody(const Mesh& mesh, int numSubdomains, std::vector<int>* subdomainBody = nullptr);

// Element-to-subdomain map splitting the box into sx x sy x sz boxes by cell
// centroid; subdomain index = ix + sx (iy + sy iz). Requires each box to own
// whole cells (sx divides nx ...), so the seed brick's 3 unit cubes come out exactly.
std::vector<int> partitionStructured(const Mesh& mesh, const BoxSpec& spec, const std::array<int, 3>& split);

// One subdomain: its cells and a local numbering of its nodes.
struct Subdomain {
  int id = -1;
  std::vector<int> cells;          // global cell ids
  std::vector<int> nodes;          // local node -> global node (sorted)
  std::vector<int> connectivity;   // local node ids of each cell, cell after cell (mesh.cellSize(cells[k]) each)
  int localNode(int globalNode) const;  // -1 if absent
};

// Subdomains first .. first + numSubdomains - 1 (every cell's subdomain
// lies among them), in order.
std::vector<Subdomain> extractSubdomains(const Mesh& mesh, const std::vector<int>& cellPart, int numSubdomains,
                                         int first = 0);

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
