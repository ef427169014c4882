#include "FrictionTestChecks.hpp"

#include <Teuchos_LocalTestingHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

namespace frictest {

using namespace Tribos;

Run solveWith(const std::string& name, const Problem& p, const Teuchos::ParameterList& params) {
  const auto d = buildDual(p, Tpetra::getDefaultComm());
  auto solver = Friction::FrictionSolverFactory().create(name, params);
  Vector x(d.map);  // zero start: projected onto Omega by the solvers
  Run run;
  run.status = solver->solve(d.dual, x);
  run.x = gather(x);
  run.slipBound = gatherContacts(run.status.slipBound, d, p.contacts);
  return run;
}

void checkSolution(const Problem& p, const Vec& x, const Vec& reference, const Vec& mu, const Vec& g, double tol,
                   Teuchos::FancyOStream& out, bool& success) {
  const double scale = std::max(1.0, *std::max_element(reference.begin(), reference.end(),
                                                       [](double a, double b) { return std::abs(a) < std::abs(b); }));
  const double error = maxAbsDiff(x, reference) / std::abs(scale);
  TEST_COMPARE(error, <=, tol);
  const double kkt = naturalResidual(p, x, mu, g);
  TEST_COMPARE(kkt, <=, tol);
  const double infeasible = feasibilityViolation(p, x, g);
  TEST_COMPARE(infeasible, <=, tol);
}

void checkCoulombFixedPoint(const Problem& p, const Run& run, const Vec& mu, double tol, Teuchos::FancyOStream& out,
                            bool& success) {
  const Vec g = slipBoundAt(p, run.x);
  const double gChange = maxAbsDiff(run.slipBound, g) / std::max(1.0, norm(g));
  TEST_COMPARE(gChange, <=, tol);
  const double kkt = naturalResidual(p, run.x, mu, g);
  TEST_COMPARE(kkt, <=, tol);
}

}  // namespace frictest
