// convergence.cpp: the semismooth* Newton method on the prism benchmark,
// with exact Newton steps ("Sparse Direct", the method of the paper; Auto
// takes inexact CG+MueLu steps from level 4, tested in ss_test_cg_muelu).
// Mesh independence: 5..10 Newton steps for L = 2..6 (L = 7, 8 are in the
// benchmark: too slow for the test budget). Superlinear convergence on L = 4
// and 5: the quotients r_{k+1}/r_k of the residuals after the approximation
// steps fall towards 0 in the last iterations.
#include <Teuchos_UnitTestHarness.hpp>

#include "PrismProblem.hpp"

namespace {

using namespace Tribos;

void checkLevel(int L, Teuchos::FancyOStream& out, bool& success) {
  Semismooth::MeshContactProblem pr = sstest::prism(L);
  pr.solverParams.set("Newton Solver", "Sparse Direct");
  const Semismooth::SemismoothResult r = Semismooth::solveFromMesh(
      pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction, pr.solverParams, &out);
  const double tol = pr.solverParams.get<double>("Tolerance", 1e-8);
  TEST_ASSERT(r.converged);
  TEST_COMPARE(r.residuals.back(), <=, tol);
  // 5..10 Newton steps.
  TEST_COMPARE(r.iterations, >=, 5);
  TEST_COMPARE(r.iterations, <=, 10);
  if (L >= 4) {
    const auto& res = r.residuals;
    const size_t k = res.size();
    TEST_COMPARE(k, >=, 4u);  // enough iterations to judge the rate
    if (k >= 4) {
      const double q1 = res[k - 3] / res[k - 4], q2 = res[k - 2] / res[k - 3], q3 = res[k - 1] / res[k - 2];
      out << "L=" << L << " last quotients " << q1 << " " << q2 << " " << q3 << "\n";
      // The quotients fall towards 0.
      TEST_COMPARE(q2, <, q1);
      TEST_COMPARE(q3, <, 1e-3);
      TEST_COMPARE(q2, <, 0.1);
    }
  }
}

}  // namespace

TEUCHOS_UNIT_TEST(Convergence, Level2) { checkLevel(2, out, success); }
TEUCHOS_UNIT_TEST(Convergence, Level3) { checkLevel(3, out, success); }
TEUCHOS_UNIT_TEST(Convergence, Level4) { checkLevel(4, out, success); }
TEUCHOS_UNIT_TEST(Convergence, Level5) { checkLevel(5, out, success); }
TEUCHOS_UNIT_TEST(Convergence, Level6) { checkLevel(6, out, success); }
