#include "Tribos_FetiSolve.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <memory>

#include "Tribos_Error.hpp"
#include "Tribos_FetiDual.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_ProjectedCG.hpp"

namespace Tribos {
namespace Contact {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The entries of params that solveFeti reads, validated against
// fetiSolveParameters() (so a misspelled algorithm or a value out of range
// is refused with its name), defaults filled.
Teuchos::ParameterList validatedSolveParameters(const Teuchos::ParameterList& params) {
  const auto valid = fetiSolveParameters();
  Teuchos::ParameterList p;
  for (auto it = valid->begin(); it != valid->end(); ++it) {
    const std::string& name = valid->name(it);
    if (name == "FETI") continue;  // only its "Projected CG" is read here
    if (params.isSublist(name)) p.sublist(name).setParameters(params.sublist(name));
    else if (params.isParameter(name)) p.setEntry(name, params.getEntry(name));
  }
  if (params.isSublist("FETI") && params.sublist("FETI").isSublist("Projected CG"))
    p.sublist("FETI").sublist("Projected CG").setParameters(params.sublist("FETI").sublist("Projected CG"));
  p.validateParametersAndSetDefaults(*valid);
  return p;
}

// The result the user gets, from r.primal and r.lambda: the nodal
// displacement, the contact forces, the KKT residuals and the verdict
// against r.tolerance. previous: the nodal displacement of the previous
// load step (the origin of the slip), or none.
void checkResult(const Feti::FetiProblem& problem, const PairFriction& friction, const Teuchos::ParameterList& p,
                 FetiSolveResult& r, const Fem::NodalVector* previous) {
  Progress::stage("result check");
  r.u = problem.nodalDisplacement(*r.primal);
  if (problem.hasContact())
    r.contact = contactResults(problem, r.u, *r.lambda, r.status.slipBound, friction, previous);
  r.contact.bonded = bondedForces(problem, *r.lambda);
  r.kkt = resultKKT(problem, r.u, r.contact, friction, r.counts);
  r.verdict = Contact::resultVerdict(r.kkt, r.solverConverged, r.solverReason, r.tolerance,
                                     p.get<double>("Result Check Factor"));
}

// What a load step continues from: the previous step's multipliers (the
// start of the iterations) and nodal displacement (the origin of the slip),
// the norm of the contact dual (the same operator), and the counts of F
// before the step. Empty: a solve from rest.
struct Continuation {
  RCP<const Vector> lambda;
  const Friction::WarmStart* warm = nullptr;  // the previous solve's final outer state
  const Fem::NodalVector* u = nullptr;
  double normPFP = 0;
  long long F_applications = 0;
  double F_seconds = 0;
};

// A dense algorithm's size limit, before the coarse space and the solve
// (the same dual size, hence the same refusal, on every rank).
void checkDualSize(const Feti::FetiProblem& problem, const PairFriction& friction, const Teuchos::ParameterList& p) {
  if (!problem.hasContact()) return;
  try {
    Friction::FrictionSolverFactory()
        .create(outerAlgorithmFor(p.get<std::string>("Outer Algorithm"), friction), p)
        ->checkDualRows(static_cast<long long>(problem.dualMap()->getGlobalNumElements()));
  } catch (const Error& e) {
    throw CollectiveError(e.what());
  }
}

// The outer algorithm r.outerAlgorithm on cp in rounds: a solve that meets
// its own test with a result that misses the check is asked again from its
// result, the tolerance tightened by the miss (Friction::tightenedTolerance);
// the check keeps the first tolerance, so converged still means factor x
// what was asked for. followsAnother: r already holds another algorithm's
// solve, whose counts this one's add to.
void solveInRounds(const FetiContactProblem& cp, const PairFriction& friction, const Teuchos::ParameterList& p,
                   RCP<Teuchos::FancyOStream> out, RCP<const Vector> start, const Continuation& from, FetiSolveResult& r,
                   Friction::WarmStart* warmOut, bool followsAnother) {
  const Feti::FetiProblem& problem = cp.fetiDual().problem();
  const int rounds = p.get<int>("Result Check Rounds");
  double requested = 0;
  // A further round resumes the outer state its round ended with (the
  // multiplier of G x = 0 and the penalty), not only x: from x alone the
  // augmented Lagrangian starts over and a round asked for one more digit
  // cost more than a cold solve asked for it.
  Friction::WarmStart roundState;
  for (int round = 1; round <= rounds; ++round) {
    Progress::stage("contact solve: " + r.outerAlgorithm + (round > 1 ? ", round " + std::to_string(round) : ""));
    const auto sol = cp.solve(r.outerAlgorithm, p, out, start.get(), requested, round == 1 ? from.warm : &roundState);
    roundState = sol.warmStart;
    if (warmOut) *warmOut = sol.warmStart;
    if (round == 1) r.tolerance = sol.requestedTolerance;
    requested = sol.requestedTolerance;
    r.status = round == 1 && !followsAnother ? sol.status : Friction::followedBy(r.status, sol.status);
    r.iterations = r.status.outer_iterations;
    r.n_A += sol.n_A;
    r.solverConverged = sol.status.converged;
    r.solverReason = sol.status.reason;
    r.lambda->assign(*sol.lambda);
    r.primal = sol.u;
    r.rounds = round;
    {
      static const auto checkTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::contact: result check");
      Teuchos::TimeMonitor checkTime(*checkTimer);
      checkResult(problem, friction, p, r, from.u);
    }
    if (!out.is_null()) {
      std::string which;
      const double worst = r.kkt.worst(&which);
      *out << "result check: largest KKT residual " << worst << " (" << which << "), limit " << r.verdict.limit
           << "\n";
    }
    if (!r.solverConverged || r.verdict.converged || round == rounds || Friction::atTightestTolerance(requested))
      break;
    // A quarter of the miss: the KKT residuals of the result (maxima over the
    // nodes) grow against the solver's measure (a norm over all rows) as the
    // iterate converges; on the million-dof brick their ratio went from 13 to
    // 27 within a round, and half the miss left a second round 9 % short.
    requested = Friction::tightenedTolerance(requested, r.verdict.limit, r.kkt.worst(), 0.25);
    start = sol.x;
  }
}

// The solve of one dual problem: projected CG without contact, else the
// outer algorithm in rounds until the result meets its check; then the
// result the user gets. normPFP: set to the norm of the contact dual.
FetiSolveResult solveDual(const RCP<const Feti::FetiDual>& dual, const PairFriction& friction,
                          const Teuchos::ParameterList& p, RCP<Teuchos::FancyOStream> out, const Continuation& from,
                          double* normPFP, Friction::WarmStart* warmOut = nullptr) {
  const Feti::FetiProblem& problem = dual->problem();
  FetiSolveResult r;
  r.lambda = rcp(new Vector(problem.dualMap()));
  PairFriction law = friction;
  const auto t0 = std::chrono::steady_clock::now();
  if (!problem.hasContact()) {
    Progress::stage("projected CG");
    const auto& pcgParams = p.sublist("FETI").sublist("Projected CG");
    Feti::ProjectedCG pcg(pcgParams);
    if (!out.is_null()) pcg.setOutputStream(out);
    const auto st = pcg.solve(*dual, *r.lambda);
    r.iterations = st.iterations;
    r.n_A = st.n_A;
    r.relativeResidual = st.relativeResidual;
    r.solverConverged = st.converged;
    if (!st.converged) r.solverReason = "projected CG: maximum iterations";
    r.tolerance = pcgParams.get<double>("Tolerance");
    r.primal = dual->recoverPrimal(*r.lambda);
    law = {FrictionSpec()};  // no contact forces to check
  } else {
    static const auto setupTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::contact: dual problem setup");
    std::unique_ptr<Teuchos::TimeMonitor> setupTime(new Teuchos::TimeMonitor(*setupTimer));
    FetiContactProblem cp(dual, friction, from.normPFP);
    if (normPFP) *normPFP = cp.norm();
    const std::string requestedAlgorithm = p.get<std::string>("Outer Algorithm");
    r.outerAlgorithm =
        outerAlgorithmFor(requestedAlgorithm, friction);
    const std::string runLawName = frictionLawName(runLaw(friction));
    TRIBOS_REQUIRE(Friction::frictionSolvers().accepts(r.outerAlgorithm, runLawName),
                   "Outer Algorithm = " << r.outerAlgorithm << " does not solve " << runLawName << " friction ("
                                        << joinNames(Friction::frictionSolvers().accepting(runLawName)) << " do)");
    // A later load step starts from the multipliers of the one before:
    // x = lambda_prev - lambda(0), lambda(0) the chain's back map of x = 0.
    RCP<const Vector> start;
    if (!from.lambda.is_null()) start = cp.startFrom(*from.lambda);
    setupTime.reset();
    // Auto's Newton is the matrix-free one at any size, asked for the
    // accuracy asked of Algorithm 2 (the user's one tolerance; the result
    // check promises the same KKT residuals whichever method ran); a solve
    // that stops without converging, or whose result misses its check, is
    // followed by Algorithm 2 from the same start, the counts of both in the
    // result.
    const bool autoNewton = requestedAlgorithm == kAutoOuterAlgorithm && r.outerAlgorithm == "Semismooth Newton";
    Teuchos::ParameterList params(p);
    if (autoNewton) {
      Teuchos::ParameterList& newton = params.sublist("Semismooth Newton");
      newton.set("Linear Solver", "Projected CG");
      newton.set("Relative Tolerance", p.sublist("Algorithm 2").get<double>("Relative Tolerance"));
    }
    solveInRounds(cp, friction, params, out, start, from, r, warmOut, false);
    if (autoNewton && !(r.solverConverged && r.verdict.converged)) {
      r.handover = r.solverConverged ? "its result missed the check: " + r.verdict.stopReason : r.solverReason;
      if (!out.is_null()) *out << "Semismooth Newton: " << r.handover << "; Algorithm2 follows\n";
      r.outerAlgorithm = "Algorithm2";
      solveInRounds(cp, friction, p, out, start, from, r, warmOut, true);
    }
  }
  r.solveSeconds = secondsSince(t0);
  r.F_applications = dual->F()->applications() - from.F_applications;
  r.F_seconds = dual->F()->seconds() - from.F_seconds;
  r.coarseSize = dual->coarse().size();
  r.coarseFactorMb = dual->coarse().factorMemoryMb();
  if (!problem.hasContact()) checkResult(problem, law, p, r, nullptr);
  return r;
}

}  // namespace

std::string outerAlgorithmFor(const std::string& requested, const PairFriction& friction) {
  if (requested != kAutoOuterAlgorithm) return Friction::frictionSolvers().canonical(requested);
  return runLaw(friction) == FrictionLaw::Coulomb ? "Semismooth Newton" : "Algorithm1";
}

RCP<const Teuchos::ParameterList> fetiSolveParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Solver");
    // The algorithms that solve this dual, and their aliases (outerAlgorithmFor maps them).
    std::vector<std::string> names{kAutoOuterAlgorithm};
    for (const auto& list : {Friction::dualSolverNames(), Friction::dualSolverAliases()})
      names.insert(names.end(), list.begin(), list.end());
    pl->set("Outer Algorithm", kAutoOuterAlgorithm,
            "contact problems: Auto (Coulomb friction: Semismooth Newton, matrix-free, at Algorithm 2's Relative "
            "Tolerance, whether Dirichlet conditions or the contact hold the bodies, followed by Algorithm2 if it "
            "stops short (the summary's newton_handover says why); Algorithm1 for Tresca friction and frictionless "
            "contact); " + Friction::dualSolverDocumentation(),
            rcp(new Teuchos::StringValidator(Teuchos::Array<std::string>(names.begin(), names.end()))));
    pl->set("Result Check Factor", 100.0,
            "converged means every KKT residual of the written result (docs/friction.md) is at most this factor "
            "times the solver's requested tolerance",
            rcp(new Teuchos::EnhancedNumberValidator<double>(1.0, 1e300)));
    pl->set("Result Check Rounds", 3,
            "contact: when the outer algorithm meets its stopping test but a KKT residual of the result exceeds "
            "the Result Check Factor times its tolerance, solve again from that result with the tolerance "
            "tightened by the miss, up to this many solves in all (1: no second solve)",
            rcp(new Teuchos::EnhancedNumberValidator<int>(1, 20)));
    Friction::FrictionSolverFactory::addValidParameters(*pl);
    pl->sublist("FETI").sublist("Projected CG").setParameters(*Feti::ProjectedCG::getValidParameters());
  }
  return pl;
}

