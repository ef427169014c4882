#include "Tribos_Decomposition.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

// The nodes two cells share when they share a face: METIS's ncommon, so that
// the dual graph joins cells through faces only. A mesh of one type here
// (bodies of different types go to METIS one by one).
idx_t facetNodes(const Mesh& mesh) { return static_cast<idx_t>(detail::cellFaces(mesh.type).front().size()); }

// METIS' element pointers and nodes of a mesh, cell after cell.
void metisCells(const Mesh& mesh, std::vector<idx_t>& eptr, std::vector<idx_t>& eind) {
  eind.assign(mesh.connectivity.begin(), mesh.connectivity.end());
  eptr.assign(static_cast<size_t>(mesh.numCells()) + 1, 0);
  for (int e = 0; e < mesh.numCells(); ++e) eptr[e + 1] = eptr[e] + mesh.cellSize(e);
}

// The cells of one body as a mesh of their own (nodes renumbered in
// ascending global order; no faces): what METIS partitions for the body.
Mesh bodyMesh(const Mesh& mesh, int body, std::vector<int>& cells) {
  Mesh sub;
  cells.clear();
  for (int c = 0; c < mesh.numCells(); ++c)
    if (mesh.bodyOf(c) == body) cells.push_back(c);
  std::vector<int> local(mesh.numNodes(), -1);
  for (int c : cells)
    for (int a = 0; a < mesh.cellSize(c); ++a) local[mesh.cell(c)[a]] = 0;
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (local[n] == 0) local[n] = sub.numNodes(), sub.coords.push_back(mesh.coords[n]);
  std::vector<int> nodes;
  for (int c : cells) {
    nodes.clear();
    for (int a = 0; a < mesh.cellSize(c); ++a) nodes.push_back(local[mesh.cell(c)[a]]);
    sub.addCell(mesh.cellType(c), nodes.data());
  }
  return sub;
}

}  // namespace

