#include "Tribos_FetiDual.hpp"

#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

FetiDual::FetiDual(RCP<const FetiProblem> problem) : problem_(problem) {
  F_ = rcp(new DualOperator(problem));
  coarse_ = rcp(new CoarseSpace(problem));
  if (problem->conjugateProjectorWanted() && ConjugateProjector::applies(*problem))
    conjugate_ = rcp(new ConjugateProjector(problem, F_));
  loadTerms();
}

FetiDual::FetiDual(RCP<const FetiProblem> problem, const FetiDual& same)
    : problem_(problem), F_(same.F_), coarse_(same.coarse_), conjugate_(same.conjugate_) {
  TRIBOS_REQUIRE(problem.get() == same.problem_.get(), "FetiDual: the operators of another problem");
  loadTerms();
}

RCP<Vector> FetiDual::roundingDefect(const Vector& lambda) const {
  auto defect = rcp(new Vector(problem_->dualMap()));
  if (!F_->rounded()) return defect;
  F_->apply(lambda, *defect);
  Vector Flambda(problem_->dualMap());
  F_->applyExact(lambda, Flambda);
  defect->update(-1.0, Flambda, 1.0);
  return defect;
}

void FetiDual::loadTerms() {
  const FetiProblem& p = *problem_;
  // h = B K+ f - c
  Vector z(p.primalMap());
  p.applyKplus(p.f(), z);
  h_ = rcp(new Vector(p.dualMap()));
  p.B()->apply(z, *h_);
  h_->update(-1.0, p.c(), 1.0);
  p.applyRt(p.f(), e_);
  lambdaTilde_ = rcp(new Vector(p.dualMap()));
  coarse_->particularSolution(e_, *lambdaTilde_);
}

RCP<Vector> FetiDual::recoverPrimal(const Vector& lambda, const std::vector<char>* activeRows) const {
  const FetiProblem& p = *problem_;
  // alpha from r = F lambda - h on the rows where B u = c holds, with the
  // exact F (as K+ below): u is then the exact primal of lambda whatever
  // precision the solver's F had. F from single-precision blocks is
  // replaced by the sparse factors; double blocks are F to round-off. One
  // extra application, outside the solvers' n_A.
  Vector r(p.dualMap());
  if (F_->rounded())
    F_->applyExact(lambda, r);
  else
    F_->apply(lambda, r);
  r.update(-1.0, *h_, 1.0);
  const auto alpha = coarse_->amplitudes(r, activeRows);
  Vector rhs(p.primalMap());
  p.B()->apply(lambda, rhs, Teuchos::TRANS);
  rhs.update(1.0, p.f(), -1.0);
  auto u = rcp(new Vector(p.primalMap()));
  p.applyKplus(rhs, *u);
  Vector Ra(p.primalMap());
  p.applyR(alpha, Ra);
  u->update(1.0, Ra, 1.0);
  return u;
}

}  // namespace Feti
}  // namespace Tribos
