#include "Tribos_FrictionSolver.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "Tribos_BlockGaussSeidel.hpp"
#include "Tribos_NonsmoothGaussSeidel.hpp"
#include "Tribos_SemismoothNewton.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_Validators.hpp"
#include "Tribos_QP.hpp"
#include "Tribos_QP_AugmentedLagrangian.hpp"
#include "Tribos_QP_Utils.hpp"
#include "Tribos_Progress.hpp"

namespace Tribos {
namespace Friction {

FrictionStatus followedBy(const FrictionStatus& earlier, const FrictionStatus& next) {
  FrictionStatus sum = next;
  sum.outer_iterations += earlier.outer_iterations;
  sum.msa_iterations += earlier.msa_iterations;
  sum.inner_iterations += earlier.inner_iterations;
  sum.n_A += earlier.n_A;
  sum.n_A_qpp += earlier.n_A_qpp;
  sum.n_A_qpq += earlier.n_A_qpq;
  sum.history.insert(sum.history.begin(), earlier.history.begin(), earlier.history.end());
  sum.steps.insert(sum.steps.begin(), earlier.steps.begin(), earlier.steps.end());
  return sum;
}

double tightenedTolerance(double requested, double target, double achieved, double margin) {
  return std::max(kTightestTolerance, requested * std::min(0.1, margin * target / std::max(achieved, target)));
}

using Teuchos::ParameterList;

namespace {

// Solver sublist validated against the solver's own valid parameters.
RCP<ParameterList> solverList(const ParameterList& parent, const std::string& name, const QP::QPSolver& solver) {
  auto pl = rcp(new ParameterList(parent.isSublist(name) ? parent.sublist(name) : ParameterList(name)));
  pl->validateParametersAndSetDefaults(*solver.getValidParameters());
  return pl;
}

RCP<QP::QPSolver> makeQPSolver(const std::string& type, const ParameterList& parent, const std::string& name) {
  QP::QPSolverFactory factory;
  auto solver = factory.create(type, Teuchos::null);
  solver->setParameters(solverList(parent, name, *solver));
  return solver;
}

SC estimateHessianNorm(const ContactDual& dual, long& n_A) { return dual.hessianNorm(QP::kNormSteps, n_A); }

// The record of one outer step (FrictionStatus::steps): residuals relative to
// ||b||, as the stopping tests measure them, so that runs of different sizes
// and loads share the axes of a convergence plot.
OuterStep outerStep(const FrictionStatus& st, const ContactDual& dual, SC slipBoundChange,
                    std::chrono::steady_clock::time_point start) {
  const SC normB = dual.normB() > 0 ? dual.normB() : 1.0;
  OuterStep s;
  s.iteration = st.msa_iterations > 0 ? st.msa_iterations : st.outer_iterations;
  s.projectedGradient = st.norm_gP / normB;
  s.normGx = st.norm_Gx / normB;
  s.slipBoundChange = slipBoundChange;
  s.n_A = st.n_A;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

// The sublists "MPRGP" and "MPGP" of the block solvers, with their defaults.
void addInnerSolverLists(ParameterList& pl) {
  QP::QPSolverFactory factory;
  for (const char* name : {"MPRGP", "MPGP"})
    pl.sublist(name).setParameters(*factory.create(name, Teuchos::null)->getValidParameters());
}

}  // namespace

// ---------------------------------------------------------------- Algorithm 1

RCP<const ParameterList> Algorithm1::validParameters() {
  static RCP<ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Algorithm 1");
    pl->set("Inner Minimization", "Block Gauss-Seidel",
            "MPRGP on the normal block then MPGP on the tangential block (Block Gauss-Seidel), or one MPGP over the product set",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Block Gauss-Seidel", "MPGP"))));
    pl->set("Sweeps", 1, "maximum block Gauss-Seidel sweeps per inner minimization (fewer when the inner tolerance is met)",
            range<int>(1, 1000));
    QP::QPSolverFactory factory;
    auto smalbe = factory.create("SMALBE", Teuchos::null);
    ParameterList& s = pl->sublist("SMALBE");
    s.setParameters(*smalbe->getValidParameters());
    s.set("Relative Tolerance", 1e-6);
    // Measured on the seed brick (docs/benchmarks.md): M = 0.1 ||A|| keeps
    // the inner solves inexact enough; problems are scaled to ||A|| = 1.
    s.set("M", 0.1);
    s.set("Maximum Outer Iterations", 1000);
    addInnerSolverLists(*pl);
  }
  return pl;
}

RCP<const ParameterList> Algorithm1::getValidParameters() const { return validParameters(); }

Algorithm1::Algorithm1(const ParameterList& params) : params_(params) {
  params_.validateParametersAndSetDefaults(*validParameters());
}

FrictionStatus Algorithm1::solve(const ContactDual& dual, Vector& x) { return solve(dual, dual.slipBound, x); }

FrictionStatus Algorithm1::solve(const ContactDual& dual, const std::vector<SC>& g, Vector& x) {
  dual.check();
  const auto start = std::chrono::steady_clock::now();
  FrictionStatus st;
  const auto Omega = dual.constraintSet(g);
  // Inner solvers: the bound block by MPRGP, the circle block by MPGP.
  RCP<QP::QPSolver> inner;
  RCP<BlockGaussSeidel> bgs;
  RCP<QP::QPSolver> mpgp = makeQPSolver("MPGP", params_, "MPGP");
  if (params_.get<std::string>("Inner Minimization") == "Block Gauss-Seidel") {
    bgs = rcp(new BlockGaussSeidel(makeQPSolver("MPRGP", params_, "MPRGP"), mpgp, params_.get<int>("Sweeps"),
                                   dual.normalBlockMask(), dual.tangentBlockMask()));
    inner = bgs;
  } else {
    inner = mpgp;
  }
  if (!out_.is_null()) inner->setOutputStream(out_);
  long powerN_A = 0;
  if (normA_ <= 0) normA_ = estimateHessianNorm(dual, powerN_A);
  const auto& sp = params_.sublist("SMALBE");
  const SC tol = std::max(sp.get<double>("Relative Tolerance") * dual.normB(), sp.get<double>("Absolute Tolerance"));
  QP::QPStatus qs;
  if (dual.G.is_null()) {
    // No equality constraint: the inner solver alone, repeated (block
    // Gauss-Seidel does a fixed number of sweeps per call).
    inner->setHessianNorm(normA_);
    inner->setTolerance(tol);
    const int maxCalls = bgs.is_null() ? 1 : sp.get<int>("Maximum Outer Iterations") * 10;
    for (int k = 0; k < maxCalls; ++k) {
      const auto s = inner->solve(*dual.A, *dual.b, Omega, x);
      qs.n_A += s.n_A;
      qs.iterations += s.iterations;
      qs.norm_gP = s.norm_gP;
      qs.converged = s.converged;
      qs.reason = s.reason;
      qs.outer_iterations = k + 1;
      if (s.converged) break;
    }
  } else {
    auto smalbeParams = rcp(new ParameterList(sp));
    QP::SMALBE smalbe(smalbeParams);
    smalbe.setEqualityConstraint(dual.G);
    smalbe.setInnerSolver(inner);
    smalbe.setHessianNorm(normA_);
    smalbe.setTolerance(tol);
    if (!out_.is_null()) smalbe.setOutputStream(out_);
    // The multiplier of G x = 0 where the last solve ended: this object's
    // own (MSA's steps), else a previous solve's final state (a further
    // result-check round, a load step). From mu = 0 SMALBE would first
    // rebuild it, and a round asked for one more digit cost more than a
    // cold solve asked for it.
    const auto& mu0 = warm_.equalityMultiplier;
    if (warmStart_ && !mu_.is_null())
      smalbe.setMultiplier(*mu_);
    else if (!mu0.is_null() && mu0->getMap()->isSameAs(*dual.G->rangeMap()))
      smalbe.setMultiplier(*mu0);
    qs = smalbe.solve(*dual.A, *dual.b, Omega, x);
    mu_ = rcp(new Vector(smalbe.multiplier(), Teuchos::Copy));
    final_ = {rcp(new Vector(*mu_, Teuchos::Copy)), 0.0};
  }
  st.converged = qs.converged;
  st.reason = qs.reason;
  st.outer_iterations = qs.outer_iterations;
  st.inner_iterations = qs.iterations;
  st.n_A = qs.n_A + powerN_A;
  st.n_A_qpp = bgs.is_null() ? 0 : bgs->n_A_qpp();
  st.n_A_qpq = bgs.is_null() ? qs.n_A : bgs->n_A_qpq();
  st.norm_gP = qs.norm_gP;
  st.norm_Gx = qs.norm_Gx;
  st.slipBound = g;
  st.history.push_back(qs.norm_gP);
  // SMALBE reports its final state only: one step, no slip-bound change
  // (the bound is given).
  st.steps.push_back(outerStep(st, dual, std::numeric_limits<SC>::quiet_NaN(), start));
  return st;
}

// ---------------------------------------------------------------- MSA

RCP<const ParameterList> MSA::validParameters() {
  static RCP<ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("MSA");
    pl->set("Tolerance", 1e-4, "stop when ||g(l+1) - g(l)|| <= Tolerance ||g(l+1)||", range<double>(1e-15, 1.0));
    pl->set("Maximum Iterations", 50, "successive approximations", range<int>(1, 100000));
    pl->set("Initial Slip Bound", "Zero", "g(0): Zero, or F times the frictionless normal force (Frictionless)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Zero", "Frictionless"))));
  }
  return pl;
}

