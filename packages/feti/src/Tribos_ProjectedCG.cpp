#include "Tribos_ProjectedCG.hpp"

#include "Tribos_Progress.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <functional>

namespace Tribos {
namespace Feti {

namespace {

// x = A^+ b for symmetric positive semidefinite A = BB' or B'B by conjugate
// gradients from x = 0: the minimum-norm solution of A x = b for b in range A.
// Both Gram matrices are block diagonal with one small block per mesh node,
// so they have few distinct eigenvalues and CG ends in a few dozen steps.
void gramSolve(const std::function<void(const Vector&, Vector&)>& A, const Vector& b, Vector& x) {
  const auto map = b.getMap();
  Vector r(map), p(map), q(map);
  x.putScalar(0.0);
  r.assign(b);
  p.assign(b);
  double rr = r.dot(r);
  const double stop = 1e-24 * rr;  // relative residual 1e-12
  for (int it = 0; it < 200 && rr > stop; ++it) {
    A(p, q);
    const double alpha = rr / p.dot(q);
    x.update(alpha, p, 1.0);
    r.update(-alpha, q, 1.0);
    const double rrNew = r.dot(r);
    p.update(1.0, r, rrNew / rr);
    rr = rrNew;
  }
}

}  // namespace

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
  // Lumped preconditioner M^-1 = P (B^+)' K B^+ P, B^+ = B'(BB')^+ = (B'B)^+ B',
  // i.e. B_D K B_D' with B_D = (BB')^-1 B. The scaling matters: with the
  // non-redundant chain gluing and the Dirichlet rows, BB' is not a multiple
  // of the identity (cond(BB') = 32 on 2x2x2 subdomains), and the unscaled
  // P B K B' P is a worse operator than none (cond 1970 against 82 for PFP,
  // docs/feti.md). The right factor is computed on the primal side,
  // (B'B)^+ (B'w): B'w lies in range B' to round-off relative to ||w||,
  // whereas w = Pg carries round-off relative to ||g|| >> ||w|| along ker B'
  // once PCG has gained a few digits, which stalls a dual-side solve when
  // redundant gluing makes BB' singular.
  const CrsMatrix& B = *prob.B();
  Vector pw(prob.primalMap()), v(prob.primalMap()), Kv(prob.primalMap()), tmp(map), scaled(map);
  auto BtB = [&](const Vector& x, Vector& y) {
    B.apply(x, tmp);
    B.apply(tmp, y, Teuchos::TRANS);
  };
  auto BBt = [&](const Vector& x, Vector& y) {
    B.apply(x, pw, Teuchos::TRANS);
    B.apply(pw, y);
  };
  auto precondition = [&](const Vector& w, Vector& y) {
    if (preconditioner_ == "None") {
      y.assign(w);
      return;
    }
    B.apply(w, pw, Teuchos::TRANS);
    if (preconditioner_ == "Lumped" || preconditioner_ == "Dirichlet") {
      gramSolve(BtB, pw, v);
      if (preconditioner_ == "Lumped") prob.applyK(v, Kv);
      else prob.applySchur(v, Kv);
      B.apply(Kv, tmp);
      gramSolve(BBt, tmp, scaled);
      coarse.project(scaled, y);
    } else {  // Lumped Unscaled
      prob.applyK(pw, Kv);
      B.apply(Kv, tmp);
      coarse.project(tmp, y);
    }
  };
  lambda.assign(dual.lambdaTilde());
  Vector g(map), w(map), y(map), p(map), q(map);
  F.apply(lambda, g);
  g.update(-1.0, dual.h(), 1.0);  // g = F lambda - h
  coarse.project(g, w);
  Vector Ph(map);
  coarse.project(dual.h(), Ph);
  const double norm0 = std::max(Ph.norm2(), 1e-300);
  PCGStatus st;
  precondition(w, y);
  p.assign(y);
  double wy = w.dot(y);
  st.relativeResidual = w.norm2() / norm0;
  while (st.relativeResidual > tol_ && st.iterations < maxIter_) {
    F.apply(p, q);
    const double alpha = wy / p.dot(q);
    lambda.update(-alpha, p, 1.0);
    g.update(-alpha, q, 1.0);
    coarse.project(g, w);
    precondition(w, y);
    const double wyNew = w.dot(y);
    p.update(1.0, y, wyNew / wy);
    wy = wyNew;
    ++st.iterations;
    st.relativeResidual = w.norm2() / norm0;
    Progress::iteration([&] {
      return "projected CG " + std::to_string(st.iterations) + ": relative residual " + Progress::sci(st.relativeResidual);
    });
    if (!out_.is_null()) *out_ << "PCG " << st.iterations << "  ||Pg||/||Ph|| = " << st.relativeResidual << "\n";
  }
  st.converged = st.relativeResidual <= tol_;
  st.n_A = F.applications() - n_A0;
  return st;
}

}  // namespace Feti
}  // namespace Tribos
