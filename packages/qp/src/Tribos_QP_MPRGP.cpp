#include "Tribos_QP_MPRGP.hpp"

#include <algorithm>

#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace QP {

MPRGP::MPRGP() : GradientProjectionSolver("MPRGP") { setParameters(Teuchos::null); }

MPRGP::MPRGP(RCP<Teuchos::ParameterList> params) : GradientProjectionSolver("MPRGP") { setParameters(params); }

void MPRGP::checkSet(const ConstraintSet& Omega) const {
  TRIBOS_REQUIRE(Omega.onlyBounds(), "MPRGP: the constraint set has " << Omega.numCircles()
                                         << " circles; MPRGP handles bounds only (use MPGP)");
}

long MPRGP::proportioningStep(const Operator& A, const Vector&, const ConstraintSet& Omega, SC, Vector& x, Vector& g,
                              const Vector& beta) {
  // exact line search along -beta; beta points into the set, so only an
  // upper bound of a box can cut the step
  Vector& Abeta = work(x);
  A.apply(beta, Abeta);
  const SC bAb = curvature(beta, Abeta, "MPRGP");
  const SC alpha = std::min(g.dot(beta) / bAb, Omega.maxFeasibleStep(x, beta));
  x.update(-alpha, beta, 1.0);
  g.update(-alpha, Abeta, 1.0);
  return 1;
}

}  // namespace QP
}  // namespace Tribos
