#include "Tribos_Assembly.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>

#include <algorithm>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"

namespace Tribos {
namespace Fem {

std::vector<Point> cellCoordinates(const Mesh::Mesh& mesh, int cell) {
  std::vector<Point> X(mesh.cellSize(cell));
  for (int a = 0; a < mesh.cellSize(cell); ++a) X[a] = mesh.coords[mesh.cell(cell)[a]];
  return X;
}

namespace {

// A cell of a subdomain: its local nodes in sub.connectivity and their count.
struct SubdomainCell {
  const int* nodes;
  int count;
};

// Calls f(k, cell) for the subdomain's cells k in [first, end), walking
// sub.connectivity cell by cell (cells of several types differ in size).
template <class F>
void forEachCell(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, size_t first, size_t end, F&& f) {
  size_t at = 0;
  for (size_t k = 0; k < first; ++k) at += mesh.cellSize(sub.cells[k]);
  for (size_t k = first; k < end; ++k) {
    const int count = mesh.cellSize(sub.cells[k]);
    f(k, SubdomainCell{&sub.connectivity[at], count});
    at += count;
  }
}

// Sparsity of the dof graph: dofs of nodes sharing a cell are coupled.
LocalCsr dofPattern(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub) {
  std::vector<std::vector<int>> adj(sub.nodes.size());
  forEachCell(mesh, sub, 0, sub.cells.size(), [&](size_t, const SubdomainCell& cell) {
    for (int a = 0; a < cell.count; ++a)
      for (int b = 0; b < cell.count; ++b) adj[cell.nodes[a]].push_back(cell.nodes[b]);
  });
  const int numNodes = static_cast<int>(sub.nodes.size());
  LocalCsr A;
  A.rows = A.cols = 3 * numNodes;
  A.rowptr.assign(A.rows + 1, 0);
  for (int n = 0; n < numNodes; ++n) {
    auto& nb = adj[n];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    for (int c = 0; c < 3; ++c) {
      for (int m : nb)
        for (int d = 0; d < 3; ++d) A.col.push_back(3 * m + d);
      A.rowptr[3 * n + c + 1] = static_cast<int>(A.col.size());
    }
  }
  A.val.assign(A.col.size(), 0.0);
  return A;
}

// Adds the element matrix Ke (3 npc x 3 npc, row-major) of the cell with
// local nodes ln. In dofPattern's layout the three rows of a node hold the
// same columns and a node's three columns are adjacent, so one search per
// pair of nodes places a whole 3 x 3 block.
void addElement(LocalCsr& A, const int* ln, int npc, const std::vector<double>& Ke) {
  const int n = 3 * npc;
  for (int a = 0; a < npc; ++a) {
    const int row = 3 * ln[a];
    auto first = A.col.begin() + A.rowptr[row], last = A.col.begin() + A.rowptr[row + 1];
    for (int b = 0; b < npc; ++b) {
      const int offset = static_cast<int>(std::lower_bound(first, last, 3 * ln[b]) - first);
      for (int c = 0; c < 3; ++c) {
        double* v = &A.val[A.rowptr[row + c] + offset];
        const double* ke = &Ke[(3 * a + c) * n + 3 * b];
        v[0] += ke[0], v[1] += ke[1], v[2] += ke[2];
      }
    }
  }
}

}  // namespace

LocalCsr assembleCellMatrices(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const ElementMatrix& elementMatrix,
                              size_t first, size_t end) {
  LocalCsr A = dofPattern(mesh, sub);
  forEachCell(mesh, sub, first, end, [&](size_t k, const SubdomainCell& cell) {
    addElement(A, cell.nodes, cell.count, elementMatrix(sub.cells[k], cellCoordinates(mesh, sub.cells[k])));
  });
  return A;
}

std::vector<double> subdomainLoad(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const LoadCase& loads) {
  std::vector<double> f(3 * sub.nodes.size(), 0.0);
  const bool hasVolumeForce = loads.volumeForce[0] != 0 || loads.volumeForce[1] != 0 || loads.volumeForce[2] != 0;
  if (hasVolumeForce)
    forEachCell(mesh, sub, 0, sub.cells.size(), [&](size_t k, const SubdomainCell& cell) {
      const int c = sub.cells[k];
      const auto fe = cellVolumeForces(mesh.cellType(c), cellCoordinates(mesh, c), loads.volumeForce);
      for (int a = 0; a < 3 * cell.count; ++a) f[3 * cell.nodes[a / 3] + a % 3] += fe[a];
    });
  // Tractions act on the facets whose cell belongs to this subdomain.
  std::vector<char> mine(mesh.numCells(), 0);
  for (int c : sub.cells) mine[c] = 1;
  for (const auto& t : loads.tractions)
    for (const Mesh::Facet& facet : mesh.face(t.face)) {
      if (!mine[facet.cell]) continue;
      std::vector<Point> X;
      for (int n : facet.nodes) X.push_back(mesh.coords[n]);
      const auto fe = facetTractionForces(X, t.traction);
      for (size_t a = 0; a < facet.nodes.size(); ++a)
        for (int d = 0; d < 3; ++d) f[3 * sub.localNode(facet.nodes[a]) + d] += fe[3 * a + d];
    }
  return f;
}

namespace {

// K and f of the subdomain with the element matrices of the cells
// [first, end) only.
SubdomainSystem assembleCells(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyMaterials& mat,
                              const LoadCase& loads, size_t first, size_t end) {
  SubdomainSystem sys;
  sys.id = sub.id;
  sys.nodes = sub.nodes;
  const int nl = static_cast<int>(sub.nodes.size());
  sys.K = assembleCellMatrices(
      mesh, sub,
      [&](int cell, const std::vector<Point>& X) { return elementStiffness(mesh.cellType(cell), X, mat.ofCell(mesh, cell)); },
      first, end);
  sys.f = subdomainLoad(mesh, sub, loads);
  sys.coords.resize(nl);
  for (int n = 0; n < nl; ++n) sys.coords[n] = mesh.coords[sub.nodes[n]];
  sys.R = rigidBodyModes(sys.coords);
  return sys;
}

}  // namespace

SubdomainSystem assembleSubdomain(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyMaterials& mat,
                                  const LoadCase& loads) {
  return assembleCells(mesh, sub, mat, loads, 0, sub.cells.size());
}

SubdomainSystem assembleSubdomain(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyMaterials& mat,
                                  const LoadCase& loads, const Comm& comm) {
  const size_t n = sub.cells.size(), P = comm.getSize(), rank = comm.getRank();
  SubdomainSystem sys;
  // A cell refused on one rank must not leave the others in the sum.
  checkOnEveryRank(comm, [&] { sys = assembleCells(mesh, sub, mat, loads, n * rank / P, n * (rank + 1) / P); });
  if (P > 1)
    MPI_Allreduce(MPI_IN_PLACE, sys.K.val.data(), static_cast<int>(sys.K.val.size()), MPI_DOUBLE, MPI_SUM,
                  rawComm(comm));
  return sys;
}

SubdomainSystem assembleSubdomain(const Mesh::Discretization& disc, int s, const BodyMaterials& mat,
                                  const LoadCase& loads) {
  SubdomainSystem sys = assembleSubdomain(disc.part, disc.subdomain(s), mat, loads);
  for (int& n : sys.nodes) n = disc.meshNode(n);
  return sys;
}

std::vector<double> subdomainLoad(const Mesh::Discretization& disc, int s, const LoadCase& loads) {
  return subdomainLoad(disc.part, disc.subdomain(s), loads);
}

RCP<CrsMatrix> toTpetra(const LocalCsr& A, const RCP<const Comm>& comm) {
  TRIBOS_REQUIRE(comm->getSize() == 1, "toTpetra expects a serial communicator");
  auto map = rcp(new Map(static_cast<Tpetra::global_size_t>(A.rows), 0, comm));
  Teuchos::ArrayRCP<size_t> rowptr(A.rows + 1);
  Teuchos::ArrayRCP<LO> col(A.col.size());
  Teuchos::ArrayRCP<SC> val(A.val.size());
  std::copy(A.rowptr.begin(), A.rowptr.end(), rowptr.begin());
  std::copy(A.col.begin(), A.col.end(), col.begin());
  std::copy(A.val.begin(), A.val.end(), val.begin());
  auto K = rcp(new CrsMatrix(map, map, rowptr, col, val));
  K->expertStaticFillComplete(map, map);
  return K;
}

std::vector<double> loadVector(const Mesh::Mesh& mesh, const LoadCase& loads) {
  std::vector<double> f(3 * static_cast<size_t>(mesh.numNodes()), 0.0);
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int npc = mesh.cellSize(c);
    const auto fe = cellVolumeForces(mesh.cellType(c), cellCoordinates(mesh, c), loads.volumeForce);
    for (int a = 0; a < 3 * npc; ++a) f[3 * mesh.cell(c)[a / 3] + a % 3] += fe[a];
  }
  for (const auto& t : loads.tractions)
    for (const Mesh::Facet& facet : mesh.face(t.face)) {
      std::vector<Point> X;
      for (int n : facet.nodes) X.push_back(mesh.coords[n]);
      const auto fe = facetTractionForces(X, t.traction);
      for (size_t a = 0; a < facet.nodes.size(); ++a)
        for (int d = 0; d < 3; ++d) f[3 * facet.nodes[a] + d] += fe[3 * a + d];
    }
  return f;
}

NodalVector assembledProduct(const std::vector<SubdomainSystem>& systems, const NodalVector& u) {
  NodalVector Ku(u.layoutPtr());
  std::vector<double> us, Kus;
  for (const auto& sys : systems) {
    us.assign(sys.numDofs(), 0.0);
    Kus.assign(sys.numDofs(), 0.0);
    for (size_t a = 0; a < sys.nodes.size(); ++a)
      for (int c = 0; c < 3; ++c) us[3 * a + c] = u.at(sys.nodes[a])[c];
    sys.K.multiply(us.data(), Kus.data());
    for (size_t a = 0; a < sys.nodes.size(); ++a)
      for (int c = 0; c < 3; ++c) Ku.at(sys.nodes[a])[c] += Kus[3 * a + c];
  }
  u.layout().sumOverHolders(Ku.values());
  return Ku;
}

NodalVector assembledLoad(const std::vector<SubdomainSystem>& systems, const RCP<const NodalLayout>& layout) {
  NodalVector f(layout);
  for (const auto& sys : systems)
    for (size_t a = 0; a < sys.nodes.size(); ++a)
      for (int c = 0; c < 3; ++c) f.at(sys.nodes[a])[c] += sys.f[3 * a + c];
  layout->sumOverHolders(f.values());
  return f;
}

}  // namespace Fem
}  // namespace Tribos
