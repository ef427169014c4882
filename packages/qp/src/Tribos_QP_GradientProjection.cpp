#include "Tribos_QP_GradientProjection.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>

#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"

namespace Tribos {
namespace QP {

GradientProjectionSolver::GradientProjectionSolver(std::string name) : name_(std::move(name)) {}

RCP<const Teuchos::ParameterList> GradientProjectionSolver::validParameters(const std::string& name) {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList(name));
  addCommonParameters(*pl, CommonParameters());
  return pl;
}

RCP<const Teuchos::ParameterList> GradientProjectionSolver::getValidParameters() const {
  return validParameters(name_);
}

void GradientProjectionSolver::setParameters(RCP<Teuchos::ParameterList> params) {
  if (params.is_null()) params = Teuchos::rcp(new Teuchos::ParameterList(name_));
  params->validateParametersAndSetDefaults(*getValidParameters());
  params_ = readCommonParameters(*params);
  output_.setVerbosity(params_.verbosity);
}

SC GradientProjectionSolver::curvature(const Vector& p, const Vector& Ap, const char* where) {
  const SC pAp = p.dot(Ap);
  TRIBOS_REQUIRE(pAp > 0 && std::isfinite(pAp),
                 where << ": the Hessian A is not positive definite: p'Ap = " << pAp << " for a direction with ||p|| = "
                       << p.norm2());
  return pAp;
}

Vector& GradientProjectionSolver::work(const Vector& x) {
  if (work_.is_null() || work_->getMap().get() != x.getMap().get()) work_ = Teuchos::rcp(new Vector(x.getMap()));
  return *work_;
}

QPStatus GradientProjectionSolver::solve(const Operator& A, const Vector& b, const ConstraintSet& Omega, Vector& x) {
  checkSet(Omega);
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::QP::" + name_ + "::solve"));
  TRIBOS_REQUIRE(x.getLocalLength() == Omega.map()->getNodeNumElements() &&
                     b.getLocalLength() == x.getLocalLength(),
                 name_ << "::solve: x (" << x.getLocalLength() << " local entries), b (" << b.getLocalLength()
                       << ") and Omega (" << Omega.map()->getNodeNumElements() << ") do not match");
  QPStatus st;
  const RCP<const Map> map = x.getMap();
  Omega.project(x);  // an infeasible start is projected first

  const SC normA = hessianNorm_ > 0 ? hessianNorm_ : estimateNorm(A, params_.powerIterations, st.n_A);
  const SC alpha_bar = params_.alphaBar / normA;
  const SC tol = toleranceOverride_ >= 0 ? toleranceOverride_ : std::max(params_.rtol * b.norm2(), params_.atol);

  g_ = Teuchos::rcp(new Vector(map));
  Vector& g = *g_;
  Vector phi(map), beta(map), phit(map), p(map), Ap(map), gP(map);
  auto computeGradient = [&]() {  // g = A x - b
    A.apply(x, g);
    ++st.n_A;
    g.update(-1.0, b, 1.0);
  };
  computeGradient();
  Omega.freeGradient(x, g, phi);
  Omega.choppedGradient(x, g, beta);
  Tpetra::deep_copy(p, phi);

  auto& out = output_.stream();
  const SC Gamma2 = params_.Gamma * params_.Gamma;
  for (;;) {
    gP.update(1.0, phi, 1.0, beta, 0.0);
    st.norm_gP = gP.norm2();
    Progress::iteration([&] {
      return name_ + " " + std::to_string(st.iterations) + ": ||g^P|| " + Progress::sci(st.norm_gP) + ", tolerance " +
             Progress::sci(tol) + ", n_A " + std::to_string(st.n_A);
    });
    if (st.norm_gP <= tol) {
      st.converged = true;
      st.reason = "||g^P|| <= tolerance";
      break;
    }
    if (st.iterations >= params_.maxIterations) {
      st.reason = "Maximum Iterations (" + std::to_string(params_.maxIterations) + ") reached";
      break;
    }
    ++st.iterations;
    Omega.reducedFreeGradient(x, g, alpha_bar, phit);
    const SC betaBeta = beta.dot(beta);
    const SC phitPhi = phit.dot(phi);
    const char* step;
    if (betaBeta <= Gamma2 * phitPhi) {
      // x is proportional: a conjugate gradient trial step on the free set
      A.apply(p, Ap);
      ++st.n_A;
      const SC pAp = curvature(p, Ap, name_.c_str());
      const SC alpha_cg = g.dot(p) / pAp;
      const SC alpha_f = Omega.maxFeasibleStep(x, p);
      if (alpha_cg <= alpha_f) {
        x.update(-alpha_cg, p, 1.0);
        g.update(-alpha_cg, Ap, 1.0);
        Omega.freeGradient(x, g, phi);
        const SC gamma = phi.dot(Ap) / pAp;
        p.update(1.0, phi, -gamma);
        ++st.cg_steps;
        step = "cg";
      } else {
        // expansion: go to the boundary, then a fixed step alpha_bar on the
        // free gradient with projection (may add and remove active constraints)
        x.update(-alpha_f, p, 1.0);
        g.update(-alpha_f, Ap, 1.0);
        Omega.freeGradient(x, g, phi);
        x.update(-alpha_bar, phi, 1.0);
        Omega.project(x);
        computeGradient();
        Omega.freeGradient(x, g, phi);
        Tpetra::deep_copy(p, phi);
        ++st.expansion_steps;
        step = "expansion";
      }
    } else {
      st.n_A += proportioningStep(A, b, Omega, alpha_bar, x, g, beta);
      Omega.freeGradient(x, g, phi);
      Tpetra::deep_copy(p, phi);
      ++st.proportioning_steps;
      step = "proportioning";
    }
    Omega.choppedGradient(x, g, beta);
    if (output_.wants(Verbosity::Medium)) {
      out << name_ << " it " << std::setw(5) << st.iterations << " " << std::setw(13) << step
          << " ||g^P|| " << std::scientific << std::setprecision(3) << st.norm_gP << " n_A " << st.n_A;
      if (output_.wants(Verbosity::High))  // the proportioning test that chose the step
        out << " ||beta||^2 " << betaBeta << " Gamma^2 phit'phi " << Gamma2 * phitPhi;
      out << "\n";
    }
  }
  if (output_.wants(Verbosity::Low)) out << name_ << ": " << st << " (tolerance " << tol << ")\n";
  return st;
}

}  // namespace QP
}  // namespace Tribos
