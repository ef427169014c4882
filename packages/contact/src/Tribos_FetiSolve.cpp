#include "Tribos_FetiSolve.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_Vector.hpp>

#include <chrono>

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
// against r.tolerance.
void checkResult(const Feti::FetiProblem& problem, const PairFriction& friction, const Teuchos::ParameterList& p,
                 FetiSolveResult& r) {
  Progress::stage("result check");
  r.u = problem.nodalDisplacement(*r.primal);
  if (problem.hasContact())
    r.contact = contactResults(problem, r.u, *r.lambda, r.status.slipBound, friction, r.counts);
  r.contact.bonded = bondedForces(problem, *r.lambda);
  r.kkt = resultKKT(problem, r.u, r.contact, friction);
  r.verdict = Contact::resultVerdict(r.kkt, r.solverConverged, r.solverReason, r.tolerance,
                                 p.get<double>("Result Check Factor"));
}

}  // namespace

std::string outerAlgorithmFor(const std::string& requested, const PairFriction& friction) {
  if (requested != kAutoOuterAlgorithm) return Friction::frictionSolvers().canonical(requested);
  return runLaw(friction) == FrictionLaw::Coulomb ? "Algorithm2" : "Algorithm1";
}

RCP<const Teuchos::ParameterList> fetiSolveParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Solver");
    auto names = Friction::frictionSolvers().names();
    names.insert(names.begin(), kAutoOuterAlgorithm);
    pl->set("Outer Algorithm", kAutoOuterAlgorithm,
            "contact problems: Auto (Algorithm2 for Coulomb friction, Algorithm1 for Tresca friction and "
            "frictionless contact); " + Friction::frictionSolvers().documentation(),
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
  if (problem->hasContact()) {
    // A dense algorithm's size limit, before the coarse space and the solve
    // (the same dual size, hence the same refusal, on every rank).
    try {
      Friction::FrictionSolverFactory()
          .create(outerAlgorithmFor(p.get<std::string>("Outer Algorithm"), friction), p)
          ->checkDualRows(static_cast<long long>(problem->dualMap()->getGlobalNumElements()));
    } catch (const Error& e) {
      throw CollectiveError(e.what());
    }
  }
  auto dual = rcp(new Feti::FetiDual(problem));
  FetiSolveResult r;
  r.lambda = rcp(new Vector(problem->dualMap()));
  PairFriction law = friction;
  const auto t0 = std::chrono::steady_clock::now();
  if (!problem->hasContact()) {
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
    FetiContactProblem cp(dual, friction);
    r.outerAlgorithm = outerAlgorithmFor(p.get<std::string>("Outer Algorithm"), friction);
    const std::string runLawName = frictionLawName(runLaw(friction));
    TRIBOS_REQUIRE(Friction::frictionSolvers().accepts(r.outerAlgorithm, runLawName),
                   "Outer Algorithm = " << r.outerAlgorithm << " does not solve " << runLawName << " friction ("
                                        << joinNames(Friction::frictionSolvers().accepting(runLawName)) << " do)");
    // Rounds: a solve that meets its own test with a result that misses the
    // check is asked again from its result, the tolerance tightened by the
    // miss (Friction::tightenedTolerance); the check keeps the first
    // tolerance, so converged still means factor x what was asked for.
    const int rounds = p.get<int>("Result Check Rounds");
    double requested = 0;
    RCP<const Vector> start;
    for (int round = 1; round <= rounds; ++round) {
      Progress::stage("contact solve: " + r.outerAlgorithm + (round > 1 ? ", round " + std::to_string(round) : ""));
      const auto sol = cp.solve(r.outerAlgorithm, p, out, start.get(), requested);
      if (round == 1) r.tolerance = sol.requestedTolerance;
      requested = sol.requestedTolerance;
      r.status = round == 1 ? sol.status : Friction::followedBy(r.status, sol.status);
      r.iterations = r.status.outer_iterations;
      r.n_A += sol.n_A;
      r.solverConverged = sol.status.converged;
      r.solverReason = sol.status.reason;
      r.lambda->assign(*sol.lambda);
      r.primal = sol.u;
      r.rounds = round;
      checkResult(*problem, friction, p, r);
      if (!r.solverConverged || r.verdict.converged || round == rounds || Friction::atTightestTolerance(requested))
        break;
      requested = Friction::tightenedTolerance(requested, r.verdict.limit, r.kkt.worst());
      start = sol.x;
    }
  }
  r.solveSeconds = secondsSince(t0);
  r.F_applications = dual->F()->applications();
  r.F_seconds = dual->F()->seconds();
  r.coarseSize = dual->coarse().size();
  r.coarseFactorMb = dual->coarse().factorMemoryMb();
  if (!problem->hasContact()) checkResult(*problem, law, p, r);
  return r;
}

}  // namespace Contact
}  // namespace Tribos