FetiSolveResult solveFeti(const RCP<const Feti::FetiProblem>& problem, const PairFriction& friction,
                          const Teuchos::ParameterList& params, RCP<Teuchos::FancyOStream> out) {
  const Teuchos::ParameterList p = validatedSolveParameters(params);
  checkDualSize(*problem, friction, p);
  return solveDual(rcp(new Feti::FetiDual(problem)), friction, p, out, Continuation(), nullptr);
}

FetiLoadSteps::FetiLoadSteps(const RCP<Feti::FetiProblem>& problem, const PairFriction& friction,
                             const Teuchos::ParameterList& params, RCP<Teuchos::FancyOStream> out)
    : problem_(problem), friction_(friction), params_(validatedSolveParameters(params)), out_(out) {
  checkDualSize(*problem_, friction_, params_);
}

FetiSolveResult FetiLoadSteps::solve(const Fem::LoadCase& loads) {
  problem_->setLoads(loads);
  return solveNext();
}

FetiSolveResult FetiLoadSteps::solveNext() {
  Continuation from;
  if (!primal_.is_null()) {
    // Friction acts on the slip since the previous step: the tangential
    // rows measure B_T (u - u_prev).
    problem_->setTangentialOffset(*primal_);
    from.lambda = lambda_;
    from.warm = &warm_;
    from.u = &u_;
  }
  if (!operators_.is_null()) {
    // The operators of the first step solved here serve this one.
    from.normPFP = normPFP_;
    from.F_applications = operators_->F()->applications();
    from.F_seconds = operators_->F()->seconds();
  }
  static const auto dualTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::contact: load step's dual");
  std::unique_ptr<Teuchos::TimeMonitor> dualTime(new Teuchos::TimeMonitor(*dualTimer));
  auto dual = operators_.is_null() ? rcp(new Feti::FetiDual(problem_)) : rcp(new Feti::FetiDual(problem_, *operators_));
  if (operators_.is_null()) operators_ = dual;
  if (!from.lambda.is_null()) from.lambda = predictedMultipliers(*dual);
  dualTime.reset();
  auto r = solveDual(dual, friction_, params_, out_, from, &normPFP_, &warm_);
  lambdaBefore_ = lambda_;
  hBefore_ = h_;
  h_ = rcp(new Vector(dual->h(), Teuchos::Copy));
  lambda_ = r.lambda;
  primal_ = r.primal;
  u_ = r.u;
  ++steps_;
  return r;
}

