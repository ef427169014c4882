// cg_muelu.cpp: "Newton Solver" = "CG+MueLu" (no factorization; full-space
// iterate in interior equilibrium, Newton steps by Belos CG with MueLu).
//  - On L = 3 and 4 it gives the x, y (contact displacements and forces) of
//    "Sparse Direct" to 1e-6 relative, and its answer reaches the Tolerance in
//    the true residual ||S x^ - l + y^||/||l||, recomputed independently with
//    ContactReduction's exact applyS (CHOLMOD) and l.
//  - Mesh independence: 5..10 Newton steps on L = 2..5; superlinear
//    convergence at the end (L = 4, 5).
//  - The reported last residual agrees with the true one to 1% of the
//    Tolerance, also when the step limit stops the iteration (the residuals
//    of the steps before are estimates).
//  - reduction() and "Dense Schur" are refused with CG+MueLu.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>

#include "PrismProblem.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;

// ||S x^ - l + y^|| / ||l|| at the answer, from the exact Schur complement
// (ContactReduction's applyS by CHOLMOD) and l.
double trueResidual(const Semismooth::ContactProblem& p, const Semismooth::SemismoothResult& c) {
  const Semismooth::ContactReduction exact(p, "CHOLMOD");
  std::vector<double> Sx;
  exact.applyS(c.x, Sx);
  std::vector<double> r(Sx.size());
  for (size_t j = 0; j < r.size(); ++j) r[j] = Sx[j] - exact.l()[j] + c.y[j];
  return Tribos::norm2(r) / Tribos::norm2(exact.l());
}

void checkLevel(int L, Teuchos::FancyOStream& out, bool& success) {
  Semismooth::MeshContactProblem pr = sstest::prism(L);
  Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                 pr.gap, pr.slipBoundTraction);
  // On several ranks the CG solves are distributed; the answer must not change.
  p.comm = Tpetra::getDefaultComm();
  Teuchos::ParameterList params = pr.solverParams;
  params.set("Newton Solver", "CG+MueLu");
  Semismooth::SemismoothStarNewton solver(p, params);
  const Semismooth::SemismoothResult c = solver.solve(&out);
  const double tol = params.get<double>("Tolerance", 1e-8);
  out << "L=" << L << ": " << c.iterations << " Newton steps, " << c.cgIterations << " CG steps\n";
  TEST_ASSERT(c.converged);
  TEST_COMPARE(c.residuals.back(), <=, tol);
  // 5..10 Newton steps.
  TEST_COMPARE(c.iterations, >=, 5);
  TEST_COMPARE(c.iterations, <=, 10);
  if (L >= 4) {  // inexact Newton with a forcing term tied to the residual stays superlinear
    const auto& res = c.residuals;
    const size_t k = res.size();
    const double q2 = res[k - 2] / res[k - 3], q3 = res[k - 1] / res[k - 2];
    out << "L=" << L << " last quotients " << q2 << " " << q3 << "\n";
    // The last step may stop at the floor of the inexact solves (a tenth of
    // the tolerance), so one of the last two quotients must be small.
    TEST_COMPARE(std::max(q2, q3), <, 0.1);
    TEST_COMPARE(std::min(q2, q3), <, 1e-2);
  }

  const double trueRel = trueResidual(p, c);
  out << "L=" << L << ": true residual " << trueRel << ", reported " << c.residuals.back() << "\n";
  TEST_COMPARE(trueRel, <=, tol);
  TEST_COMPARE(std::abs(trueRel - c.residuals.back()), <=, 0.01 * tol);

  if (L == 3 || L == 4) {
    const Semismooth::SemismoothResult d = Semismooth::solveFromMesh(
        pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction, pr.solverParams, nullptr);
    out << "L=" << L << ": vs Sparse Direct: x " << Test::maxRelDiff(c.x, d.x) << ", y " << Test::maxRelDiff(c.y, d.y)
        << ", u " << Test::maxRelDiff(c.u, d.u) << "\n";
    TEST_COMPARE(Test::maxRelDiff(c.x, d.x), <=, 1e-6);
    TEST_COMPARE(Test::maxRelDiff(c.y, d.y), <=, 1e-6);
    TEST_COMPARE(Test::maxRelDiff(c.u, d.u), <=, 1e-6);
  }
  if (L == 2) {
    bool refused = false;
    try {
      solver.reduction();
    } catch (const Error&) {
      refused = true;
    }
    TEST_ASSERT(refused);  // reduction() is refused with CG+MueLu
    refused = false;
    Teuchos::ParameterList dense = params;
    dense.set("Dense Schur", true);
    try {
      Semismooth::SemismoothStarNewton bad(p, dense);
    } catch (const Error&) {
      refused = true;
    }
    TEST_ASSERT(refused);  // Dense Schur is refused with CG+MueLu
  }
}

// The residual of a step is estimated (the Newton steps restore equilibrium
// themselves); the one that ends the iteration is confirmed. Stopped by the
// step limit, the run must say so and report the true residual of its
// answer, not an estimate.
void checkStoppedEarly(int maxSteps, Teuchos::FancyOStream& out, bool& success) {
  Semismooth::MeshContactProblem pr = sstest::prism(4);
  Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                 pr.gap, pr.slipBoundTraction);
  p.comm = Tpetra::getDefaultComm();
  Teuchos::ParameterList params = pr.solverParams;
  params.set("Newton Solver", "CG+MueLu");
  params.set("Maximum Iterations", maxSteps);
  const Semismooth::SemismoothResult c = Semismooth::SemismoothStarNewton(p, params).solve(&out);
  const double tol = params.get<double>("Tolerance", 1e-8);
  TEST_ASSERT(!c.converged);
  TEST_EQUALITY(c.iterations, maxSteps);
  const double trueRel = trueResidual(p, c);
  out << maxSteps << " steps: true residual " << trueRel << ", reported " << c.residuals.back() << "\n";
  TEST_COMPARE(trueRel, >, tol);
  // Relative to ||l||, which the initial solve gives to its tolerance (1e-3
  // of the solve, 1e-5 of ||l|| here): an estimate would be off by a factor.
  TEST_COMPARE(std::abs(trueRel - c.residuals.back()), <=, 1e-3 * trueRel + 0.01 * tol);
}

}  // namespace

TEUCHOS_UNIT_TEST(CGMueLu, StoppedEarly) {
  checkStoppedEarly(2, out, success);
  checkStoppedEarly(5, out, success);
}
TEUCHOS_UNIT_TEST(CGMueLu, Level2) { checkLevel(2, out, success); }
TEUCHOS_UNIT_TEST(CGMueLu, Level3) { checkLevel(3, out, success); }
TEUCHOS_UNIT_TEST(CGMueLu, Level4) { checkLevel(4, out, success); }
TEUCHOS_UNIT_TEST(CGMueLu, Level5) { checkLevel(5, out, success); }
