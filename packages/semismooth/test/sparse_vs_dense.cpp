// sparse_vs_dense.cpp: on the smallest prism (L = 2) the sparse path (S
// applied by K_rr solves, Newton steps in the full primal space) and the
// dense-Schur path (S formed, Newton systems on the contact boundary) give
// the same iterates to 1e-10, so does KLU2 instead of CHOLMOD, and Newton
// steps by CG agree to 1e-8; the contact frames are objective (the same prism
// rotated in space gives the rotated solution); parameters are validated.
#include "SemismoothTestUtils.hpp"
#include "Tribos_TestSupport.hpp"

#include <Teuchos_ParameterList.hpp>


int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  Semismooth::MeshContactProblem pr = sstest::prism(2);
  Teuchos::ParameterList sparseParams = pr.solverParams, denseParams = pr.solverParams;
  sparseParams.set("Dense Schur", false);
  denseParams.set("Dense Schur", true);
  const auto solve = [&](const Teuchos::ParameterList& params) {
    return Semismooth::solveFromMesh(pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction,
                                     params, nullptr);
  };
  const Semismooth::SemismoothResult s = solve(sparseParams), d = solve(denseParams);
  SS_CHECK(s.converged && d.converged, "no convergence");
  SS_CHECK(s.iterations == d.iterations, "iterations " << s.iterations << " vs " << d.iterations);
  for (size_t k = 0; k < std::min(s.residuals.size(), d.residuals.size()); ++k) {
    SS_CHECK(s.numContact[k] == d.numContact[k] && s.numStick[k] == d.numStick[k], "active sets differ at " << k);
    if (s.residuals[k] > 1e-6) SS_CHECK(std::abs(s.residuals[k] - d.residuals[k]) <= 1e-10, "residual " << k);
  }
  std::cout << "u: " << Test::maxRelDiff(s.u, d.u) << ", x: " << Test::maxRelDiff(s.x, d.x) << ", y: " << Test::maxRelDiff(s.y, d.y) << "\n";
  SS_CHECK(Test::maxRelDiff(s.u, d.u) <= 1e-10, "u differs by " << Test::maxRelDiff(s.u, d.u));
  SS_CHECK(Test::maxRelDiff(s.x, d.x) <= 1e-10, "x differs by " << Test::maxRelDiff(s.x, d.x));
  SS_CHECK(Test::maxRelDiff(s.y, d.y) <= 1e-10, "y differs by " << Test::maxRelDiff(s.y, d.y));

  // Newton steps by CG on the contact boundary: the same iterates up to the
  // CG tolerance (1e-12).
  {
    Teuchos::ParameterList cgParams = sparseParams;
    cgParams.set("Newton Solver", "Reduced CG");
    const Semismooth::SemismoothResult c = solve(cgParams);
    std::cout << "Reduced CG: u differs by " << Test::maxRelDiff(c.u, s.u) << ", " << c.cgIterations << " CG steps\n";
    SS_CHECK(c.converged && c.iterations == s.iterations && Test::maxRelDiff(c.u, s.u) <= 1e-8,
             "Reduced CG: u differs by " << Test::maxRelDiff(c.u, s.u));
  }

  // Another sparse direct backend (refactoring from scratch each time).
  {
    Teuchos::ParameterList kluParams = sparseParams;
    kluParams.set("Local Solver", "KLU2");
    const Semismooth::SemismoothResult k = solve(kluParams);
    SS_CHECK(k.converged && k.iterations == s.iterations && Test::maxRelDiff(k.u, s.u) <= 1e-10,
             "KLU2: u differs by " << Test::maxRelDiff(k.u, s.u));
  }

  // The dense S is symmetric positive definite and agrees with applyS.
  {
    const Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads,
                                                                         pr.contactFace, pr.gap, pr.slipBoundTraction);
    Semismooth::ContactReduction red(p, "CHOLMOD");
    const std::vector<double> S = red.denseS();
    const int nc = red.numReduced();
    double asym = 0, smax = 0, diagMin = 1e300;
    for (int i = 0; i < nc; ++i) {
      diagMin = std::min(diagMin, S[static_cast<size_t>(i) * nc + i]);
      for (int j = 0; j < nc; ++j) {
        asym = std::max(asym, std::abs(S[static_cast<size_t>(i) * nc + j] - S[static_cast<size_t>(j) * nc + i]));
        smax = std::max(smax, std::abs(S[static_cast<size_t>(i) * nc + j]));
      }
    }
    SS_CHECK(asym <= 1e-10 * smax && diagMin > 0, "S is not symmetric with a positive diagonal");
  }

  // Objectivity: rotate the body, its loads and thus its contact plane.
  {
    const double c = std::cos(0.7), sn = std::sin(0.7), c2 = std::cos(-0.4), s2 = std::sin(-0.4);
    // Q = Rz(0.7) Rx(-0.4)
    const double Rz[3][3] = {{c, -sn, 0}, {sn, c, 0}, {0, 0, 1}}, Rx[3][3] = {{1, 0, 0}, {0, c2, -s2}, {0, s2, c2}};
    double Q[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        Q[a][b] = 0;
        for (int k = 0; k < 3; ++k) Q[a][b] += Rz[a][k] * Rx[k][b];
      }
    auto rot = [&](const std::array<double, 3>& v) {
      std::array<double, 3> w{0, 0, 0};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) w[a] += Q[a][b] * v[b];
      return w;
    };
    Semismooth::MeshContactProblem rp = pr;
    for (auto& X : rp.mesh.coords) X = rot(X);
    for (auto& t : rp.loads.tractions) t.traction = rot(t.traction);
    const Semismooth::SemismoothResult q = Semismooth::solveFromMesh(
        rp.mesh, rp.material, rp.loads, rp.contactFace, rp.gap, rp.slipBoundTraction, sparseParams, nullptr);
    std::vector<double> Qu(s.u.size());
    for (size_t node = 0; node < s.u.size() / 3; ++node) {
      const auto w = rot({s.u[3 * node], s.u[3 * node + 1], s.u[3 * node + 2]});
      for (int a = 0; a < 3; ++a) Qu[3 * node + a] = w[a];
    }
    std::cout << "rotated prism: u differs from Q u by " << Test::maxRelDiff(q.u, Qu) << "\n";
    SS_CHECK(q.converged && Test::maxRelDiff(q.u, Qu) <= 1e-8, "rotated prism: u differs from Q u by " << Test::maxRelDiff(q.u, Qu));
  }

  // Misspelled names and bad values are rejected with the parameter's name.
  {
    Teuchos::ParameterList bad;
    bad.set("Local Solver", "UMFPACK");
    bool threw = false;
    try {
      bad.validateParametersAndSetDefaults(*Semismooth::SemismoothStarNewton::getValidParameters());
    } catch (const std::exception& e) {
      threw = std::string(e.what()).find("Local Solver") != std::string::npos;
    }
    SS_CHECK(threw, "an unknown local solver must be rejected naming the parameter");
    Teuchos::ParameterList typo;
    typo.set("Tolerence", 1e-6);
    threw = false;
    try {
      typo.validateParametersAndSetDefaults(*Semismooth::SemismoothStarNewton::getValidParameters());
    } catch (const std::exception&) {
      threw = true;
    }
    SS_CHECK(threw, "a misspelled parameter must be rejected");
  }
  return sstest::finish();
}
