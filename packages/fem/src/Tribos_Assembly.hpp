// Tribos_Assembly.hpp: subdomain stiffness K_s, load f_s and rigid-body kernel R_s.
#pragma once

#include <functional>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_LocalCsr.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Fem {

// Everything FETI needs of one subdomain. Dirichlet conditions are not applied
// here: in Total FETI they become rows of B, so K_s is always floating.
struct SubdomainSystem {
  int id = -1;
  std::vector<int> nodes;     // local node -> global node
  LocalCsr K;                 // 3n x 3n, symmetric positive semidefinite
  std::vector<double> f;      // tractions and volume forces of the subdomain's own cells
  std::vector<double> R;      // 3n x 6, column-major, orthonormal columns spanning ker K
  std::vector<Point> coords;  // node coordinates (local node order)
  // Whether K has the rigid-body motions as its kernel (R), as a stiffness
  // of a subdomain without Dirichlet conditions has (TFETI). False: K is
  // positive definite, e.g. the K + M / (beta dt^2) of an implicit time
  // step (docs/dynamics.md); R is empty, K+ is K's inverse and the
  // subdomain adds nothing to the coarse space.
  bool floating = true;
  int numDofs() const { return 3 * static_cast<int>(nodes.size()); }
};

SubdomainSystem assembleSubdomain(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyMaterials& mat,
                                  const LoadCase& loads);
// The same system on every rank of comm, the element matrices shared out:
// each rank computes a contiguous block of the cells, and K is their sum.
// Collective.
SubdomainSystem assembleSubdomain(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyMaterials& mat,
                                  const LoadCase& loads, const Comm& comm);
// Subdomain s of this rank's part, its nodes named by their mesh numbers.
SubdomainSystem assembleSubdomain(const Mesh::Discretization& disc, int s, const BodyMaterials& mat,
                                  const LoadCase& loads);

// The load vector f of a subdomain alone (3 per local node): the volume
// force of its cells and the tractions on the facets of its cells; what
// assembleSubdomain puts in f, again for another load of the same mesh.
std::vector<double> subdomainLoad(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const LoadCase& loads);
std::vector<double> subdomainLoad(const Mesh::Discretization& disc, int s, const LoadCase& loads);

// Cell node coordinates.
std::vector<Point> cellCoordinates(const Mesh::Mesh& mesh, int cell);

// The element matrix (3 npc x 3 npc, row-major, dof 3 node + component) of a
// cell of the mesh given its node coordinates.
using ElementMatrix = std::function<std::vector<double>(int cell, const std::vector<Point>& X)>;
// The sum of the element matrices of the cells [first, end) of sub.cells in
// the subdomain's CSR layout: dof 3 local node + component, the dofs of
// nodes sharing a cell coupled, columns ascending. assembleSubdomain's K and
// the mass matrix (Tribos_Mass.hpp) share it, so their patterns are equal.
LocalCsr assembleCellMatrices(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const ElementMatrix& elementMatrix,
                              size_t first, size_t end);

// K_s as a Tpetra::CrsMatrix on the given (typically serial) communicator.
RCP<CrsMatrix> toTpetra(const LocalCsr& A, const RCP<const Comm>& comm);

// K u and f of the whole mesh, summed over the subdomain systems of all
// ranks, at the nodes of u's layout (which must hold the nodes of this
// rank's systems). Collective.
NodalVector assembledProduct(const std::vector<SubdomainSystem>& systems, const NodalVector& u);
NodalVector assembledLoad(const std::vector<SubdomainSystem>& systems, const RCP<const NodalLayout>& layout);

// The load vector of a mesh, 3 per node: its cells' volume forces and its
// faces' tractions (of a part of a mesh: the part's share).
std::vector<double> loadVector(const Mesh::Mesh& mesh, const LoadCase& loads);

}  // namespace Fem
}  // namespace Tribos
