#include <algorithm>
// cg_muelu.cpp: "Newton Solver" = "CG+MueLu" (no factorization; full-space
// iterate in interior equilibrium, Newton steps by Belos CG with MueLu).
//  - On L = 3 and 4 it gives the x, y (contact displacements and forces) of
//    "Sparse Direct" to 1e-6 relative, and its answer reaches the Tolerance in
//    the true residual ||S x^ - l + y^||/||l||, recomputed independently with
//    ContactReduction's exact applyS (CHOLMOD) and l.
//  - Mesh independence: 5..10 Newton steps on L = 2..5; superlinear
//    convergence at the end (L = 4, 5).
//  - The reported last residual agrees with the true one to 1%.
//  - reduction() and "Dense Schur" are refused with CG+MueLu.
#include "SemismoothTestUtils.hpp"
#include "Tribos_TestSupport.hpp"

#include <Teuchos_ParameterList.hpp>

#include "Tribos_Error.hpp"


int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  for (int L = 2; L <= 5; ++L) {
    Semismooth::MeshContactProblem pr = sstest::prism(L);
    Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                   pr.gap, pr.slipBoundTraction);
    // On several ranks the CG solves are distributed; the answer must not change.
    p.comm = Tpetra::getDefaultComm();
    Teuchos::ParameterList params = pr.solverParams;
    params.set("Newton Solver", "CG+MueLu");
    Semismooth::SemismoothStarNewton solver(p, params);
    const Semismooth::SemismoothResult c = solver.solve(&std::cout);
    const double tol = params.get<double>("Tolerance", 1e-8);
    std::cout << "L=" << L << ": " << c.iterations << " Newton steps, " << c.cgIterations << " CG steps\n";
    SS_CHECK(c.converged && c.residuals.back() <= tol, "L=" << L << ": CG+MueLu did not converge");
    SS_CHECK(c.iterations >= 5 && c.iterations <= 10, "L=" << L << ": " << c.iterations << " Newton steps");
    if (L >= 4) {  // inexact Newton with a forcing term tied to the residual stays superlinear
      const auto& res = c.residuals;
      const size_t k = res.size();
      const double q2 = res[k - 2] / res[k - 3], q3 = res[k - 1] / res[k - 2];
      std::cout << "L=" << L << " last quotients " << q2 << " " << q3 << "\n";
      // The last step may stop at the floor of the inexact solves (a tenth of
      // the tolerance), so one of the last two quotients must be small.
      SS_CHECK(std::max(q2, q3) < 0.1 && std::min(q2, q3) < 1e-2,
               "L=" << L << ": quotients " << q2 << ", " << q3 << " do not fall towards 0");
    }

    // The true residual at the answer, from the exact Schur complement.
    const Semismooth::ContactReduction exact(p, "CHOLMOD");
    std::vector<double> Sx;
    exact.applyS(c.x, Sx);
    std::vector<double> r(Sx.size());
    for (size_t j = 0; j < r.size(); ++j) r[j] = Sx[j] - exact.l()[j] + c.y[j];
    const double trueRel = Semismooth::norm2(r) / Semismooth::norm2(exact.l());
    std::cout << "L=" << L << ": true residual " << trueRel << ", reported " << c.residuals.back() << "\n";
    SS_CHECK(trueRel <= tol, "L=" << L << ": true residual " << trueRel << " above Tolerance " << tol);
    SS_CHECK(std::abs(trueRel - c.residuals.back()) <= 0.01 * tol,
             "L=" << L << ": reported residual " << c.residuals.back() << ", true " << trueRel);

    if (L == 3 || L == 4) {
      const Semismooth::SemismoothResult d = Semismooth::solveFromMesh(
          pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction, pr.solverParams, nullptr);
      std::cout << "L=" << L << ": vs Sparse Direct: x " << Test::maxRelDiff(c.x, d.x) << ", y " << Test::maxRelDiff(c.y, d.y) << ", u "
                << Test::maxRelDiff(c.u, d.u) << "\n";
      SS_CHECK(Test::maxRelDiff(c.x, d.x) <= 1e-6, "L=" << L << ": x differs by " << Test::maxRelDiff(c.x, d.x));
      SS_CHECK(Test::maxRelDiff(c.y, d.y) <= 1e-6, "L=" << L << ": y differs by " << Test::maxRelDiff(c.y, d.y));
      SS_CHECK(Test::maxRelDiff(c.u, d.u) <= 1e-6, "L=" << L << ": u differs by " << Test::maxRelDiff(c.u, d.u));
    }
    if (L == 2) {
      bool refused = false;
      try {
        solver.reduction();
      } catch (const Error&) {
        refused = true;
      }
      SS_CHECK(refused, "reduction() must be refused with CG+MueLu");
      refused = false;
      Teuchos::ParameterList dense = params;
      dense.set("Dense Schur", true);
      try {
        Semismooth::SemismoothStarNewton bad(p, dense);
      } catch (const Error&) {
        refused = true;
      }
      SS_CHECK(refused, "Dense Schur must be refused with CG+MueLu");
    }
  }
  return sstest::finish();
}