RCP<const ParameterList> MSA::getValidParameters() const { return validParameters(); }

double Algorithm1::requestedTolerance() const { return params_.sublist("SMALBE").get<double>("Relative Tolerance"); }

void Algorithm1::setRequestedTolerance(double tolerance) {
  setValidated(params_.sublist("SMALBE"), validParameters()->sublist("SMALBE"), "Relative Tolerance", tolerance,
               "Algorithm 1");
}

void Algorithm1::setMaximumIterations(int iterations) {
  setValidated(params_.sublist("SMALBE"), validParameters()->sublist("SMALBE"), "Maximum Outer Iterations",
               iterations, "Algorithm 1");
}

MSA::MSA(const ParameterList& params, const ParameterList& algorithm1) : params_(params), tresca_(algorithm1) {
  params_.validateParametersAndSetDefaults(*validParameters());
}

FrictionStatus MSA::solve(const ContactDual& dual, Vector& x) {
  const auto start = std::chrono::steady_clock::now();
  FrictionStatus st;
  const auto& comm = *dual.map()->getComm();
  if (!out_.is_null()) tresca_.setOutputStream(out_);
  tresca_.setWarmStart(true);
  long powerN_A = 0;
  tresca_.setHessianNorm(estimateHessianNorm(dual, powerN_A));
  st.n_A = powerN_A;
  auto accumulate = [&](const FrictionStatus& s) {
    st.outer_iterations += s.outer_iterations;
    st.inner_iterations += s.inner_iterations;
    st.n_A += s.n_A;
    st.n_A_qpp += s.n_A_qpp;
    st.n_A_qpq += s.n_A_qpq;
    st.norm_gP = s.norm_gP;
    st.norm_Gx = s.norm_Gx;
  };
  std::vector<SC> g(dual.numLocalContacts(), 0.0);
  if (params_.get<std::string>("Initial Slip Bound") == "Frictionless") {
    accumulate(tresca_.solve(dual, g, x));
    g = dual.coulombSlipBound(x);
  }
  const SC eps = params_.get<double>("Tolerance");
  const int maxIter = params_.get<int>("Maximum Iterations");
  for (int l = 1; l <= maxIter; ++l) {
    const auto s = tresca_.solve(dual, g, x);
    accumulate(s);
    const auto gNew = dual.coulombSlipBound(x);
    const SC norm = globalNorm(gNew, comm);
    st.slip_bound_change = globalDistance(gNew, g, comm) / (norm > 0 ? norm : 1.0);
    st.history.push_back(st.slip_bound_change);
    st.msa_iterations = l;
    st.steps.push_back(outerStep(st, dual, st.slip_bound_change, start));
    st.slipBound = g;
    if (!out_.is_null())
      *out_ << "MSA " << std::setw(3) << l << "  ||g(l+1) - g(l)||/||g(l+1)|| = " << std::scientific << std::setprecision(3)
            << st.slip_bound_change << "  SMALBE outer " << s.outer_iterations << "  n_A " << s.n_A << "\n";
    Progress::iteration([&] {
      return "MSA " + std::to_string(l) + ": slip-bound change " + Progress::sci(st.slip_bound_change) + ", n_A " +
             std::to_string(st.n_A);
    });
    if (!s.converged) {
      st.reason = "Tresca step " + std::to_string(l) + " did not converge: " + s.reason;
      // A rigid motion that only friction holds has no frictionless
      // equilibrium, so MSA cannot start from the slip bound 0.
      if (globalNorm(g, comm) == 0)
        st.reason += " (its slip bound is 0: a body that only friction holds in some direction has no "
                     "frictionless equilibrium; solve it by Algorithm2)";
      return st;
    }
    if (st.slip_bound_change <= eps || norm == 0) {
      st.converged = true;
      st.reason = "slip bound fixed point reached";
      return st;
    }
    g = gNew;
  }
  st.reason = "Maximum Iterations (" + std::to_string(maxIter) + ") of MSA reached";
  return st;
}

