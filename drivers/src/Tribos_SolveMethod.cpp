#include "Tribos_SolveMethod.hpp"

#include <chrono>
#include <iostream>
#include <algorithm>
#include <map>
#include <memory>
#include <optional>

#include "Tribos_Assembly.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FCLIB_Export.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_SemismoothSolve.hpp"

namespace Tribos {

namespace {

using Teuchos::ParameterList;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The history row of a solver that reports its final state only (projected
// CG and the monolithic CG keep no residual per iteration): the iterations,
// the final relative residual and the work of the whole solve.
IO::HistoryRow finalRow(long long iterations, double relativeResidual, long long n_A, double seconds) {
  IO::HistoryRow row;
  row.iteration = iterations;
  row.relativeResidual = relativeResidual;
  row.n_A = static_cast<double>(n_A);
  row.seconds = seconds;
  return row;
}

// The reaction of the supports (Contact::supportReactions) from K and f
// assembled anew on this rank's subdomains: for the methods whose own
// matrices do not hold the supports (the monolithic system, FETI-1's
// subdomains with their Dirichlet dofs eliminated, the semismooth* method's
// reduced system). r.u's layout holds the nodes of the rank's part.
// Collective.
Fem::NodalVector reactionOfAssembly(const Discretized& d, const Fem::LoadCase& loads, const Contact::SolveResult& r) {
  std::vector<Fem::SubdomainSystem> systems;
  for (int s = d.disc.firstLocalSubdomain(); s < d.disc.endLocalSubdomain(); ++s)
    systems.push_back(Fem::assembleSubdomain(d.disc, s, d.materials, loads));
  return Contact::supportReactions(Fem::assembledProduct(systems, r.u), Fem::assembledLoad(systems, r.u.layoutPtr()),
                                   r.contact, Fem::constrainedDofs(d.disc, loads.dirichlet));
}

// The members every method keeps: what its maker was given.
class MethodBase : public SolveMethod {
 public:
  MethodBase(const ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm)
      : params_(params), options_(options), comm_(comm) {}

 protected:
  double resultCheckFactor() const { return params_.sublist("Solver").get<double>("Result Check Factor"); }
  const ParameterList& params_;
  const RunOptions& options_;
  RCP<const Comm> comm_;
};

// The assembled problem by CG + MueLu; the residuals of the result from K
// and f assembled anew per subdomain, as for FETI.
class MonolithicMethod : public MethodBase {
 public:
  using MethodBase::MethodBase;
  StepSolution solve(const Discretized& d, const Fem::LoadCase& loads, RunReport& report) override {
    // (The whole mesh was checked to hold every rigid motion before any work.)
    // A linear problem has no history: each load step is solved afresh.
    const auto dirichlet = Fem::constrainedDofs(d.disc, loads.dirichlet);
    Progress::stage("assembly");
    const auto t0 = std::chrono::steady_clock::now();
    Fem::MonolithicSystem system(d.disc, d.materials, loads, comm_);
    StepSolution sol;
    sol.setupSeconds = seconds(t0);
    Progress::stage("monolithic solve");
    const auto t1 = std::chrono::steady_clock::now();
    const auto& list = params_.sublist("Solver").sublist("Monolithic");
    const auto res = system.solve(list);
    auto& r = sol.result;
    r.solveSeconds = seconds(t1);
    r.u = res.u;
    r.solverConverged = res.converged;
    if (!res.converged) r.solverReason = "monolithic CG: maximum iterations";
    r.iterations = res.iterations;
    r.tolerance = list.get<double>("Tolerance");
    report.primalDofs = static_cast<long long>(system.matrix()->getGlobalNumRows());
    report.dualDofs = 0;
    report.outerIterations = res.iterations;
    report.n_A = res.iterations;
    report.relativeResidual = res.relativeResidual;
    sol.history.rows.push_back(finalRow(res.iterations, res.relativeResidual, res.iterations, r.solveSeconds));
    Progress::stage("result check");
    // The rank keeps the nodes of its part (the writer's cells).
    std::vector<Fem::SubdomainSystem> systems;
    for (int s = d.disc.firstLocalSubdomain(); s < d.disc.endLocalSubdomain(); ++s)
      systems.push_back(Fem::assembleSubdomain(d.disc, s, d.materials, loads));
    const Fem::NodalVector Ku = Fem::assembledProduct(systems, r.u), f = Fem::assembledLoad(systems, r.u.layoutPtr());
    r.kkt = Contact::resultKKT(r.u, Ku, f, dirichlet, FrictionLaw::Frictionless, {});
    r.reaction = Contact::supportReactions(Ku, f, r.contact, dirichlet);
    r.verdict = Contact::resultVerdict(r.kkt, r.solverConverged, r.solverReason, r.tolerance, resultCheckFactor());
    return sol;
  }
};

// Values given at the owned nodes of disc (3 per node of ownedNodes(), in
// its order), at the nodes the problem holds results at (those of its
// subdomains and the partners of its contact nodes), asked of their owners.
// Collective.
Fem::NodalVector nodalOnProblem(const Feti::FetiProblem& problem, const Mesh::Discretization& disc,
                                const std::vector<double>& owned, const Comm& comm) {
  std::map<int, const double*> byNode;  // part node -> its 3 values
  for (size_t i = 0; i < disc.ownedNodes().size(); ++i) byNode[disc.ownedNodes()[i]] = &owned[3 * i];
  const auto& layout = problem.nodalLayout();
  const auto values = disc.askOwners(layout->nodes(), 3,
                                     [&](int partNode, double* out) {
                                       const double* x = byNode.at(partNode);
                                       std::copy(x, x + 3, out);
                                     },
                                     comm);
  Fem::NodalVector x(layout);
  x.values() = values;  // askOwners answers in the order asked: layout->nodes()
  return x;
}

// The friction of each contact pair (none without contact).
Contact::PairFriction runFriction(const ParameterList& params) {
  return params.sublist("Contact").get<bool>("Enabled") ? Input::pairFriction(params) : Contact::PairFriction{{}};
}

// The FETI problem's sizes and its solve's figures.
void reportFeti(const Feti::FetiProblem& problem, const Contact::FetiSolveResult& r, RunReport& report,
                const Comm& comm) {
  report.primalDofs = static_cast<long long>(problem.primalMap()->getGlobalNumElements());
  report.dualDofs = static_cast<long long>(problem.dualMap()->getGlobalNumElements());
  FetiReport feti;
  feti.localSolver = problem.localSolverName();
  feti.factorSeconds = maxOver(problem.factorTime(), comm);
  feti.factorMemoryMb = maxOver(problem.factorMemoryMb(), comm);
  feti.denseBlockMemoryMb = maxOver(problem.denseBlockMemoryMb(), comm);
  feti.F_applications = r.F_applications;
  feti.F_seconds = maxOver(r.F_seconds, comm);
  feti.coarseSize = r.coarseSize;
  feti.coarseFactorMb = r.coarseFactorMb;
  report.feti = feti;
}

// The outer algorithm's report and one history row per outer step.
void reportContact(const Contact::FetiSolveResult& r, const Contact::PairFriction& friction, RunReport& report,
                   IO::IterationHistory& history) {
  const auto& st = r.status;
  OuterAlgorithmReport outer;
  outer.name = r.outerAlgorithm;
  outer.handover = r.handover;
  outer.preconditioner = r.outerAlgorithm == "Semismooth Newton" ? st.preconditioner : "";
  outer.resultCheckRounds = r.rounds;
  outer.msaIterations = st.msa_iterations;
  outer.innerIterations = st.inner_iterations;
  outer.n_A_qpp = static_cast<long long>(st.n_A_qpp);
  outer.n_A_qpq = static_cast<long long>(st.n_A_qpq);
  outer.slipBoundChange = st.slip_bound_change;
  outer.history = st.history;
  report.outer = outer;
  report.frictionLaw = frictionLawName(Contact::runLaw(friction));
  report.outerIterations = st.outer_iterations;
  for (const auto& step : st.steps) {
    IO::HistoryRow row;
    row.iteration = step.iteration;
    row.relativeResidual = step.projectedGradient;
    row.gLambda = step.normGx;
    row.slipBoundChange = step.slipBoundChange;
    row.n_A = static_cast<double>(step.n_A);
    row.seconds = step.seconds;
    history.rows.push_back(row);
  }
  report.contact = ContactCountReport{r.counts.nodes, r.counts.active, r.counts.stick, r.counts.slip};
}

// Total FETI, the solve an application runs on its own subdomains
// (Contact::solveFeti), with the FCLIB export of a contact problem.
class FetiMethod : public MethodBase {
 public:
  using MethodBase::MethodBase;
  StepSolution solve(const Discretized& d, const Fem::LoadCase& loads, RunReport& report) override {
    const auto& solverParams = params_.sublist("Solver");
    const bool contact = params_.sublist("Contact").get<bool>("Enabled");
    const Contact::PairFriction friction = runFriction(params_);
    const auto out = options_.verbose ? Teuchos::fancyOStream(Teuchos::rcpFromRef(std::cout))
                                      : RCP<Teuchos::FancyOStream>();
    // The solvers' progress lines are collective figures: once, from rank 0.
    if (!out.is_null()) {
      out->setProcRankAndSize(comm_->getRank(), comm_->getSize());
      out->setOutputToRootOnly(0);
    }
    StepSolution sol;
    // The first step sets the problem up; a history keeps it for the next.
    if (problem_.is_null()) {
      Progress::stage("FETI setup: assembly, gluing, coarse space");
      const auto t0 = std::chrono::steady_clock::now();
      problem_ = rcp(new Feti::FetiProblem(d.disc, d.materials, loads, d.constraints, solverParams.sublist("FETI"), comm_));
      if (Input::loadStepTimes(params_).size() > 1)
        steps_ = std::make_unique<Contact::FetiLoadSteps>(problem_, friction, solverParams, out);
      if (resumeFrom_) steps_->resumeFrom(nodalOnProblem(*problem_, d.disc, *resumeFrom_, *comm_));
      resumeFrom_.reset();
      sol.setupSeconds = seconds(t0);
    }
    const auto r = steps_ ? steps_->solve(loads) : Contact::solveFeti(problem_, friction, solverParams, out);
    sol.result = r;
    // TFETI's subdomain matrices are the bodies' K; FETI-1 replaced the
    // Dirichlet rows in them (a single step: assembled once more).
    sol.result.reaction =
        solverParams.sublist("FETI").get<std::string>("Formulation") == "FETI-1"
            ? reactionOfAssembly(d, loads, sol.result)
            : Contact::supportReactions(problem_->assembledProduct(r.u), problem_->assembledLoad(), r.contact,
                                        problem_->dirichlet());
    const auto& problem = problem_;
    report.n_A = r.n_A;
    if (!problem->hasContact()) {
      report.outerIterations = r.iterations;
      report.relativeResidual = r.relativeResidual;
      sol.history.rows.push_back(finalRow(r.iterations, r.relativeResidual, r.n_A, r.solveSeconds));
    } else {
      reportContact(r, friction, report, sol.history);
      if (!options_.exportFclib.empty()) exportFclib(*problem, d, loads, friction, r, report);
    }
    reportFeti(*problem, r, report, *comm_);
    return sol;
  }

  void resumeFrom(ResumedStep step) override {
    TRIBOS_REQUIRE(problem_.is_null(), "FetiMethod::resumeFrom: called after the first step");
    TRIBOS_REQUIRE(Input::loadStepTimes(params_).size() > 1, "FetiMethod::resumeFrom: the run has one load step");
    resumeFrom_ = std::move(step.uOwned);
  }

 private:
  RCP<Feti::FetiProblem> problem_;
  std::unique_ptr<Contact::FetiLoadSteps> steps_;  // a run of several load steps
  std::optional<std::vector<double>> resumeFrom_;  // until the first step: the displacement a restart continues from

  // FCLIB global problem: assembled K, contact rows in the local frame,
  // gaps, F (docs/fclib.md); the whole mesh is on rank 0.
  void exportFclib(const Feti::FetiProblem& problem, const Discretized& d, const Fem::LoadCase& loads,
                   const Contact::PairFriction& friction, const Contact::FetiSolveResult& r, RunReport& report) const {
    Progress::stage("FCLIB export");
    FCLIB::Info info{params_.get<std::string>("Problem Name"), "Tribos FETI contact problem, " + r.outerAlgorithm, ""};
    FCLIB::exportFeti(options_.exportFclib, problem, *d.whole, d.materials, loads, Contact::runLaw(friction),
                      friction[0].coefficient, *r.primal, *r.lambda, info);
    report.fclibExport = options_.exportFclib;
  }
};

// The semismooth* method on the whole mesh, which every rank holds.
class SemismoothMethod : public MethodBase {
 public:
  using MethodBase::MethodBase;
  StepSolution solve(const Discretized& d, const Fem::LoadCase& loads, RunReport& report) override {
    Progress::stage("semismooth* Newton");
    const auto plane = Input::planeContact(params_);  // Tresca or frictionless (the input refuses Coulomb here)
    const auto r = Semismooth::solvePlaneContact(
        *d.whole, Input::material(params_), loads, plane, params_.sublist("Solver").sublist("SemismoothStarNewton"),
        resultCheckFactor(), comm_, options_.verbose ? &std::cout : nullptr);
    StepSolution sol;
    sol.result = r;
    // Each contact node's area, the share of the contact face that the slip
    // bounds use (int N_s dA), for its tractions.
    const auto area = Fem::faceNodalAreas(*d.whole, plane.face);
    for (auto& c : sol.result.contact.constraint) c.area = area.at(c.node);
    sol.result.reaction = reactionOfAssembly(d, loads, sol.result);
    SemismoothReport newton;
    newton.newtonIterations = r.iterations;
    newton.residuals = r.residuals;
    newton.assemblySeconds = r.assemblySeconds;
    newton.reductionSeconds = r.reductionSeconds;
    newton.newtonSeconds = r.newtonSeconds;
    newton.cgIterations = r.cgIterations;
    newton.preconditionerSeconds = r.preconditionerSeconds;
    report.semismooth = newton;
    report.frictionLaw = frictionLawName(plane.law);
    report.outerIterations = r.iterations;
    report.primalDofs = 3LL * d.whole->numNodes();
    report.dualDofs = 0;
    report.n_A = 0;
    report.contact = ContactCountReport{r.counts.nodes, r.counts.active, r.counts.stick, r.counts.slip};
    // One row per residual, the last one after the last Newton step (the list
    // may start with the residual of the initial approximation, step 0); the
    // method times its whole solve only (the last row gets it) and makes no
    // Hessian multiplications of a dual.
    for (size_t k = 0; k < r.residuals.size(); ++k) {
      IO::HistoryRow row;
      row.iteration = static_cast<long long>(r.iterations) - static_cast<long long>(r.residuals.size() - 1 - k);
      row.relativeResidual = r.residuals[k];
      row.n_A = 0;
      sol.history.rows.push_back(row);
    }
    if (!sol.history.rows.empty()) sol.history.rows.back().seconds = r.solveSeconds;
    return sol;
  }
};

template <class Method>
SolveMethodRegistry::Maker maker() {
  return [](const ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm) -> RCP<SolveMethod> {
    return rcp(new Method(params, options, comm));
  };
}

// Implicit dynamics (Dynamics/Enabled): each solve is the next time step of
// Contact::ImplicitDynamics, made at the first with the loads at t = 0;
// `loads` are those at the step's end (the curves at t, a load without one
// at its full Value).
class FetiDynamicsMethod : public MethodBase {
 public:
  using MethodBase::MethodBase;
  StepSolution solve(const Discretized& d, const Fem::LoadCase& loads, RunReport& report) override {
    const auto& solverParams = params_.sublist("Solver");
    const bool contact = params_.sublist("Contact").get<bool>("Enabled");
    const Contact::PairFriction friction = runFriction(params_);
    StepSolution sol;
    if (!run_) {
      Progress::stage("FETI setup: assembly of K + 4 M / dt^2, gluing");
      const auto t0 = std::chrono::steady_clock::now();
      const Fem::LoadHistory history = Input::loadHistory(params_);
      run_ = std::make_unique<Contact::ImplicitDynamics>(
          d.disc, d.materials, Input::densities(params_, d.disc.part), Fem::loadCaseAt(history, 0.0), d.constraints,
          friction, Input::dynamicsSpec(params_, d.disc.part), solverParams.sublist("FETI"), solverParams, comm_);
      if (resumeFrom_) {
        const auto& problem = run_->problem();
        const ResumedStep& at = *resumeFrom_;
        run_->resumeFrom({at.time, nodalOnProblem(problem, d.disc, at.uOwned, *comm_),
                          nodalOnProblem(problem, d.disc, at.vOwned, *comm_), at.externalWork, at.frictionDissipation},
                         Fem::loadCaseAt(history, at.time));
        resumeFrom_.reset();
      }
      sol.setupSeconds = seconds(t0);
    }
    Progress::stage("time step");
    Contact::DynamicStep step = run_->step(loads);
    const auto& r = step.solve;
    sol.result = r;
    sol.velocity = run_->velocity();
    sol.dynamics = DynamicsStepReport{step.kineticEnergy, step.strainEnergy, step.externalWork,
                                      step.frictionDissipation, step.contactForce};
    report.n_A = r.n_A;
    if (contact) {
      reportContact(r, friction, report, sol.history);
    } else {
      report.outerIterations = r.iterations;
      report.relativeResidual = r.relativeResidual;
      sol.history.rows.push_back(finalRow(r.iterations, r.relativeResidual, r.n_A, r.solveSeconds));
    }
    reportFeti(run_->problem(), r, report, *comm_);
    return sol;
  }

  // The state of the step continued from: its displacement and velocity,
  // time and running sums (ImplicitDynamics::resumeFrom; the
  // contact-stabilized scheme, as checkRunnable requires of a restart).
  void resumeFrom(ResumedStep step) override {
    TRIBOS_REQUIRE(!run_, "FetiDynamicsMethod::resumeFrom: called after the first step");
    TRIBOS_REQUIRE(step.vOwned.size() == step.uOwned.size(), "FetiDynamicsMethod::resumeFrom: no velocity of the step");
    resumeFrom_ = std::move(step);
  }

 private:
  std::unique_ptr<Contact::ImplicitDynamics> run_;
  std::optional<ResumedStep> resumeFrom_;  // until the first step: the step a restart continues from
};

}  // namespace

const SolveMethodRegistry& solveMethods() {
  static const SolveMethodRegistry registry = [] {
    SolveMethodRegistry r("solution method");
    r.add("Monolithic", maker<MonolithicMethod>(), "the assembled problem by CG + MueLu (no contact)");
    r.add("FETI", maker<FetiMethod>(), "Total FETI: projected CG, or the outer contact algorithm");
    r.add("SemismoothStarNewton", maker<SemismoothMethod>(),
          "one face on a rigid plane, Tresca or frictionless, by the semismooth* Newton method");
    r.add("FETI Dynamics", maker<FetiDynamicsMethod>(), "implicit time steps of K + 4 M / dt^2 through FETI");
    return r;
  }();
  return registry;
}

const char* solveMethodName(Input::Method method) {
  switch (method) {
    case Input::Method::Monolithic: return "Monolithic";
    case Input::Method::Semismooth: return "SemismoothStarNewton";
    case Input::Method::FetiDynamics: return "FETI Dynamics";
    case Input::Method::FetiLinear:
    case Input::Method::FetiContact: break;
  }
  return "FETI";
}

}  // namespace Tribos
