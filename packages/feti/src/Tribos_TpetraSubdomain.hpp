// Tribos_TpetraSubdomain.hpp: a subdomain as a Trilinos application holds it,
// its stiffness a Tpetra::CrsMatrix (or any Tpetra::RowMatrix, or a
// matrix-free Tpetra::Operator) on one process and its rigid-body modes a
// Tpetra::MultiVector, turned into the Fem::SubdomainSystem that
// FetiProblem factors.
//
// Local dof i of the subdomain (3 localNode + c, c = x y z) is local index i
// of K's maps. FETI needs K+ (a generalized inverse of the floating
// subdomain's K), which comes from a sparse Cholesky factorization of K
// regularized at the fixing dofs of R (Tribos_SubdomainPseudoInverse.hpp); an
// operator cannot be factored, so its matrix is taken first:
//   - a RowMatrix (a CrsMatrix among them): its rows are copied, O(nnz);
//   - any other Operator: its matrix is assembled by probing, K applied to
//     the unit vectors, 64 of them at a time: 3n/64 applications of K to a
//     block of 64 vectors, and the nonzero entries of the columns kept.
//     This is exact for an operator that computes K x as a sum of products
//     of x's entries (an element-by-element product does: an entry of K
//     that no element couples comes out as an exact zero), and costs about
//     3n/64 block products more than copying a matrix; an operator that
//     adds rounding noise outside K's pattern gives dense rows. Its
//     rigid-body modes R are then required: the check ||K r|| <= 1e-8
//     max|K_ii| of FetiProblem compares the probed matrix with the
//     application's own statement of its kernel.
// An iterative solve with K (CG on the range of K) would make every
// application of F inexact, and the dual solvers' stopping tests assume an
// exact F, so it is not offered.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

struct TpetraSubdomain {
  int id = -1;                     // the subdomain number (0..S-1)
  std::vector<int> nodes;          // global node number of each local node (3 dofs each)
  std::vector<Fem::Point> coords;  // coordinates of each local node
  // The stiffness of the floating subdomain (no Dirichlet conditions; they
  // are rows of B), symmetric positive semidefinite, on a serial
  // communicator with 3 nodes.size() local rows; its domain and range map
  // (and row map) the same.
  RCP<const Operator> K;
  RCP<const Vector> f;             // the load on K's domain map; null: zero
  // The six rigid-body modes (a MultiVector of 6 columns on K's domain map,
  // any basis of the kernel of K); null: built from coords (a RowMatrix K
  // only).
  RCP<const MultiVector> R;
  // False: K is positive definite (a time step's K + M / (beta dt^2),
  // docs/dynamics.md), has no kernel and R stays null; Fem::SubdomainSystem.
  bool floating = true;
};

// FETI's K+ and the Cholesky factorization assume K = K': throws
// Tribos::Error naming `name` and the first pair of entries that differ by
// more than 1e-10 max |K_ii|.
void requireSymmetric(const LocalCsr& K, const std::string& name);
// The subdomain as FetiProblem takes it. Throws Tribos::Error naming the
// subdomain and the parameter: K null, not on one process, of the wrong
// size, maps that differ, a RowMatrix not fill-complete or with a column
// outside its rows, a K that is not symmetric; R without 6 columns or on
// another map, missing for an Operator that is not a RowMatrix; f on another
// map. (FetiProblem checks the rest: finite values, R in the kernel of K.)
Fem::SubdomainSystem subdomainSystem(const TpetraSubdomain& subdomain);

// This rank's subdomains, every rank refusing alike (CollectiveError) when
// one of them finds a subdomain wrong. Collective.
std::vector<Fem::SubdomainSystem> subdomainSystems(const std::vector<TpetraSubdomain>& subdomains, const Comm& comm);

// FetiProblem from this rank's subdomains (ids ascending, each rank a
// contiguous range, rank 0 first), the rows of B (gluing and Dirichlet rows,
// contact rows from addContactConditions) and the FetiProblem parameters
// (FetiProblem::getValidParameters()). Collective.
RCP<FetiProblem> createFetiProblem(const std::vector<TpetraSubdomain>& subdomains, FetiConstraints constraints,
                                   const Teuchos::ParameterList& params, const RCP<const Comm>& comm);

}  // namespace Feti
}  // namespace Tribos