std::vector<int> partitionMetis(const Mesh& mesh, int numSubdomains) {
  const int ne = mesh.numCells();
  TRIBOS_REQUIRE(numSubdomains >= 1 && numSubdomains <= ne,
                 "METIS partition: need 1 <= subdomains <= cells (" << ne << "), got " << numSubdomains);
  std::vector<int> part(ne, 0);
  if (numSubdomains == 1) return part;
  TRIBOS_REQUIRE(!mesh.mixed(), "METIS partition: the mesh holds cells of several types; partition it body by body "
                                "(partitionMetisByBody)");
  std::vector<idx_t> eptr, eind;
  metisCells(mesh, eptr, eind);
  idx_t nn = mesh.numNodes(), nev = ne, ncommon = facetNodes(mesh);
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

std::vector<int> subdomainsPerBody(const Mesh& mesh, int numSubdomains) {
  const int B = mesh.numBodies();
  if (B == 1) return {numSubdomains};  // partitionMetis checks it against the cells
  std::string names;
  for (int b = 0; b < B; ++b) names += (b ? ", " : "") + mesh.bodyName(b);
  TRIBOS_REQUIRE(numSubdomains >= B, "the mesh has " << B << " bodies (" << names << ") but only " << numSubdomains
                                                    << " subdomain" << (numSubdomains == 1 ? "" : "s")
                                                    << " are asked for; each body needs at least one of its own");
  std::vector<long long> cells(B, 0);
  for (int c = 0; c < mesh.numCells(); ++c) ++cells[mesh.bodyOf(c)];
  const long long N = mesh.numCells(), S = numSubdomains;
  // Body b deserves S n_b / N subdomains: floors first (at least one), then
  // one more for the largest shortfalls S n_b - a_b N, or one less for the
  // largest surpluses, ties to the lower body.
  std::vector<int> count(B);
  long long total = 0;
  for (int b = 0; b < B; ++b) total += count[b] = static_cast<int>(std::max(1LL, S * cells[b] / N));
  auto shortfall = [&](int b) { return S * cells[b] - count[b] * N; };
  for (; total < S; ++total) {
    int best = 0;
    for (int b = 1; b < B; ++b)
      if (shortfall(b) > shortfall(best)) best = b;
    ++count[best];
  }
  for (; total > S; --total) {
    int best = -1;
    for (int b = 0; b < B; ++b)
      if (count[b] > 1 && (best < 0 || shortfall(b) < shortfall(best))) best = b;
    --count[best];
  }
  for (int b = 0; b < B; ++b)
    TRIBOS_REQUIRE(count[b] <= cells[b], "body \"" << mesh.bodyName(b) << "\" has " << cells[b] << " cells but gets "
                                                   << count[b] << " of the " << numSubdomains
                                                   << " subdomains (in proportion to its cells); ask for fewer subdomains");
  return count;
}

namespace {

// Two cells of one body in pieces that share no face (q < start), or
// {-1, -1} when every body of this mesh of one cell type is connected.
std::pair<int, int> disconnectedCells(const Mesh& mesh) {
  const int ne = mesh.numCells();
  std::vector<idx_t> eptr, eind;
  metisCells(mesh, eptr, eind);
  idx_t nev = ne, nn = mesh.numNodes(), ncommon = facetNodes(mesh), numflag = 0;
  idx_t *xadj = nullptr, *adjncy = nullptr;
  const int status = METIS_MeshToDual(&nev, &nn, eptr.data(), eind.data(), &ncommon, &numflag, &xadj, &adjncy);
  TRIBOS_REQUIRE(status == METIS_OK, "METIS_MeshToDual failed with status " << status);
  // Pieces by breadth-first search within each body.
  std::vector<int> piece(ne, -1), firstCell;  // the first cell of each piece
  std::vector<int> queue;
  std::pair<int, int> found{-1, -1};
  for (int start = 0; start < ne && found.first < 0; ++start) {
    if (piece[start] >= 0) continue;
    const int p = static_cast<int>(firstCell.size()), body = mesh.bodyOf(start);
    for (int q : firstCell)
      if (mesh.bodyOf(q) == body && found.first < 0) found = {q, start};
    firstCell.push_back(start);
    piece[start] = p;
    queue.assign(1, start);
    for (size_t k = 0; k < queue.size(); ++k)
      for (idx_t j = xadj[queue[k]]; j < xadj[queue[k] + 1]; ++j) {
        const int n = static_cast<int>(adjncy[j]);
        if (piece[n] < 0 && mesh.bodyOf(n) == body) piece[n] = p, queue.push_back(n);
      }
  }
  METIS_Free(xadj);
  METIS_Free(adjncy);
  return found;
}

}  // namespace

void requireConnectedBodies(const Mesh& mesh) {
  if (mesh.numCells() == 0) return;
  std::pair<int, int> found{-1, -1};
  int body = 0;
  if (!mesh.mixed()) {
    found = disconnectedCells(mesh);
    if (found.first >= 0) body = mesh.bodyOf(found.first);
  } else {
    // Faces of different types have different node counts (METIS' ncommon):
    // body by body, each of one type.
    std::vector<int> cells;
    for (body = 0; body < mesh.numBodies() && found.first < 0; ++body) {
      found = disconnectedCells(bodyMesh(mesh, body, cells));
      if (found.first >= 0) found = {cells[found.first], cells[found.second]};
    }
    --body;
  }
  if (found.first < 0) return;
  throw Error("body \"" + mesh.bodyName(body) + "\" is in several pieces that share no face (cells " +
              std::to_string(found.first) + " and " + std::to_string(found.second) +
              " of the mesh are in different pieces): a subdomain of two pieces has 12 rigid motions, not the 6 "
              "FETI counts; make each piece a body of its own (a physical volume or element block each)");
}


std::vector<int> partitionMetisByBody(const Mesh& mesh, int numSubdomains, std::vector<int>* subdomainBody) {
  requireConnectedBodies(mesh);
  const std::vector<int> count = subdomainsPerBody(mesh, numSubdomains);
  if (subdomainBody) {
    subdomainBody->clear();
    for (int b = 0; b < mesh.numBodies(); ++b) subdomainBody->insert(subdomainBody->end(), count[b], b);
  }
  if (mesh.numBodies() == 1) return partitionMetis(mesh, numSubdomains);
  std::vector<int> part(mesh.numCells(), -1), cells;
  int first = 0;
  for (int b = 0; b < mesh.numBodies(); ++b) {
    const std::vector<int> bodyPart = partitionMetis(bodyMesh(mesh, b, cells), count[b]);
    for (size_t k = 0; k < cells.size(); ++k) part[cells[k]] = first + bodyPart[k];
    first += count[b];
  }
  return part;
}

std::vector<int> partitionStructured(const Mesh& mesh, const BoxSpec& spec, const std::array<int, 3>& split) {
  for (int a = 0; a < 3; ++a)
    TRIBOS_REQUIRE(split[a] >= 1 && spec.cells[a] % split[a] == 0,
                   "structured partition: " << split[a] << " boxes along axis " << "xyz"[a]
                                           << " must divide the " << spec.cells[a] << " cells");
  const std::array<std::array<double, 2>, 3> range = {spec.x, spec.y, spec.z};
  std::vector<int> part(mesh.numCells());
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int npc = mesh.cellSize(c);
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

std::vector<Subdomain> extractSubdomains(const Mesh& mesh, const std::vector<int>& cellPart, int numSubdomains,
                                         int first) {
  TRIBOS_REQUIRE(static_cast<int>(cellPart.size()) == mesh.numCells(), "partition size differs from cell count");
  std::vector<Subdomain> subs(numSubdomains);
  for (int s = 0; s < numSubdomains; ++s) subs[s].id = first + s;
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int s = cellPart[c] - first;
    TRIBOS_REQUIRE(s >= 0 && s < numSubdomains, "cell " << c << " has invalid subdomain " << cellPart[c]);
    subs[s].cells.push_back(c);
  }
  for (Subdomain& s : subs) {
    TRIBOS_REQUIRE(!s.cells.empty(), "subdomain " << s.id << " has no cells");
    for (int c : s.cells) s.nodes.insert(s.nodes.end(), mesh.cell(c), mesh.cell(c) + mesh.cellSize(c));
    std::sort(s.nodes.begin(), s.nodes.end());
    s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
    for (int c : s.cells)
      for (int k = 0; k < mesh.cellSize(c); ++k) s.connectivity.push_back(s.localNode(mesh.cell(c)[k]));
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