// ---------------------------------------------------------------- Algorithm 2

RCP<const ParameterList> Algorithm2::validParameters() {
  static RCP<ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Algorithm 2");
    pl->set("Relative Tolerance", 1e-6,
            "stop when ||g^P|| and ||G lambda|| <= tol ||b||; g^P is taken with the slip bound F lambda_N of the final "
            "iterate, so this bounds the residual of the Coulomb conditions",
            range<double>(1e-15, 1.0));
    pl->set("Slip Bound Tolerance", 0.0,
            "optional third test ||g(l+1) - g(l)|| <= tol ||g(l+1)||; 0 switches it off (the change between two inexact "
            "iterates stalls near the noise of the inner solves and adds iterations, not accuracy)",
            range<double>(0.0, 1.0));
    pl->set("Maximum Iterations", 5000,
            "outer iterations; with one sweep each costs about as much as a few applications of F, and the "
            "two blocks by FETI-1 at tolerance 1e-8 take 1341",
            range<int>(1, 1000000));
    pl->set("Sweeps", 1,
            "block Gauss-Seidel sweeps (lambda_c, then lambda_t in Lambda_t(F lambda_N)) per outer iteration, fewer "
            "when the inner tolerance is met; one sweep (the default) leaves the coupling of the blocks to the outer "
            "loop, which costs fewer applications of F in all than repeated sweeps (docs/friction.md)",
            range<int>(1, 1000));
    pl->set("Inner Tolerance Floor", 0.5,
            "inner solves stop no lower than this times the outer tolerance (below 1, so that a sweep can bring the "
            "joint projected gradient under the outer tolerance)",
            range<double>(1e-6, 1.0));
    pl->set("Inner Relative Tolerance", 0.3,
            "inner solves stop no lower than this times the joint projected gradient of the previous outer iteration: "
            "the block Gauss-Seidel sweeps cannot bring the joint residual down faster than the coupling of the blocks "
            "allows, so tighter block solves are wasted work; 0 leaves only M ||G lambda||, eta and the floor",
            range<double>(0.0, 1.0));
    pl->set("rho", 0.0, "initial penalty; 0 means ||A||", range<double>(0.0, 1e300));
    pl->set("Residual Balancing", 2.0,
            "rho <- rho Factor * rho when ||G lambda|| > this times ||g^P|| (the penalty is too weak for the equality "
            "constraint), rho <- rho / rho Factor when ||g^P|| > this times ||G lambda|| (the penalty couples the "
            "Gauss-Seidel blocks more than feasibility needs); 0 keeps rho fixed, otherwise at least 1",
            range<double>(0.0, 1e6));
    pl->set("rho Factor", 2.0, "factor of a residual-balancing change of rho", range<double>(1.0 + 1e-12, 1e6));
    pl->set("Minimum rho", 0.25, "lower limit of residual balancing, as a multiple of the initial rho",
            range<double>(1e-12, 1.0));
    pl->set("Maximum rho", 8.0, "upper limit of residual balancing, as a multiple of the initial rho",
            range<double>(1.0, 1e12));
    pl->set("M", 0.0, "inner precision control; 0 means 0.3 ||A||", range<double>(0.0, 1e300));
    pl->set("eta", 1e-2,
            "inner precision cap, as a multiple of ||b||; it is the precision of the first outer iteration, whose "
            "iterate sets the first slip bound and the scale of ||G lambda||",
            range<double>(1e-300, 1e300));
    pl->set("beta", 2.0, "M <- M / beta when the augmented Lagrangian does not grow enough", range<double>(1.0 + 1e-12, 1e6));
    addInnerSolverLists(*pl);
  }
  return pl;
}

