#include "Tribos_Decomposition.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Mesh {

std::vector<int> partitionMetis(const Mesh& mesh, int numSubdomains) {
  const int ne = mesh.numCells();
  TRIBOS_REQUIRE(numSubdomains >= 1 && numSubdomains <= ne,
                 "METIS partition: need 1 <= subdomains <= cells (" << ne << "), got " << numSubdomains);
  std::vector<int> part(ne, 0);
  if (numSubdomains == 1) return part;
  const int npc = mesh.nodesPerCell();
  std::vector<idx_t> eptr(ne + 1), eind(mesh.connectivity.begin(), mesh.connectivity.end());
  for (int e = 0; e <= ne; ++e) eptr[e] = static_cast<idx_t>(e) * npc;
  idx_t nn = mesh.numNodes(), nev = ne, ncommon = mesh.type == CellType::Tet4 ? 3 : 4;
  idx_t nparts = numSubdomains, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;       // reproducible partitions
  options[METIS_OPTION_CONTIG] = 1;     // connected subdomains keep R_s at 6 modes
  std::vector<idx_t> epart(ne), npart(nn);
  const int status = METIS_PartMeshDual(&nev, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                                        nullptr, options, &objval, epart.data(), npart.data());
  TRIBOS_REQUIRE(status == METIS_OK, "METIS_PartMeshDual failed with status " << status << " for "
                                                                              << numSubdomains << " subdomains");
  for (int e = 0; e < ne; ++e) part[e] = static_cast<int>(epart[e]);
  return part;
}

std::vector<int> partitionStructured(const Mesh& mesh, const BoxSpec& spec, const std::array<int, 3>& split) {
  for (int a = 0; a < 3; ++a)
    TRIBOS_REQUIRE(split[a] >= 1 && spec.cells[a] % split[a] == 0,
                   "structured partition: " << split[a] << " boxes along axis " << "xyz"[a]
                                           << " must divide the " << spec.cells[a] << " cells");
  const std::array<std::array<double, 2>, 3> range = {spec.x, spec.y, spec.z};
  std::vector<int> part(mesh.numCells());
  const int npc = mesh.nodesPerCell();
  for (int c = 0; c < mesh.numCells(); ++c) {
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      double centroid = 0;
      for (int k = 0; k < npc; ++k) centroid += mesh.coords[mesh.cell(c)[k]][a] / npc;
      const double t = (centroid - range[a][0]) / (range[a][1] - range[a][0]);
      idx[a] = std::min(split[a] - 1, static_cast<int>(std::floor(t * split[a])));
    }
    part[c] = idx[0] + split[0] * (idx[1] + split[1] * idx[2]);
  }
  return part;
}

int Subdomain::localNode(int globalNode) const {
  auto it = std::lower_bound(nodes.begin(), nodes.end(), globalNode);
  return (it != nodes.end() && *it == globalNode) ? static_cast<int>(it - nodes.begin()) : -1;
}

std::vector<Subdomain> extractSubdomains(const Mesh& mesh, const std::vector<int>& cellPart, int numSubdomains) {
  TRIBOS_REQUIRE(static_cast<int>(cellPart.size()) == mesh.numCells(), "partition size differs from cell count");
  std::vector<Subdomain> subs(numSubdomains);
  for (int s = 0; s < numSubdomains; ++s) subs[s].id = s;
  for (int c = 0; c < mesh.numCells(); ++c) {
    TRIBOS_REQUIRE(cellPart[c] >= 0 && cellPart[c] < numSubdomains, "cell " << c << " has invalid subdomain " << cellPart[c]);
    subs[cellPart[c]].cells.push_back(c);
  }
  const int npc = mesh.nodesPerCell();
  for (Subdomain& s : subs) {
    TRIBOS_REQUIRE(!s.cells.empty(), "subdomain " << s.id << " has no cells");
    for (int c : s.cells) s.nodes.insert(s.nodes.end(), mesh.cell(c), mesh.cell(c) + npc);
    std::sort(s.nodes.begin(), s.nodes.end());
    s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
    for (int c : s.cells)
      for (int k = 0; k < npc; ++k) s.connectivity.push_back(s.localNode(mesh.cell(c)[k]));
  }
  return subs;
}

int RankLayout::owner(int subdomain) const {
  int r = static_cast<int>((static_cast<long long>(subdomain) * numRanks) / numSubdomains);
  while (r + 1 < numRanks && firstSubdomain(r + 1) <= subdomain) ++r;
  while (r > 0 && firstSubdomain(r) > subdomain) --r;
  return r;
}

RankLayout makeRankLayout(int numSubdomains, int numRanks) {
  TRIBOS_REQUIRE(numSubdomains >= numRanks, "the run has " << numRanks << " MPI ranks but only " << numSubdomains
                                                           << " subdomains; use at most as many ranks as subdomains");
  RankLayout layout;
  layout.numSubdomains = numSubdomains;
  layout.numRanks = numRanks;
  return layout;
}

}  // namespace Mesh
}  // namespace Tribos
