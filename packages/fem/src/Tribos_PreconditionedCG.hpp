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

// A MueLu hierarchy for A (params: MueLu's list) with the rigid-body modes
// as near null space.
RCP<MueLuOperator> mueluPreconditioner(const RCP<CrsMatrix>& A, const RCP<MultiVector>& nullspace,
                                       Teuchos::ParameterList params);

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
