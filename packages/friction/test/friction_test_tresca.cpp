// friction_test_tresca.cpp: Algorithm 1 (SMALBE, or the inner solver alone
// without G) and its block Gauss-Seidel inner minimization on problems with
// Tresca friction whose solution is enumerated or manufactured.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include "FrictionTestChecks.hpp"
#include "Tribos_BlockGaussSeidel.hpp"
#include "Tribos_QP_Factory.hpp"

namespace {

using namespace frictest;
using Tribos::Vector;

// Three contacts, one in each state of a Tresca contact.
const std::vector<ContactState> stickSlipSeparated{{true, true, 0.7}, {true, false, 2.5}, {false, false, -1.0}};

TEUCHOS_UNIT_TEST(Algorithm1, IntervalsMatchEnumeratedStates) {
  ManufacturedOptions opt;
  opt.tangent = Tangent::Interval;
  opt.lower = 0.1;  // a zero start is infeasible and must be projected
  auto problem = manufacture({{true, true, 0.0}, {true, false, 3.0}, {false, true, 0.0}}, opt).problem;
  // Forget the manufactured x: the reference is what enumeration finds.
  const auto solutions = enumerateSolutions(problem);
  TEST_EQUALITY(solutions.size(), 1u);
  if (solutions.size() != 1) return;
  const Run run = solveWith("Tresca", problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  checkSolution(problem, run.x, solutions[0], {}, problem.slipBound, checkTolerance, out, success);
}

TEUCHOS_UNIT_TEST(Algorithm1, DisksManufacturedStickSlipSeparated) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  const Run run = solveWith("Tresca", m.problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  TEST_COMPARE(run.status.n_A_qpp, >, 0);
  TEST_COMPARE(run.status.n_A_qpq, >, 0);
  checkSolution(m.problem, run.x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

TEUCHOS_UNIT_TEST(Algorithm1, JointMPGPInnerMinimization) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  auto params = solverParameters(solveTolerance);
  params.sublist("Algorithm 1").set("Inner Minimization", "MPGP");
  const Run run = solveWith("Tresca", m.problem, params);
  TEST_ASSERT(run.status.converged);
  TEST_EQUALITY(run.status.n_A_qpp, 0);  // no bound-only solver in the joint minimization
  checkSolution(m.problem, run.x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

TEUCHOS_UNIT_TEST(Algorithm1, SmalbeEqualityConstraint) {
  ManufacturedOptions opt;
  opt.equalityRows = 2;
  opt.seed = 5;
  const auto m = manufacture(stickSlipSeparated, opt);
  const Run run = solveWith("Tresca", m.problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  TEST_COMPARE(run.status.outer_iterations, >=, 1);
  checkSolution(m.problem, run.x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

// A solve resumed from another's result and final state (a further
// result-check round, a load step): the multiplier of G x = 0 comes with
// it, so asking for more digits costs fewer applications than resuming
// from the result alone, where SMALBE rebuilds the multiplier from zero.
TEUCHOS_UNIT_TEST(Algorithm1, ResumesTheEqualityMultiplier) {
  ManufacturedOptions opt;
  opt.equalityRows = 2;
  opt.seed = 5;
  const auto m = manufacture(stickSlipSeparated, opt);
  const auto d = buildDual(m.problem, Tpetra::getDefaultComm());
  auto solver = [&](double tol) { return Tribos::Friction::FrictionSolverFactory().create("Tresca", solverParameters(tol)); };
  auto first = solver(1e-4);
  Vector x1(d.map);
  TEST_ASSERT(first->solve(d.dual, x1).converged);
  const Tribos::Friction::WarmStart state = first->finalState();
  TEST_ASSERT(!state.equalityMultiplier.is_null());
  // The next round, from x1 with the state and from x1 alone.
  Vector withState(x1, Teuchos::Copy), alone(x1, Teuchos::Copy);
  auto resumed = solver(solveTolerance);
  resumed->setWarmStart(state);
  const auto sResumed = resumed->solve(d.dual, withState);
  const auto sAlone = solver(solveTolerance)->solve(d.dual, alone);
  TEST_ASSERT(sResumed.converged && sAlone.converged);
  out << "n_A resumed with the multiplier " << sResumed.n_A << ", from x alone " << sAlone.n_A << "\n";
  TEST_COMPARE(sResumed.n_A, <, sAlone.n_A);
  checkSolution(m.problem, gather(withState), m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

// ---------------------------------------------------------------- block Gauss-Seidel

double energy(const Problem& p, const Vec& x) {
  const Vec Ax = multiply(p.A, x);
  double f = 0;
  for (int i = 0; i < p.size(); ++i) f += 0.5 * x[i] * Ax[i] - p.b[i] * x[i];
  return f;
}

struct GaussSeidelRun {
  Tribos::QP::QPStatus status;
  long n_A_qpp = 0, n_A_qpq = 0;
  std::vector<Vec> iterates;  // x after every call
};

// `calls` solves of `sweeps` sweeps each, from x = 0 (projected).
GaussSeidelRun gaussSeidel(const Problem& p, int sweeps, int calls) {
  const auto d = buildDual(p, Tpetra::getDefaultComm());
  Tribos::QP::QPSolverFactory factory;
  Tribos::Friction::BlockGaussSeidel bgs(factory.create("MPRGP", Teuchos::null), factory.create("MPGP", Teuchos::null),
                                         sweeps, d.dual.normalBlockMask(), d.dual.tangentBlockMask());
  bgs.setHessianNorm(1.0);  // spdMatrix scales ||A|| <= 1
  bgs.setTolerance(solveTolerance * norm(p.b));
  const auto Omega = d.dual.constraintSet(d.dual.slipBound);
  Vector x(d.map);
  GaussSeidelRun run;
  for (int c = 0; c < calls; ++c) {
    const auto s = bgs.solve(*d.dual.A, *d.dual.b, Omega, x);
    run.status.n_A += s.n_A;
    run.status.converged = s.converged;
    run.status.reason = s.reason;
    run.iterates.push_back(gather(x));
  }
  run.n_A_qpp = bgs.n_A_qpp();
  run.n_A_qpq = bgs.n_A_qpq();
  return run;
}

TEUCHOS_UNIT_TEST(BlockGaussSeidel, DecoupledBlocksSolvedInOneSweep) {
  // Without normal-tangential coupling the two block minimizations are
  // independent: one sweep is the exact minimizer. With coupling it is not.
  ManufacturedOptions opt;
  opt.decoupled = true;
  const auto decoupled = manufacture(stickSlipSeparated, opt);
  const auto one = gaussSeidel(decoupled.problem, 1, 1);
  checkSolution(decoupled.problem, one.iterates.back(), decoupled.x, decoupled.mu, decoupled.problem.slipBound,
                checkTolerance, out, success);
  const auto coupled = manufacture(stickSlipSeparated, ManufacturedOptions());
  const auto oneCoupled = gaussSeidel(coupled.problem, 1, 1);
  const double error = maxAbsDiff(oneCoupled.iterates.back(), coupled.x);
  TEST_COMPARE(error, >, 1e-6);
}

TEUCHOS_UNIT_TEST(BlockGaussSeidel, CoupledBlocksReachTrescaSolution) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  const auto run = gaussSeidel(m.problem, 500, 1);
  TEST_ASSERT(run.status.converged);
  TEST_EQUALITY(run.status.n_A, run.n_A_qpp + run.n_A_qpq);
  TEST_COMPARE(run.n_A_qpp, >, 0);
  TEST_COMPARE(run.n_A_qpq, >, 0);
  checkSolution(m.problem, run.iterates.back(), m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

TEUCHOS_UNIT_TEST(BlockGaussSeidel, SweepsNeverIncreaseEnergy) {
  // Each block step minimizes f over its block from a feasible point, so f
  // cannot grow from sweep to sweep (up to round-off).
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  const auto run = gaussSeidel(m.problem, 1, 8);
  for (size_t i = 1; i < run.iterates.size(); ++i) {
    const double before = energy(m.problem, run.iterates[i - 1]), after = energy(m.problem, run.iterates[i]);
    TEST_COMPARE(after, <=, before + 1e-14 * std::abs(before));
  }
  TEST_COMPARE(energy(m.problem, run.iterates.back()), >=, energy(m.problem, m.x) - 1e-14);
}

}  // namespace
