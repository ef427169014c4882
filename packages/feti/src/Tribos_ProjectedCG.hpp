// Tribos_ProjectedCG.hpp: the FETI dual solve without inequality constraints:
// conjugate gradients on the projected dual problem
//   P F P lambda^ = P (h - F lambda~),  lambda = lambda~ + lambda^,
// with an optional lumped preconditioner P B_D K B_D' P, B_D = (BB')^-1 B.
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_FetiDual.hpp"

namespace Tribos {
namespace Feti {

struct PCGStatus {
  bool converged = false;
  int iterations = 0;
  long long n_A = 0;
  double relativeResidual = 0;  // ||P(h - F lambda)|| / ||P h||, with the exact F
  // Restarts from the gradient of the exact F when F is rounded
  // (single-precision dense blocks), at most 3.
  int refinements = 0;
};

class ProjectedCG {
 public:
  explicit ProjectedCG(const Teuchos::ParameterList& params);
  static RCP<const Teuchos::ParameterList> getValidParameters();
  void setOutputStream(RCP<Teuchos::FancyOStream> out) { out_ = out; }
  // lambda on output: the multipliers satisfying G lambda = e. With F
  // rounded (DualOperator::rounded) the tolerance is met for the exact F by
  // iterative refinement; F's exact applications are not counted in n_A.
  PCGStatus solve(const FetiDual& dual, Vector& lambda) const;

 private:
  double tol_;
  int maxIter_;
  std::string preconditioner_;
  RCP<Teuchos::FancyOStream> out_;
};

}  // namespace Feti
}  // namespace Tribos