double MSA::requestedTolerance() const {
  return std::max(tresca_.requestedTolerance(), params_.get<double>("Tolerance"));
}

void MSA::setRequestedTolerance(double tolerance) {
  setValidated(params_, *validParameters(), "Tolerance", tolerance, "MSA");
  tresca_.setRequestedTolerance(tolerance);
}

void MSA::setMaximumIterations(int iterations) { setValidated(params_, *validParameters(), "Maximum Iterations", iterations, "MSA"); }

Algorithm2::Algorithm2(const ParameterList& params) : SingleLoopSolver(params, validParameters()) {
  const double ratio = params_.get<double>("Residual Balancing");
  if (ratio > 0 && ratio < 1)
    throw Error("Algorithm 2: Residual Balancing = " + std::to_string(ratio) +
                " must be 0 (rho fixed) or at least 1 (otherwise both residuals could ask for opposite changes)");
}


FrictionStatus Algorithm2::solve(const ContactDual& dual, Vector& x) {
  dual.check();
  const auto start = std::chrono::steady_clock::now();
  FrictionStatus st;
  const auto& comm = *dual.map()->getComm();
  const RCP<const QP::EqualityConstraint> G =
      dual.G.is_null() ? RCP<const QP::EqualityConstraint>(rcp(new QP::NoEqualityConstraint(dual.map()->getComm()))) : dual.G;
  auto mprgp = makeQPSolver("MPRGP", params_, "MPRGP");
  auto mpgp = makeQPSolver("MPGP", params_, "MPGP");
  if (!out_.is_null()) mprgp->setOutputStream(out_), mpgp->setOutputStream(out_);
  const SC normA = estimateHessianNorm(dual, st.n_A);
  const SC normB = dual.normB();
  SC rho = params_.get<double>("rho") > 0 ? params_.get<double>("rho") : normA;
  // Limits with a little slack, so that rho0 * factor^k hits them exactly.
  const QP::RhoBalancing balancing{params_.get<double>("Residual Balancing"), params_.get<double>("rho Factor"),
                               params_.get<double>("Minimum rho") * rho * (1 - 1e-12),
                               params_.get<double>("Maximum rho") * rho * (1 + 1e-12)};
  // M = 0.3 ||A||: chosen on the seed brick (docs/friction.md).
  SC M = params_.get<double>("M") > 0 ? params_.get<double>("M") : 0.3 * normA;
  const SC eta = params_.get<double>("eta") * (normB > 0 ? normB : 1.0);
  const SC beta = params_.get<double>("beta");
  const SC tol = params_.get<double>("Relative Tolerance") * normB;
  const SC slipTol = params_.get<double>("Slip Bound Tolerance");
  const SC innerFloor = params_.get<double>("Inner Tolerance Floor");
  const SC innerRelative = params_.get<double>("Inner Relative Tolerance");
  const int sweeps = params_.get<int>("Sweeps");

  const auto normalMask = dual.normalBlockMask(), tangentMask = dual.tangentBlockMask();
  // ||A + rho G'G|| <= ||A|| + rho ||G'G||; ||G'G|| by the power method once
  // (1 for the orthonormal FETI constraint), not counted as Hessian work.
  QP::AugmentedLagrangian al(*dual.A, *G, dual.jointHessian.get());
  const SC normGtG = dual.G.is_null() ? 0 : al.normGtG(20);
  const auto& mu0 = warm_.equalityMultiplier;
  if (!mu0.is_null() && mu0->getMap()->isSameAs(*al.multiplier()->getMap())) {
    al.multiplier()->assign(*mu0);
    if (warm_.rho > 0) rho = std::min(std::max(warm_.rho, balancing.lowest), balancing.highest);
  }
  // The state a next solve may start from (setWarmStart), at every return.
  auto finish = [&](FrictionStatus& s) -> FrictionStatus& {
    final_ = {rcp(new Vector(*al.multiplier(), Teuchos::Copy)), rho};
    return s;
  };
  Vector grad(dual.map()), gP(dual.map());
  std::vector<SC> g = dual.coulombSlipBound(x);
  SC normGx = al.normGx(x);
  const int maxIter = params_.get<int>("Maximum Iterations");
  for (int l = 1; l <= maxIter; ++l) {
    const Vector& bIn = al.linearTerm(*dual.b);
    const QP::AugmentedHessian& H = al.hessian(rho);
    // The first blocks start from G x = 0, where M ||G x|| would ask for an
    // exact solve of a problem whose slip bound is still a guess: use eta.
    // Later, SMALBE's M ||G x|| (M shrinks whenever L grows too little) is
    // relaxed to a fraction of the previous joint projected gradient.
    const SC innerTol = std::max(
        innerFloor * tol, l == 1 ? eta : std::min(std::max(M * normGx, innerRelative * st.norm_gP), eta));
    for (auto* s : {&mprgp, &mpgp}) {
      (*s)->setHessianNorm(normA + rho * normGtG);
      (*s)->setTolerance(innerTol);
    }
    // lambda_c with lambda_t fixed, then lambda_t in Lambda_t(F lambda_N(l+1));
    // repeated up to "Sweeps" times while the joint projected gradient is
    // above the inner tolerance.
    std::vector<SC> gNew;
    long nA_c = 0, nA_t = 0;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      const auto sc = mprgp->solve(H, bIn, dual.constraintSet(sweep == 0 ? g : gNew).fixedOutside(normalMask), x);
      gNew = dual.coulombSlipBound(x);
      const auto Omega = dual.constraintSet(gNew);
      const auto stt = mpgp->solve(H, bIn, Omega.fixedOutside(tangentMask), x);
      st.n_A += sc.n_A + stt.n_A;
      st.n_A_qpp += sc.n_A;
      st.n_A_qpq += stt.n_A;
      st.inner_iterations += sc.iterations + stt.iterations;
      Tpetra::deep_copy(grad, *mpgp->gradient());
      Omega.projectedGradient(x, grad, gP);
      st.norm_gP = gP.norm2();
      nA_c += sc.n_A;
      nA_t += stt.n_A;
      if (st.norm_gP <= innerTol) break;
    }
    const QP::AugmentedLagrangian::Step step = al.update(x, grad, rho);
    normGx = step.normGx;
    // Relative to the larger of the two bounds, so that a bound that
    // vanishes (contact lost) gives a change of at most 2, not 1/round-off.
    const SC gNorm = std::max(globalNorm(gNew, comm), globalNorm(g, comm));
    st.slip_bound_change = globalDistance(gNew, g, comm) / (gNorm > 0 ? gNorm : 1.0);
    st.history.push_back(st.slip_bound_change);
    st.outer_iterations = l;
    st.norm_Gx = normGx;
    st.slipBound = gNew;
    st.steps.push_back(outerStep(st, dual, st.slip_bound_change, start));
    if (!out_.is_null())
      *out_ << "Algorithm 2 " << std::setw(3) << l << "  tol " << std::scientific << std::setprecision(3) << tol
            << "  ||g^P|| " << st.norm_gP << "  ||G lambda|| " << normGx << "  dg " << st.slip_bound_change << "  rho " << rho
            << "  M " << M << "  n_A " << nA_c << "+" << nA_t << "\n";
    Progress::iteration([&] {
      return "Algorithm 2 outer " + std::to_string(l) + ": ||g^P|| " + Progress::sci(st.norm_gP) + ", ||G lambda|| " +
             Progress::sci(normGx) + ", slip-bound change " + Progress::sci(st.slip_bound_change) + ", tolerance " +
             Progress::sci(tol);
    });
    g = gNew;
    if (st.norm_gP <= tol && normGx <= tol && (slipTol == 0 || st.slip_bound_change <= slipTol)) {
      st.converged = true;
      st.reason = slipTol == 0 ? "projected gradient and ||G lambda|| below tolerance"
                               : "projected gradient, ||G lambda|| and slip-bound change below tolerance";
      return finish(st);
    }
    if (l > 1 && step.grewTooLittle) M /= beta;
    if (!dual.G.is_null()) rho = balancing.update(rho, normGx, st.norm_gP);  // rho acts only through G
  }
  st.reason = "Maximum Iterations (" + std::to_string(maxIter) + ") of Algorithm 2 reached";
  return finish(st);
}

