// friction_test_problems.cpp: the references and checks of the other tests
// are themselves right: a manufactured solution is a KKT point and nothing
// near it is, enumeration finds the manufactured solution, and the Coulomb
// fixed-point check tells a wrong friction coefficient.
#include <Teuchos_UnitTestHarness.hpp>

#include "FrictionTestChecks.hpp"

namespace {

using namespace frictest;

const std::vector<ContactState> stickSlipSeparated{{true, true, 0.7}, {true, false, 2.5}, {false, false, -1.0}};

TEUCHOS_UNIT_TEST(TestProblems, ManufacturedIsKKTPointAndNeighboursAreNot) {
  ManufacturedOptions opt;
  opt.equalityRows = 1;
  const auto m = manufacture(stickSlipSeparated, opt);
  const Vec& g = m.problem.slipBound;
  TEST_COMPARE(naturalResidual(m.problem, m.x, m.mu, g), <=, 1e-14);
  TEST_COMPARE(feasibilityViolation(m.problem, m.x, g), <=, 1e-14);
  for (int i = 0; i < m.problem.size(); ++i) {
    Vec x = m.x;
    x[i] += 1e-4;
    const double moved = std::max(naturalResidual(m.problem, x, m.mu, g), feasibilityViolation(m.problem, x, g));
    TEST_COMPARE(moved, >, 1e-6);
  }
}

TEUCHOS_UNIT_TEST(TestProblems, EnumerationFindsManufacturedSolution) {
  for (Law law : {Law::Tresca, Law::Coulomb}) {
    ManufacturedOptions opt;
    opt.tangent = Tangent::Interval;
    opt.law = law;
    const auto m = manufacture({{true, true, 0.0}, {true, false, 3.0}, {false, true, 3.0}}, opt);
    const auto solutions = enumerateSolutions(m.problem);
    TEST_EQUALITY(solutions.size(), 1u);
    if (solutions.size() == 1) TEST_COMPARE(maxAbsDiff(solutions[0], m.x), <=, 1e-12);
  }
}

TEUCHOS_UNIT_TEST(TestProblems, FixedPointCheckDetectsWrongFriction) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions{Tangent::Disk, Law::Coulomb});
  Problem other = m.problem;
  for (double& F : other.friction) F *= 1.01;
  TEST_COMPARE(naturalResidual(m.problem, m.x, m.mu, slipBoundAt(m.problem, m.x)), <=, 1e-14);
  TEST_COMPARE(naturalResidual(other, m.x, m.mu, slipBoundAt(other, m.x)), >, 1e-6);
}

}  // namespace
