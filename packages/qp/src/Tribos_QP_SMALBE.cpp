#include "Tribos_QP_SMALBE.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <vector>

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_QP_AugmentedLagrangian.hpp"
#include "Tribos_QP_Factory.hpp"

namespace Tribos {
namespace QP {

SMALBE::SMALBE() { setParameters(Teuchos::null); }

SMALBE::SMALBE(RCP<Teuchos::ParameterList> params) { setParameters(params); }

RCP<const Teuchos::ParameterList> SMALBE::validParameters() {
  using Teuchos::rcp;
  auto pl = rcp(new Teuchos::ParameterList("SMALBE"));
  CommonParameters d;
  d.maxIterations = 100000;  // total inner iterations are limited by the inner solver
  addCommonParameters(*pl, d);
  pl->getEntryRCP("Maximum Iterations")->setDocString("limit on the total number of inner iterations");
  auto nonneg = rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1e300));
  pl->set("M", 0.0, "inner precision ||g^P|| <= min(M ||Gx||, eta); 0: 100 ||A||", nonneg);
  pl->set("rho", 0.0, "penalty rho; 0: ||A||", nonneg);
  pl->set("eta", 0.1, "inner precision cap as a multiple of ||b||",
          rcp(new Teuchos::EnhancedNumberValidator<double>(1e-300, 1e300)));
  pl->set("beta", 2.0, "update factor of M (M/beta) or rho (beta rho)",
          rcp(new Teuchos::EnhancedNumberValidator<double>(1.0 + 1e-12, 1e300)));
  Teuchos::setStringToIntegralParameter<int>("Penalty Update", "M",
                                             "what changes when L does not grow enough: M <- M/beta or rho <- beta rho",
                                             Teuchos::tuple<std::string>("M", "rho"), Teuchos::tuple<int>(0, 1), pl.get());
  pl->set("Maximum Outer Iterations", 100, "outer (multiplier) iterations",
          rcp(new Teuchos::EnhancedNumberValidator<int>(1, 1000000000)));
  Teuchos::ParameterList& inner = pl->sublist("Inner Solver", false, "inner bound/circle QP solver");
  Teuchos::setStringToIntegralParameter<int>("Type", "MPGP", "inner solver", Teuchos::tuple<std::string>("MPRGP", "MPGP"),
                                             Teuchos::tuple<int>(0, 1), &inner);
  addCommonParameters(inner, CommonParameters());
  return pl;
}

void SMALBE::setParameters(RCP<Teuchos::ParameterList> params) {
  if (params.is_null()) params = Teuchos::rcp(new Teuchos::ParameterList("SMALBE"));
  params->validateParametersAndSetDefaults(*getValidParameters());
  params_ = params;
  s_.common = readCommonParameters(*params);
  s_.M = params->get<double>("M");
  s_.rho = params->get<double>("rho");
  s_.eta = params->get<double>("eta");
  s_.beta = params->get<double>("beta");
  s_.updateRho = Teuchos::getIntegralValue<int>(*params, "Penalty Update") == 1;
  s_.maxOuter = params->get<int>("Maximum Outer Iterations");
  output_.setVerbosity(s_.common.verbosity);
  if (innerFromParameters_) {
    auto innerParams = Teuchos::rcp(new Teuchos::ParameterList(params->sublist("Inner Solver")));
    const std::string type = innerParams->get<std::string>("Type");
    innerParams->remove("Type");
    inner_ = QPSolverFactory().create(type, innerParams);
  }
}

void SMALBE::setOutputStream(RCP<Teuchos::FancyOStream> out) {
  output_.setStream(out);
  if (!inner_.is_null()) inner_->setOutputStream(out);
}

void SMALBE::setEqualityConstraint(RCP<const EqualityConstraint> G) {
  TRIBOS_REQUIRE(!G.is_null(), "SMALBE::setEqualityConstraint: G is null");
  G_ = G;
}

void SMALBE::setInnerSolver(RCP<QPSolver> inner) {
  TRIBOS_REQUIRE(!inner.is_null(), "SMALBE::setInnerSolver: inner solver is null");
  inner_ = inner;
  innerFromParameters_ = false;
}

void SMALBE::setMultiplier(const Vector& mu0) { mu0_ = Teuchos::rcp(new Vector(mu0, Teuchos::Copy)); }

const Vector& SMALBE::multiplier() const {
  TRIBOS_REQUIRE(!mu_.is_null(), "SMALBE::multiplier: no solve has been done yet");
  return *mu_;
}

SC SMALBE::innerTolerance(SC M, SC normGx, SC eta, SC tol) const {
  // ||Gx|| of the previous outer iterate stands in for that of the inner one
  const SC t = normGx > 0 ? std::min(M * normGx, eta) : eta;
  return std::max(t, tol);
}