// ---------------------------------------------------------------- factory

// ---------------------------------------------------------------- SingleLoopSolver

SingleLoopSolver::SingleLoopSolver(const ParameterList& params, RCP<const ParameterList> valid)
    : params_(params), valid_(valid) {
  params_.validateParametersAndSetDefaults(*valid_);
}

double SingleLoopSolver::requestedTolerance() const { return params_.get<double>("Relative Tolerance"); }

void SingleLoopSolver::setRequestedTolerance(double tolerance) {
  setValidated(params_, *valid_, "Relative Tolerance", tolerance, valid_->name());
  parametersChanged();
}

void SingleLoopSolver::setMaximumIterations(int iterations) {
  setValidated(params_, *valid_, "Maximum Iterations", iterations, valid_->name());
  parametersChanged();
}

const FrictionSolverRegistry& frictionSolvers() {
  static const FrictionSolverRegistry registry = [] {
    auto sub = [](const ParameterList& p, const char* n) { return p.isSublist(n) ? p.sublist(n) : ParameterList(n); };
    FrictionSolverRegistry r("outer algorithm");
    // (Named Tresca once: the alias keeps such inputs running.)
    r.add("Algorithm1", [=](const ParameterList& p) -> RCP<FrictionSolver> { return rcp(new Algorithm1(sub(p, "Algorithm 1"))); },
          "Algorithm 1: SMALBE for the given slip bound (Tresca friction, frictionless contact)",
          {"Frictionless", "Tresca"}, {"Tresca"});
    r.add("MSA+Algorithm1",
          [=](const ParameterList& p) -> RCP<FrictionSolver> { return rcp(new MSA(sub(p, "MSA"), sub(p, "Algorithm 1"))); },
          "the method of successive approximations over Tresca problems", {"Coulomb"});
    r.add("Algorithm2", [=](const ParameterList& p) -> RCP<FrictionSolver> { return rcp(new Algorithm2(sub(p, "Algorithm 2"))); },
          "the slip bound updated inside the augmented Lagrangian loop", {"Coulomb"});
    r.add("Semismooth Newton",
          [=](const ParameterList& p) -> RCP<FrictionSolver> {
            return rcp(new SemismoothNewton(sub(p, "Semismooth Newton")));
          },
          "Newton on the Alart-Curnier function with an Armijo line search (dense: up to its Dense Limit of "
          "dual rows)",
          {"Coulomb"});
    r.add("NSGS",
          [=](const ParameterList& p) -> RCP<FrictionSolver> { return rcp(new NonsmoothGaussSeidel(sub(p, "NSGS"))); },
          "nonsmooth Gauss-Seidel: sweeps over the contacts, each solved exactly (needs W explicitly: FCLIB "
          "problems)",
          {kExplicitCoulomb});
    return r;
  }();
  return registry;
}

