// friction_test_coulomb.cpp: Coulomb friction by successive approximations
// (MSA + Algorithm 1) and by the fused Algorithm 2, on problems with an
// enumerated or manufactured solution; every solution must be Coulomb's fixed
// point g = F lambda_N.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include "FrictionTestChecks.hpp"

namespace {

using namespace frictest;

// In contact and slipping, in contact and sticking, separated (g = 0).
const std::vector<ContactState> stickSlipSeparated{{true, true, 0.7}, {true, false, 2.5}, {false, false, -1.0}};

ManufacturedOptions coulomb() {
  ManufacturedOptions opt;
  opt.law = Law::Coulomb;
  opt.friction = 0.3;
  return opt;
}

void intervalsMatchEnumeration(const std::string& algorithm, Teuchos::FancyOStream& out, bool& success) {
  ManufacturedOptions opt = coulomb();
  opt.tangent = Tangent::Interval;
  const auto problem = manufacture({{true, true, 0.0}, {true, false, 3.0}, {false, true, 0.0}}, opt).problem;
  const auto solutions = enumerateSolutions(problem);
  TEST_EQUALITY(solutions.size(), 1u);  // F small: the fixed point is unique
  if (solutions.size() != 1) return;
  const Run run = solveWith(algorithm, problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  checkSolution(problem, run.x, solutions[0], {}, slipBoundAt(problem, solutions[0]), checkTolerance, out, success);
  checkCoulombFixedPoint(problem, run, {}, checkTolerance, out, success);
}

void disksManufactured(const std::string& algorithm, const ManufacturedOptions& opt, Teuchos::FancyOStream& out,
                       bool& success) {
  const auto m = manufacture(stickSlipSeparated, opt);
  const Run run = solveWith(algorithm, m.problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  checkSolution(m.problem, run.x, m.x, m.mu, slipBoundAt(m.problem, m.x), checkTolerance, out, success);
  checkCoulombFixedPoint(m.problem, run, m.mu, checkTolerance, out, success);
}

// The shift of a particular solution lambda~ of G lambda = e: bounds
// x_N >= -lambda~_N and normal force x_N + lambda~_N.
ManufacturedOptions shiftedWithEquality() {
  ManufacturedOptions opt = coulomb();
  opt.equalityRows = 2;
  opt.lower = -0.2;
  opt.offset = 0.2;
  opt.seed = 11;
  return opt;
}

TEUCHOS_UNIT_TEST(MSA, IntervalsMatchEnumeratedStates) { intervalsMatchEnumeration("MSA+Algorithm1", out, success); }

TEUCHOS_UNIT_TEST(MSA, DisksManufacturedFixedPoint) {
  disksManufactured("MSA+Algorithm1", coulomb(), out, success);
}

TEUCHOS_UNIT_TEST(MSA, EqualityConstraintShiftedBounds) {
  disksManufactured("MSA+Algorithm1", shiftedWithEquality(), out, success);
}

TEUCHOS_UNIT_TEST(MSA, CountsSuccessiveApproximations) {
  // g(0) = 0 is not the fixed point, so at least two Tresca solves; every
  // one converged, and the history holds one change of g per step.
  const auto m = manufacture(stickSlipSeparated, coulomb());
  const Run run = solveWith("MSA+Algorithm1", m.problem, solverParameters(solveTolerance));
  TEST_ASSERT(run.status.converged);
  TEST_COMPARE(run.status.msa_iterations, >=, 2);
  TEST_EQUALITY(static_cast<int>(run.status.history.size()), run.status.msa_iterations);
  TEST_COMPARE(run.status.slip_bound_change, <=, solveTolerance);
}

TEUCHOS_UNIT_TEST(Algorithm2, IntervalsMatchEnumeratedStates) { intervalsMatchEnumeration("Algorithm2", out, success); }

TEUCHOS_UNIT_TEST(Algorithm2, DisksManufacturedFixedPoint) { disksManufactured("Algorithm2", coulomb(), out, success); }

TEUCHOS_UNIT_TEST(Algorithm2, EqualityConstraintShiftedBounds) {
  disksManufactured("Algorithm2", shiftedWithEquality(), out, success);
}

// Semismooth Newton: the same manufactured and enumerated Coulomb solutions,
// node by node (checkSolution: the solution, the natural residual of every
// contact, feasibility), and Coulomb's fixed point, on every number of ranks
// and with G x = 0 (its multiplier alpha joins the Newton unknowns).
TEUCHOS_UNIT_TEST(SemismoothNewton, IntervalsMatchEnumeratedStates) {
  intervalsMatchEnumeration("Semismooth Newton", out, success);
}

TEUCHOS_UNIT_TEST(SemismoothNewton, DisksManufacturedFixedPoint) {
  disksManufactured("Semismooth Newton", coulomb(), out, success);
}

TEUCHOS_UNIT_TEST(SemismoothNewton, ShiftedBoundsWithoutEquality) {
  ManufacturedOptions opt = coulomb();
  opt.lower = -0.2;
  opt.offset = 0.2;
  opt.seed = 5;
  disksManufactured("Semismooth Newton", opt, out, success);
}

TEUCHOS_UNIT_TEST(SemismoothNewton, EqualityConstraintShiftedBounds) {
  disksManufactured("Semismooth Newton", shiftedWithEquality(), out, success);
}

TEUCHOS_UNIT_TEST(SemismoothNewton, SuperlinearOnManufactured) {
  // The stopping measure after each step: once the contact states are
  // settled the ratio of successive residuals falls (superlinear), ending
  // far below the linear rate of a first-order method; with and without G.
  for (int rows : {0, 2}) {
    ManufacturedOptions opt = coulomb();
    opt.equalityRows = rows;
    const auto m = manufacture(stickSlipSeparated, opt);
    const Run run = solveWith("Semismooth Newton", m.problem, solverParameters(1e-14));
    TEST_ASSERT(run.status.converged);
    const auto& h = run.status.history;
    TEST_COMPARE(h.size(), >=, 3u);
    if (h.size() < 3) continue;
    const size_t k = h.size() - 1;
    if (h[k] == 0.0) continue;  // exact in the last step: nothing finer to measure
    const double last = h[k] / h[k - 1], before = h[k - 1] / h[k - 2];
    out << "G rows " << rows << ", residuals:";
    for (double r : h) out << " " << r;
    out << "\n";
    TEST_COMPARE(last, <, before);
    TEST_COMPARE(last, <, 1e-2);
  }
}

TEUCHOS_UNIT_TEST(SemismoothNewton, RefusesAboveDenseLimit) {
  const auto m = manufacture(stickSlipSeparated, coulomb());
  auto params = solverParameters(solveTolerance);
  params.sublist("Semismooth Newton").set("Dense Limit", m.problem.size() - 1);
  params.sublist("Semismooth Newton").set("Linear Solver", "Dense LU");  // Auto would go matrix-free
  try {
    solveWith("Semismooth Newton", m.problem, params);
    TEST_ASSERT(false);
  } catch (const std::exception& e) {
    out << e.what() << "\n";
    TEST_ASSERT(std::string(e.what()).find("Dense Limit") != std::string::npos);
  }
}

}  // namespace
