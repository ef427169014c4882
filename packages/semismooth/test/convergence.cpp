// convergence.cpp: the semismooth* Newton method on the prism benchmark.
// Mesh independence: 5..10 Newton steps for L = 2..6 (L = 7, 8 are in the
// benchmark: too slow for the test budget). Superlinear convergence on L = 4
// and 5: the quotients r_{k+1}/r_k of the residuals after the approximation
// steps fall towards 0 in the last iterations.
#include "SemismoothTestUtils.hpp"

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  for (int L = 2; L <= 6; ++L) {
    Semismooth::MeshContactProblem pr = sstest::prism(L);
    const Semismooth::SemismoothResult r = Semismooth::solveFromMesh(
        pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction, pr.solverParams, &std::cout);
    const double tol = pr.solverParams.get<double>("Tolerance", 1e-8);
    SS_CHECK(r.converged && r.residuals.back() <= tol, "L=" << L << " did not converge");
    SS_CHECK(r.iterations >= 5 && r.iterations <= 10, "L=" << L << ": " << r.iterations << " Newton steps");
    if (L >= 4) {
      const auto& res = r.residuals;
      const size_t k = res.size();
      SS_CHECK(k >= 4, "L=" << L << ": too few iterations to judge the rate");
      if (k >= 4) {
        const double q1 = res[k - 3] / res[k - 4], q2 = res[k - 2] / res[k - 3], q3 = res[k - 1] / res[k - 2];
        std::cout << "L=" << L << " last quotients " << q1 << " " << q2 << " " << q3 << "\n";
        SS_CHECK(q2 < q1 && q3 < 1e-3 && q2 < 0.1, "L=" << L << ": quotients " << q1 << ", " << q2 << ", " << q3
                                                         << " do not fall towards 0");
      }
    }
  }
  return sstest::finish();
}