std::vector<std::string> dualSolverNames() {
  std::vector<std::string> out;
  for (const auto& name : frictionSolvers().names())
    for (FrictionLaw law : {FrictionLaw::Frictionless, FrictionLaw::Tresca, FrictionLaw::Coulomb})
      if (frictionSolvers().accepts(name, frictionLawName(law))) {
        out.push_back(name);
        break;
      }
  return out;
}

std::vector<std::string> dualSolverAliases() {
  const auto names = dualSolverNames();
  std::vector<std::string> out;
  for (const auto& alias : frictionSolvers().aliases())
    if (std::find(names.begin(), names.end(), frictionSolvers().canonical(alias)) != names.end()) out.push_back(alias);
  return out;
}

std::string dualSolverDocumentation() {
  std::string doc = frictionSolvers().documentation(dualSolverNames());
  for (const auto& alias : dualSolverAliases()) doc += "; " + alias + " (" + frictionSolvers().canonical(alias) + ")";
  return doc;
}

RCP<FrictionSolver> FrictionSolverFactory::create(const std::string& name, const ParameterList& params) const {
  return frictionSolvers().create(name, params);
}

void FrictionSolverFactory::addValidParameters(ParameterList& solverList) {
  solverList.sublist("Algorithm 1").setParameters(*Algorithm1::validParameters());
  solverList.sublist("MSA").setParameters(*MSA::validParameters());
  solverList.sublist("Algorithm 2").setParameters(*Algorithm2::validParameters());
  solverList.sublist("Semismooth Newton").setParameters(*SemismoothNewton::validParameters());
  solverList.sublist("NSGS").setParameters(*NonsmoothGaussSeidel::validParameters());
}

}  // namespace Friction
}  // namespace Tribos