QPStatus SMALBE::solve(const Operator& A, const Vector& b, const ConstraintSet& Omega, Vector& x) {
  TRIBOS_REQUIRE(!G_.is_null(), "SMALBE::solve: no equality constraint (call setEqualityConstraint)");
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::QP::SMALBE::solve"));
  QPStatus st;
  const RCP<const Map> xmap = x.getMap();
  const EqualityConstraint& G = *G_;
  Omega.project(x);

  const SC normA = hessianNorm_ > 0 ? hessianNorm_ : estimateNorm(A, s_.common.powerIterations, st.n_A);
  AugmentedLagrangian al(A, G);
  const SC normGtG = al.normGtG(s_.common.powerIterations);
  const SC normB = b.norm2();
  SC rho = s_.rho > 0 ? s_.rho : normA;
  SC M = s_.M > 0 ? s_.M : 100 * normA;
  const SC rho0 = rho, M0 = M;
  const SC eta = s_.eta * (normB > 0 ? normB : 1.0);
  const SC tol = toleranceOverride_ >= 0 ? toleranceOverride_ : std::max(s_.common.rtol * normB, s_.common.atol);

  mu_ = al.multiplier();
  if (!mu0_.is_null()) Tpetra::deep_copy(*mu_, *mu0_);
  Vector gP(xmap);
  g_ = Teuchos::rcp(new Vector(xmap));
  Vector& g = *g_;
  SC normGx = al.normGx(x);
  SC innerTol = innerTolerance(M, normGx, eta, tol);
  std::vector<SC> GxHistory;
  auto& out = output_.stream();

  for (int k = 0; k < s_.maxOuter; ++k) {
    // inner problem: min L(x, mu, rho) = 1/2 x'(A + rho G'G)x - (b - G'mu)'x over Omega
    const Vector& b_in = al.linearTerm(b);
    const AugmentedHessian& H = al.hessian(rho);
    inner_->setHessianNorm(normA + rho * normGtG);
    inner_->setTolerance(innerTol);
    // M sets the inner precision only while M ||Gx|| is above the final
    // tolerance; below it every inner solve is asked for the final tolerance
    // whatever M is, so a lower M cannot make it more precise.
    const bool precisionFromM = innerTol > tol;
    const QPStatus ist = inner_->solve(H, b_in, Omega, x);
    st.iterations += ist.iterations;
    st.cg_steps += ist.cg_steps;
    st.expansion_steps += ist.expansion_steps;
    st.proportioning_steps += ist.proportioning_steps;
    st.n_A += ist.n_A;
    if (!inner_->gradient().is_null()) {
      Tpetra::deep_copy(g, *inner_->gradient());
    } else {
      H.apply(x, g);
      ++st.n_A;
      g.update(-1.0, b_in, 1.0);
    }
    Omega.projectedGradient(x, g, gP);
    st.norm_gP = gP.norm2();
    const AugmentedLagrangian::Step step = al.update(x, g, rho);
    normGx = step.normGx;
    st.norm_Gx = normGx;
    st.outer_iterations = k + 1;
    Progress::iteration([&] {
      return "SMALBE outer " + std::to_string(k + 1) + ": ||g^P|| " + Progress::sci(st.norm_gP) + ", ||Gx|| " +
             Progress::sci(normGx) + ", tolerance " + Progress::sci(tol) + ", inner iterations " +
             std::to_string(st.iterations);
    });
    if (output_.wants(Verbosity::Medium))
      out << "SMALBE outer " << std::setw(4) << k + 1 << " ||g^P|| " << std::scientific << std::setprecision(3)
          << st.norm_gP << " ||Gx|| " << normGx << " rho " << rho << " M " << M << " inner " << ist.iterations
          << " its, tol " << innerTol << "\n";
    if (st.norm_gP <= tol && normGx <= tol) {
      st.converged = true;
      st.reason = "||g^P|| <= tolerance and ||Gx|| <= tolerance";
      break;
    }
    // semi-monotonicity: L must grow by rho/2 ||Gx||^2, else tighten. The
    // test presumes the inner problem was solved to its tolerance; an inner
    // solver that stopped early (e.g. a fixed number of block Gauss-Seidel
    // sweeps) says nothing about M, and neither does one whose precision
    // the final tolerance set: near the solution rho/2 ||Gx||^2 falls to the
    // round-off of L, and lowering M there only ran it down to its floor.
    if (k > 0 && ist.converged && precisionFromM && step.grewTooLittle) {
      if (s_.updateRho) rho *= s_.beta;
      else M /= s_.beta;
    }
    // ||Gx|| that does not decrease over a window of outer iterations with
    // solved inner problems: strengthen the penalty
    GxHistory.push_back(normGx);
    const size_t w = static_cast<size_t>(s_.stagnationWindow);
    if (GxHistory.size() > w && normGx > 0.9 * GxHistory[GxHistory.size() - 1 - w] && ist.converged) {
      rho *= stagnationRhoFactor;
      GxHistory.clear();
    }
    if (st.iterations >= s_.common.maxIterations) {
      st.reason = "Maximum Iterations (" + std::to_string(s_.common.maxIterations) + " inner iterations in total) reached";
      break;
    }
    if (M < M0 * minMFactor) {
      st.reason = "M fell below its floor (M0 * 1e-10): the set {G x = 0} and Omega look inconsistent";
      break;
    }
    if (rho > rho0 * maxRhoFactor) {
      st.reason = "rho grew beyond its cap (rho0 * 1e6) with ||Gx|| = " + std::to_string(normGx) +
                  " stagnating over " + std::to_string(s_.stagnationWindow) +
                  " outer iterations: the set {G x = 0} and Omega look inconsistent";
      break;
    }
    innerTol = innerTolerance(M, normGx, eta, tol);
  }
  if (!st.converged && st.reason.empty())
    st.reason = "Maximum Outer Iterations (" + std::to_string(s_.maxOuter) + ") reached";
  if (output_.wants(Verbosity::Low)) out << "SMALBE: " << st << " (tolerance " << tol << ")\n";
  return st;
}

}  // namespace QP
}  // namespace Tribos
