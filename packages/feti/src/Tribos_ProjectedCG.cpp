#include "Tribos_ProjectedCG.hpp"

#include "Tribos_DualPreconditioner.hpp"
#include "Tribos_Progress.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <functional>

namespace Tribos {
namespace Feti {


RCP<const Teuchos::ParameterList> ProjectedCG::getValidParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Projected CG");
    pl->set("Tolerance", 1e-10, "relative norm of the projected dual residual",
            rcp(new Teuchos::EnhancedNumberValidator<double>(1e-16, 1.0)));
    pl->set("Maximum Iterations", 1000, "iteration limit", rcp(new Teuchos::EnhancedNumberValidator<int>(1, 1000000)));
    pl->set("Preconditioner", "Lumped",
            "None, Lumped (P B_D K B_D' P with B_D = (BB')^-1 B), Dirichlet (P B_D S B_D' P, S the Schur "
            "complements on the interface dofs) or Lumped Unscaled (P B K B' P, for comparison "
            "only: worse than None with the chain gluing); see docs/feti.md",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("None", "Lumped", "Dirichlet", "Lumped Unscaled"))));
  }
  return pl;
}

ProjectedCG::ProjectedCG(const Teuchos::ParameterList& params) {
  Teuchos::ParameterList p(params);
  p.validateParametersAndSetDefaults(*getValidParameters(), 0);
  tol_ = p.get<double>("Tolerance");
  maxIter_ = p.get<int>("Maximum Iterations");
  preconditioner_ = p.get<std::string>("Preconditioner");
}

PCGStatus ProjectedCG::solve(const FetiDual& dual, Vector& lambda) const {
  const FetiProblem& prob = dual.problem();
  const CoarseSpace& coarse = dual.coarse();
  const DualOperator& F = *dual.F();
  const auto map = prob.dualMap();
  const long long n_A0 = F.applications();
  // The preconditioner y = M^-1 w (Tribos_DualPreconditioner.hpp).
  const DualPreconditioner M(dual, preconditioner_);
  lambda.assign(dual.lambdaTilde());
  Vector g(map), w(map), y(map), p(map), q(map);
  F.apply(lambda, g);
  g.update(-1.0, dual.h(), 1.0);  // g = F lambda - h
  Vector Ph(map);
  coarse.project(dual.h(), Ph);
  const double norm0 = std::max(Ph.norm2(), 1e-300);
  PCGStatus st;
  // CG from lambda with the gradient g, until ||P g|| meets the tolerance;
  // g is updated by the recurrence g <- g - alpha F p.
  auto iterate = [&] {
    coarse.project(g, w);
    M.apply(w, y);
    p.assign(y);
    double wy = w.dot(y);
    st.relativeResidual = w.norm2() / norm0;
    while (st.relativeResidual > tol_ && st.iterations < maxIter_) {
      F.apply(p, q);
      const double alpha = wy / p.dot(q);
      lambda.update(-alpha, p, 1.0);
      g.update(-alpha, q, 1.0);
      coarse.project(g, w);
      M.apply(w, y);
      const double wyNew = w.dot(y);
      p.update(1.0, y, wyNew / wy);
      wy = wyNew;
      ++st.iterations;
      st.relativeResidual = w.norm2() / norm0;
      Progress::iteration([&] {
        return "projected CG " + std::to_string(st.iterations) + ": relative residual " +
               Progress::sci(st.relativeResidual);
      });
      if (!out_.is_null()) *out_ << "PCG " << st.iterations << "  ||Pg||/||Ph|| = " << st.relativeResidual << "\n";
    }
  };
  iterate();
  // With single-precision blocks the recurrence converges for F~, not F:
  // the gradient at lambda is recomputed with the exact F (the sparse
  // factors) and CG restarted from it while that misses the tolerance
  // (iterative refinement). A round only has to correct the rounding of the
  // previous round's change, about 1e-7 of it, so one round usually does.
  constexpr int kMaxRefinements = 3;
  while (F.rounded() && st.relativeResidual <= tol_) {
    F.applyExact(lambda, g);
    g.update(-1.0, dual.h(), 1.0);
    coarse.project(g, w);
    st.relativeResidual = w.norm2() / norm0;
    if (!out_.is_null())
      *out_ << "PCG: with the exact F ||Pg||/||Ph|| = " << st.relativeResidual
            << (st.relativeResidual > tol_ && st.refinements < kMaxRefinements ? "; CG restarted from it" : "") << "\n";
    if (st.relativeResidual <= tol_ || st.refinements == kMaxRefinements) break;
    ++st.refinements;
    iterate();
  }
  st.converged = st.relativeResidual <= tol_;
  st.n_A = F.applications() - n_A0;
  return st;
}

}  // namespace Feti
}  // namespace Tribos
