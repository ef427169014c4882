// sparse_vs_dense.cpp: on the smallest prism (L = 2) the sparse path (S
// applied by K_rr solves, Newton steps in the full primal space) and the
// dense-Schur path (S formed, Newton systems on the contact boundary) give
// the same iterates to 1e-10, so does KLU2 instead of CHOLMOD, and Newton
// steps by CG agree to 1e-8; the contact frames are objective (the same prism
// rotated in space gives the rotated solution); parameters are validated.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>

#include "PrismProblem.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;
using Test::maxRelDiff;

const Semismooth::MeshContactProblem& prism2() {
  static const Semismooth::MeshContactProblem pr = sstest::prism(2);
  return pr;
}

Teuchos::ParameterList sparseParams() {
  Teuchos::ParameterList p = prism2().solverParams;
  p.set("Dense Schur", false);
  return p;
}

Semismooth::SemismoothResult solve(const Teuchos::ParameterList& params) {
  const auto& pr = prism2();
  return Semismooth::solveFromMesh(pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction,
                                   params, nullptr);
}

// The sparse path, the reference of every case; solved once.
const Semismooth::SemismoothResult& sparse() {
  static const Semismooth::SemismoothResult s = solve(sparseParams());
  return s;
}

}  // namespace

TEUCHOS_UNIT_TEST(SparseVsDense, SameIterates) {
  Teuchos::ParameterList denseParams = prism2().solverParams;
  denseParams.set("Dense Schur", true);
  const Semismooth::SemismoothResult& s = sparse();
  const Semismooth::SemismoothResult d = solve(denseParams);
  TEST_ASSERT(s.converged);
  TEST_ASSERT(d.converged);
  TEST_EQUALITY(s.iterations, d.iterations);
  for (size_t k = 0; k < std::min(s.residuals.size(), d.residuals.size()); ++k) {
    out << "step " << k << "\n";
    // The same active sets.
    TEST_EQUALITY(s.numContact[k], d.numContact[k]);
    TEST_EQUALITY(s.numStick[k], d.numStick[k]);
    if (s.residuals[k] > 1e-6) TEST_COMPARE(std::abs(s.residuals[k] - d.residuals[k]), <=, 1e-10);
  }
  out << "u: " << maxRelDiff(s.u, d.u) << ", x: " << maxRelDiff(s.x, d.x) << ", y: " << maxRelDiff(s.y, d.y) << "\n";
  TEST_COMPARE(maxRelDiff(s.u, d.u), <=, 1e-10);
  TEST_COMPARE(maxRelDiff(s.x, d.x), <=, 1e-10);
  TEST_COMPARE(maxRelDiff(s.y, d.y), <=, 1e-10);
}

// Newton steps by CG on the contact boundary: the same iterates up to the
// CG tolerance (1e-12).
TEUCHOS_UNIT_TEST(SparseVsDense, ReducedCG) {
  const Semismooth::SemismoothResult& s = sparse();
  Teuchos::ParameterList cgParams = sparseParams();
  cgParams.set("Newton Solver", "Reduced CG");
  const Semismooth::SemismoothResult c = solve(cgParams);
  out << "Reduced CG: u differs by " << maxRelDiff(c.u, s.u) << ", " << c.cgIterations << " CG steps\n";
  TEST_ASSERT(c.converged);
  TEST_EQUALITY(c.iterations, s.iterations);
  TEST_COMPARE(maxRelDiff(c.u, s.u), <=, 1e-8);
}

// Another sparse direct backend (refactoring from scratch each time).
TEUCHOS_UNIT_TEST(SparseVsDense, KLU2) {
  const Semismooth::SemismoothResult& s = sparse();
  Teuchos::ParameterList kluParams = sparseParams();
  kluParams.set("Local Solver", "KLU2");
  const Semismooth::SemismoothResult k = solve(kluParams);
  TEST_ASSERT(k.converged);
  TEST_EQUALITY(k.iterations, s.iterations);
  TEST_COMPARE(maxRelDiff(k.u, s.u), <=, 1e-10);
}

// The dense S is symmetric with a positive diagonal.
TEUCHOS_UNIT_TEST(SparseVsDense, DenseSchurSymmetric) {
  const auto& pr = prism2();
  const Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                       pr.gap, pr.slipBoundTraction);
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
  TEST_COMPARE(asym, <=, 1e-10 * smax);
  TEST_COMPARE(diagMin, >, 0);
}

// Objectivity: rotate the body, its loads and thus its contact plane.
TEUCHOS_UNIT_TEST(SparseVsDense, RotatedPrism) {
  const Semismooth::SemismoothResult& s = sparse();
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
  Semismooth::MeshContactProblem rp = prism2();
  for (auto& X : rp.mesh.coords) X = rot(X);
  for (auto& t : rp.loads.tractions) t.traction = rot(t.traction);
  const Semismooth::SemismoothResult q = Semismooth::solveFromMesh(
      rp.mesh, rp.material, rp.loads, rp.contactFace, rp.gap, rp.slipBoundTraction, sparseParams(), nullptr);
  std::vector<double> Qu(s.u.size());
  for (size_t node = 0; node < s.u.size() / 3; ++node) {
    const auto w = rot({s.u[3 * node], s.u[3 * node + 1], s.u[3 * node + 2]});
    for (int a = 0; a < 3; ++a) Qu[3 * node + a] = w[a];
  }
  out << "rotated prism: u differs from Q u by " << maxRelDiff(q.u, Qu) << "\n";
  TEST_ASSERT(q.converged);
  TEST_COMPARE(maxRelDiff(q.u, Qu), <=, 1e-8);
}

// Misspelled names and bad values are rejected with the parameter's name.
TEUCHOS_UNIT_TEST(SparseVsDense, ParametersValidated) {
  Teuchos::ParameterList bad;
  bad.set("Local Solver", "UMFPACK");
  bool threw = false;
  try {
    bad.validateParametersAndSetDefaults(*Semismooth::SemismoothStarNewton::getValidParameters());
  } catch (const std::exception& e) {
    threw = std::string(e.what()).find("Local Solver") != std::string::npos;
  }
  TEST_ASSERT(threw);  // an unknown local solver is rejected naming the parameter
  Teuchos::ParameterList typo;
  typo.set("Tolerence", 1e-6);
  threw = false;
  try {
    typo.validateParametersAndSetDefaults(*Semismooth::SemismoothStarNewton::getValidParameters());
  } catch (const std::exception&) {
    threw = true;
  }
  TEST_ASSERT(threw);  // a misspelled parameter is rejected
}
