// Tribos_QP_MPGP.hpp: modified proportioning with gradient projections for
// separable convex sets (bounds and disks), Kucera's algorithm for separable
// quadratic constraints. Along a disk boundary the chopped gradient is
// tangential, so a step along it leaves the disk; the proportioning step is
// therefore the gradient projection step x <- P(x - alpha_bar g), which
// decreases f for alpha_bar <= 2/||A||.
#pragma once

#include "Tribos_QP_GradientProjection.hpp"

namespace Tribos {
namespace QP {

class MPGP : public GradientProjectionSolver {
 public:
  MPGP();
  explicit MPGP(RCP<Teuchos::ParameterList> params);
  // The parameters setParameters() accepts, without a solver (the static
  // twin of getValidParameters(), as in friction's outer algorithms).
  static RCP<const Teuchos::ParameterList> validParameters() { return GradientProjectionSolver::validParameters("MPGP"); }

 protected:
  void checkSet(const ConstraintSet&) const override {}
  long proportioningStep(const Operator& A, const Vector& b, const ConstraintSet& Omega,
                         SC alpha_bar, Vector& x, Vector& g, const Vector& beta) override;
};

}  // namespace QP
}  // namespace Tribos