// The multipliers extrapolated along the load path: lambda_prev + omega
// (lambda_prev - lambda_before), omega the share of the previous increment
// of the dual right-hand side h that this step repeats, (dh_now . dh_prev) /
// ||dh_prev||^2, kept in [0, 2]. A load applied in equal increments
// (proportional loading: omega = 1) starts where its solution lies when
// the contact state does not change; a reversal or a new load (omega <= 0)
// starts from the previous step's multipliers, as does the second step.
void FetiLoadSteps::stiffnessChanged() {
  operators_ = Teuchos::null;
  normPFP_ = 0;
  // The multipliers stay a start; the extrapolation along the load path
  // does not hold across a change of K.
  lambdaBefore_ = hBefore_ = h_ = Teuchos::null;
}

RCP<const Vector> FetiLoadSteps::predictedMultipliers(const Feti::FetiDual& dual) const {
  if (lambdaBefore_.is_null() || hBefore_.is_null() || h_.is_null()) return lambda_;
  Vector now(dual.h(), Teuchos::Copy), before(*h_, Teuchos::Copy);
  now.update(-1.0, *h_, 1.0);
  before.update(-1.0, *hBefore_, 1.0);
  const double scale = before.dot(before);
  if (!(scale > 0)) return lambda_;
  const double omega = std::min(2.0, now.dot(before) / scale);
  if (!(omega > 0)) return lambda_;
  auto predicted = rcp(new Vector(*lambda_, Teuchos::Copy));
  predicted->update(-omega, *lambdaBefore_, 1.0 + omega);
  return predicted;
}

void FetiLoadSteps::resumeFrom(const Fem::NodalVector& uPrevious) {
  const Fem::NodalLayout& layout = *problem_->nodalLayout();
  TRIBOS_REQUIRE(!uPrevious.empty() && uPrevious.layout().nodes() == layout.nodes(),
                 "FetiLoadSteps::resumeFrom: the displacement is not given at the problem's nodes (nodalLayout())");
  auto primal = rcp(new Vector(problem_->primalMap()));
  auto values = primal->getDataNonConst();
  size_t offset = 0;
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) {
    const auto& sys = problem_->subdomain(k);
    for (size_t a = 0; a < sys.nodes.size(); ++a)
      for (int c = 0; c < 3; ++c) values[offset + 3 * a + c] = uPrevious.at(sys.nodes[a])[c];
    offset += sys.numDofs();
  }
  primal_ = primal;
  u_ = uPrevious;
  lambda_ = lambdaBefore_ = Teuchos::null;
  h_ = hBefore_ = Teuchos::null;
}

}  // namespace Contact
}  // namespace Tribos
