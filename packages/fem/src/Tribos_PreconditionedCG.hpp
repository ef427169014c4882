// Tribos_PreconditionedCG.hpp: Belos CG preconditioned by MueLu smoothed
// aggregation, the one iterative solver of assembled elasticity systems (the
// monolithic solve, the semismooth* full-space Newton steps).
#pragma once

#include <Teuchos_ParameterList.hpp>

#include "Tribos_Types.hpp"

namespace MueLu {
template <class Scalar, class LocalOrdinal, class GlobalOrdinal, class Node>
class TpetraOperator;
}

namespace Tribos {
namespace Fem {

using MueLuOperator = MueLu::TpetraOperator<SC, LO, GO, Node>;

// What MueLu needs of an elasticity matrix beside its values: the
// rigid-body modes (near null space, on the matrix's row map) and the node
// coordinates (3 columns on the node map: node g holds rows 3g..3g+2).
struct ElasticityModes {
  RCP<MultiVector> nullspace, coordinates;
};

// A MueLu hierarchy for A (params: MueLu's list) with the rigid-body modes
// as near null space.
RCP<MueLuOperator> mueluPreconditioner(const RCP<CrsMatrix>& A, const ElasticityModes& modes,
                                       Teuchos::ParameterList params);

// The coarsest level of a hierarchy for a matrix of `rows` rows on numRanks
// ranks: at most coarseMaxSize rows, factored by KLU2 on one rank. On several
// ranks MueLu first moves it there (repartitioning to one part, for which
// Zoltan2 takes its trivial path; it asks for the node coordinates): Amesos2
// KLU2 of this Trilinos build returns wrong solutions on more than one rank,
// and a smoothed coarse level costs a third to a half more CG steps
// (docs/semismooth.md). A matrix that is its own coarsest level on several
// ranks cannot be moved: it is smoothed (four Gauss-Seidel sweeps).
void setCoarseLevelOnOneRank(Teuchos::ParameterList& mueluParams, int coarseMaxSize, long long rows, int numRanks);

struct CGResult {
  bool converged = false;
  int iterations = 0;
};

// Belos CG on A x = b, preconditioned by M, from the x given, to
// ||b - A x|| <= tol ||b|| (relative) or <= tol (absolute, for callers that
// tie the tolerance to quantities b does not know). A round-off breakdown
// (p'Ap <= 0 once the residual stagnates) stops instead of throwing.
CGResult preconditionedCG(const RCP<const Operator>& A, const RCP<Operator>& M, const Vector& b, Vector& x,
                          double tol, bool absolute, int maxIterations);

}  // namespace Fem
}  // namespace Tribos
