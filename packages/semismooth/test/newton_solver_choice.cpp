// newton_solver_choice.cpp: "Newton Solver" = "Auto", the default of the
// semismooth* method: a factorization up to kAutoSparseDirectMaxDofs primal
// dofs, with "Dense Schur" and without node coordinates; CG+MueLu beyond.
// A name given explicitly is kept (aliases made canonical).
#include <Teuchos_UnitTestHarness.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace {

using namespace Tribos::Semismooth;

Teuchos::ParameterList validated(Teuchos::ParameterList p = Teuchos::ParameterList()) {
  p.validateParametersAndSetDefaults(*SemismoothStarNewton::getValidParameters());
  return p;
}

TEUCHOS_UNIT_TEST(NewtonSolverChoice, AutoIsTheDefault) {
  TEST_EQUALITY(validated().get<std::string>("Newton Solver"), std::string(kAutoNewtonSolver));
}

TEUCHOS_UNIT_TEST(NewtonSolverChoice, AutoFollowsTheSize) {
  const Teuchos::ParameterList p = validated();
  const long long n = kAutoSparseDirectMaxDofs;
  TEST_EQUALITY(chosenNewtonSolver(p, n, true), std::string("Sparse Direct"));
  TEST_EQUALITY(chosenNewtonSolver(p, n + 1, true), std::string("CG+MueLu"));
  // MueLu's aggregation needs the coordinates.
  TEST_EQUALITY(chosenNewtonSolver(p, 100 * n, false), std::string("Sparse Direct"));
}

TEUCHOS_UNIT_TEST(NewtonSolverChoice, DenseSchurTakesAFactorization) {
  Teuchos::ParameterList p;
  p.set("Dense Schur", true);
  p = validated(p);
  TEST_EQUALITY(chosenNewtonSolver(p, 100 * kAutoSparseDirectMaxDofs, true), std::string("Sparse Direct"));
  TEST_NOTHROW(SemismoothStarNewton::checkParameters(p));
}

TEUCHOS_UNIT_TEST(NewtonSolverChoice, ExplicitNamesAreKept) {
  for (const std::string name : {"Sparse Direct", "Reduced CG", "CG+MueLu"}) {
    Teuchos::ParameterList p;
    p.set("Newton Solver", name);
    p = validated(p);
    TEST_EQUALITY(chosenNewtonSolver(p, 10, true), name);
    TEST_EQUALITY(chosenNewtonSolver(p, 100 * kAutoSparseDirectMaxDofs, false), name);
  }
}

TEUCHOS_UNIT_TEST(NewtonSolverChoice, UnknownNamesAreRefused) {
  Teuchos::ParameterList p;
  p.set("Newton Solver", "auto");
  TEST_THROW(validated(p), Teuchos::Exceptions::InvalidParameterValue);
}

}  // namespace
