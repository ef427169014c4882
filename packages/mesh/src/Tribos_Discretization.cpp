#include "Tribos_Discretization.hpp"

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Mesh {

Discretization::Discretization(Mesh m, const BoxSpec& s, const DecompositionSpec& dec, int numRanks, int rank)
    : mesh(std::move(m)), spec(s), myRank(rank) {
  mesh.checkBodies();
  int S = 0;
  if (dec.partitioner == "Structured") {
    TRIBOS_REQUIRE(mesh.numBodies() == 1, "the Structured partitioner splits one box, but the mesh has "
                                              << mesh.numBodies() << " bodies; use METIS");
    cellPart = partitionStructured(mesh, spec, dec.grid);
    S = dec.grid[0] * dec.grid[1] * dec.grid[2];
    subdomainBody.assign(S, 0);
  } else if (dec.partitioner == "METIS") {
    cellPart = partitionMetisByBody(mesh, dec.subdomains, &subdomainBody);
    S = dec.subdomains;
  } else {
    throw Error("partitioner \"" + dec.partitioner + "\" unknown; valid: Structured, METIS");
  }
  subdomains = extractSubdomains(mesh, cellPart, S);
  layout = makeRankLayout(S, numRanks);
  nodeFirstSubdomain_.assign(mesh.numNodes(), S);
  for (const Subdomain& sd : subdomains)
    for (int n : sd.nodes)
      if (sd.id < nodeFirstSubdomain_[n]) nodeFirstSubdomain_[n] = sd.id;
  nodeOwner_.resize(mesh.numNodes());
  for (int n = 0; n < mesh.numNodes(); ++n) {
    TRIBOS_REQUIRE(nodeFirstSubdomain_[n] < S, "mesh node " << n << " belongs to no cell");
    nodeOwner_[n] = layout.owner(nodeFirstSubdomain_[n]);
    if (nodeOwner_[n] == myRank) ownedNodes_.push_back(n);
  }
  std::vector<long long> count(numRanks + 1, 0);
  for (int n = 0; n < mesh.numNodes(); ++n) ++count[nodeOwner_[n] + 1];
  for (int r = 0; r < numRanks; ++r) count[r + 1] += count[r];
  nodeIndex_.resize(mesh.numNodes());
  for (int n = 0; n < mesh.numNodes(); ++n) nodeIndex_[n] = count[nodeOwner_[n]]++;
}

std::vector<int> Discretization::localCells() const {
  std::vector<int> cells;
  for (int s = firstLocalSubdomain(); s < endLocalSubdomain(); ++s)
    cells.insert(cells.end(), subdomains[s].cells.begin(), subdomains[s].cells.end());
  return cells;
}

}  // namespace Mesh
}  // namespace Tribos
