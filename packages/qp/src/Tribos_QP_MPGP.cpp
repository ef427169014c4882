#include "Tribos_QP_MPGP.hpp"

#include <Tpetra_Vector.hpp>

namespace Tribos {
namespace QP {

MPGP::MPGP() : GradientProjectionSolver("MPGP") { setParameters(Teuchos::null); }

MPGP::MPGP(RCP<Teuchos::ParameterList> params) : GradientProjectionSolver("MPGP") { setParameters(params); }

long MPGP::proportioningStep(const Operator& A, const Vector& b, const ConstraintSet& Omega, SC alpha_bar, Vector& x,
                             Vector& g, const Vector&) {
  // gradient projection step x <- P(x - alpha_bar g); fixed components stay put
  Vector& d = work(x);
  Tpetra::deep_copy(d, g);
  Omega.zeroFixed(d);
  x.update(-alpha_bar, d, 1.0);
  Omega.project(x);
  A.apply(x, g);
  g.update(-1.0, b, 1.0);
  return 1;
}

}  // namespace QP
}  // namespace Tribos
