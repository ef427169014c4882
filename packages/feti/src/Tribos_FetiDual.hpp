// Tribos_FetiDual.hpp: the dual problem of a FetiProblem,
//   min 1/2 lambda'F lambda - lambda'h  s.t.  G lambda = e (+ contact sets),
// with the particular solution lambda~ (G lambda~ = e) and primal recovery
//   u = K+(f - B'lambda) + R alpha.
#pragma once

#include "Tribos_ConjugateProjector.hpp"
#include "Tribos_FetiOperators.hpp"
#include "Tribos_FetiProblem.hpp"

namespace Tribos {
namespace Feti {

class FetiDual {
 public:
  explicit FetiDual(RCP<const FetiProblem> problem);
  // The dual of the same problem at other loads (FetiProblem::setLoads,
  // setTangentialOffset): F and the coarse space of `same` (which depend on
  // K and B only), h, e and lambda~ anew.
  FetiDual(RCP<const FetiProblem> problem, const FetiDual& same);
  // The defect of the rounded F at lambda, (F~ - F) lambda, F~ what F()
  // applies (F()->rounded(): single-precision dense blocks) and F the exact
  // operator (DualOperator::applyExact); zero when F is not rounded. Adding
  // it to h gives the dual whose gradient at lambda is the exact one, F~
  // lambda - (h + defect) = F lambda - h: defect correction (docs/feti.md).
  // One application of each. Collective.
  RCP<Vector> roundingDefect(const Vector& lambda) const;

  const FetiProblem& problem() const { return *problem_; }
  RCP<DualOperator> F() const { return F_; }
  const CoarseSpace& coarse() const { return *coarse_; }
  RCP<const CoarseSpace> coarsePtr() const { return coarse_; }
  // The projector conjugate to F that takes the rigid motions of positive
  // definite subdomains out (ConjugateProjector); null where it does not
  // apply or "Conjugate Projector" is false.
  RCP<const ConjugateProjector> conjugateProjector() const { return conjugate_; }
  const Vector& h() const { return *h_; }
  const std::vector<double>& e() const { return e_; }
  const Vector& lambdaTilde() const { return *lambdaTilde_; }

  // Primal displacement from the multipliers: u = K+(f - B'lambda) + R alpha,
  // alpha from the rows S where B u = c holds: the equality rows (default),
  // or the rows a caller knows to be active (a body held by its contact).
  RCP<Vector> recoverPrimal(const Vector& lambda, const std::vector<char>* activeRows = nullptr) const;

 private:
  RCP<const FetiProblem> problem_;
  RCP<DualOperator> F_;
  RCP<CoarseSpace> coarse_;
  RCP<const ConjugateProjector> conjugate_;
  RCP<Vector> h_, lambdaTilde_;
  std::vector<double> e_;
  // h, e and lambda~ of the problem's current loads.
  void loadTerms();
};

}  // namespace Feti
}  // namespace Tribos
