// Tribos_QP_MPRGP.hpp: modified proportioning with reduced gradient projections
// (Dostal-Schoeberl) for simple bounds (lower, box, fixed, free). The
// proportioning step moves along the chopped gradient beta with the exact
// line search, limited to the feasible step (beta points into the box).
#pragma once

#include "Tribos_QP_GradientProjection.hpp"

namespace Tribos {
namespace QP {

class MPRGP : public GradientProjectionSolver {
 public:
  MPRGP();
  explicit MPRGP(RCP<Teuchos::ParameterList> params);
  // The parameters setParameters() accepts, without a solver (the static
  // twin of getValidParameters(), as in friction's outer algorithms).
  static RCP<const Teuchos::ParameterList> validParameters() { return GradientProjectionSolver::validParameters("MPRGP"); }

 protected:
  void checkSet(const ConstraintSet& Omega) const override;
  long proportioningStep(const Operator& A, const Vector& b, const ConstraintSet& Omega,
                         SC alpha_bar, Vector& x, Vector& g, const Vector& beta) override;
};

}  // namespace QP
}  // namespace Tribos
