// Tribos_FetiDual.hpp: the dual problem of a FetiProblem,
//   min 1/2 lambda'F lambda - lambda'h  s.t.  G lambda = e (+ contact sets),
// with the particular solution lambda~ (G lambda~ = e) and primal recovery
//   u = K+(f - B'lambda) + R alpha.
#pragma once

#include "Tribos_FetiOperators.hpp"
#include "Tribos_FetiProblem.hpp"

namespace Tribos {
namespace Feti {

class FetiDual {
 public:
  explicit FetiDual(RCP<const FetiProblem> problem);

  const FetiProblem& problem() const { return *problem_; }
  RCP<const FetiProblem> problemPtr() const { return problem_; }
  RCP<DualOperator> F() const { return F_; }
  const CoarseSpace& coarse() const { return *coarse_; }
  RCP<const CoarseSpace> coarsePtr() const { return coarse_; }
  const Vector& h() const { return *h_; }
  const std::vector<double>& e() const { return e_; }
  const Vector& lambdaTilde() const { return *lambdaTilde_; }

  // Primal displacement from the multipliers (amplitudes alpha from the
  // equality rows, where B u = c holds exactly).
  RCP<Vector> recoverPrimal(const Vector& lambda) const;

 private:
  RCP<const FetiProblem> problem_;
  RCP<DualOperator> F_;
  RCP<CoarseSpace> coarse_;
  RCP<Vector> h_, lambdaTilde_;
  std::vector<double> e_;
};

}  // namespace Feti
}  // namespace Tribos
