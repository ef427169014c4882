// The cone projection and the natural-map error on problems with a known
// exact solution (one contact in stick, one in slip, one separated).
#include <Teuchos_UnitTestHarness.hpp>
#include <cmath>
#include <iomanip>
#include <random>

#include "Tribos_FCLIB_Accuracy.hpp"
#include "Tribos_Vec3.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;
using namespace Tribos::FCLIB;
using Tribos::Vec3, Tribos::dot, Tribos::minus, Tribos::norm;

namespace {

bool inCone(const Vec3& r, double mu, double tol) {
  return std::hypot(r[1], r[2]) <= mu * r[0] + tol;
}
// Polar cone of K_mu: {mu ||y_T|| <= -y_N}.
bool inPolarCone(const Vec3& y, double mu, double tol) {
  return mu * std::hypot(y[1], y[2]) <= -y[0] + tol;
}

// Moreau: x = P(x) + (x - P(x)) with P(x) in K, x - P(x) in the polar cone and
// the two orthogonal; these characterize the Euclidean projection onto K.
void checkProjection(Teuchos::FancyOStream& out, bool& success) {
  std::mt19937 gen(7);
  std::normal_distribution<double> g;
  int count = 0;
  for (double mu : {0.0, 0.1, 0.3, 1.0, 2.5}) {
    for (int trial = 0; trial < 2000; ++trial) {
      const Vec3 x = {g(gen), g(gen), g(gen)};
      const Vec3 p = projectOntoCoulombCone(x, mu);
      const Vec3 d = minus(x, p);
      const double tol = 1e-14 * (1.0 + norm(x));
      out << "mu " << mu << ", x " << x[0] << " " << x[1] << " " << x[2] << "\n";
      TEST_ASSERT(inCone(p, mu, tol));
      TEST_ASSERT(inPolarCone(d, mu, tol));
      TEST_COMPARE(std::abs(dot(p, d)), <=, tol * (1.0 + norm(x)));  // Moreau: p orthogonal to x - p
      const Vec3 pp = projectOntoCoulombCone(p, mu);
      TEST_COMPARE(norm(minus(pp, p)), <=, 4e-16 * (1.0 + norm(p)));  // idempotent
      ++count;
    }
  }
  // Exact cases: interior point unchanged bitwise, polar point to 0.
  const Vec3 inside = {1.0, 0.1, -0.2};
  TEST_ASSERT(projectOntoCoulombCone(inside, 0.5) == inside);  // an interior point stays
  TEST_ASSERT(projectOntoCoulombCone({-1.0, 0.1, 0.1}, 0.5) == (Vec3{0, 0, 0}));  // a polar point goes to 0
  TEST_ASSERT(projectOntoCoulombCone({2.0, 3.0, 4.0}, 0.0) == (Vec3{2.0, 0, 0}));  // mu = 0
  std::cout << "projection: " << count << " random points checked" << std::endl;
}

// Contacts of the constructed solution, in the local frame (N, T1, T2).
struct ExactContacts {
  std::vector<double> r, u, mu;
};

ExactContacts buildExactContacts() {
  ExactContacts e;
  e.mu = {0.5, 0.5, 0.3, 0.0};
  // Stick: r strictly inside the cone, u = 0.
  e.r.insert(e.r.end(), {1.0, 0.2, -0.1});
  e.u.insert(e.u.end(), {0.0, 0.0, 0.0});
  // Slip: r on the cone boundary, u_T opposite to r_T, u_N = 0.
  const double rN = 2.0, angle = 0.7, speed = 0.8;
  const Vec3 rSlip = {rN, 0.5 * rN * std::cos(angle), 0.5 * rN * std::sin(angle)};
  e.r.insert(e.r.end(), rSlip.begin(), rSlip.end());
  e.u.insert(e.u.end(), {0.0, -speed * std::cos(angle), -speed * std::sin(angle)});
  // Separation: r = 0, gap opening.
  e.r.insert(e.r.end(), {0.0, 0.0, 0.0});
  e.u.insert(e.u.end(), {0.7, 0.3, -0.2});
  // Frictionless contact in compression, sliding freely.
  e.r.insert(e.r.end(), {1.5, 0.0, 0.0});
  e.u.insert(e.u.end(), {0.0, 0.4, 0.1});
  return e;
}

LocalCsr randomSPD(int n, std::mt19937& gen) {
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<double> B(n * n);
  for (double& b : B) b = uni(gen);
  std::vector<int> row, col;
  std::vector<double> val;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = (i == j) ? 1.0 : 0.0;
      for (int k = 0; k < n; ++k) s += B[i * n + k] * B[j * n + k];
      row.push_back(i);
      col.push_back(j);
      val.push_back(s);
    }
  return fromTriplets(n, n, row, col, val, "randomSPD");
}

void checkLocalExactSolution(Teuchos::FancyOStream& out, bool& success) {
  std::mt19937 gen(11);
  const ExactContacts e = buildExactContacts();
  LocalProblem P;
  P.mu = e.mu;
  P.W = randomSPD(static_cast<int>(e.r.size()), gen);
  // q such that u = W r + q holds at the exact solution.
  std::vector<double> Wr;
  P.W.multiply(e.r, Wr);
  P.q.resize(Wr.size());
  for (std::size_t k = 0; k < Wr.size(); ++k) P.q[k] = e.u[k] - Wr[k];
  validate(P, "constructed local problem");

  const NaturalMapError exact = naturalMapError(P, e.r);
  std::cout << std::scientific << std::setprecision(3) << "local exact: err/||q|| = "
            << exact.relativeToQ << ", err/max = " << exact.relativeToMax << std::endl;
  TEST_COMPARE(exact.relativeToQ, <=, 1e-14);
  TEST_COMPARE(exact.relativeToMax, <=, 1e-14);

  // Each perturbation breaks the conditions at one contact.
  for (std::size_t k = 0; k < e.r.size(); ++k) {
    std::vector<double> r = e.r;
    r[k] += 1e-3;
    const NaturalMapError perturbed = naturalMapError(P, r);
    TEST_COMPARE(perturbed.relativeToQ, >, 1e-6);  // perturbing r[
  }
  std::vector<double> zero(e.r.size(), 0.0);
  TEST_COMPARE(naturalMapError(P, zero).relativeToQ, >, 1e-3);  // r = 0 is not a solution
}

void checkGlobalExactSolution(Teuchos::FancyOStream& out, bool& success) {
  std::mt19937 gen(13);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const ExactContacts e = buildExactContacts();
  const int ndof = 20, m = static_cast<int>(e.r.size());
  GlobalProblem P;
  P.mu = e.mu;
  P.M = randomSPD(ndof, gen);
  std::vector<int> row, col;
  std::vector<double> val;
  for (int i = 0; i < ndof; ++i)
    for (int j = 0; j < m; ++j)
      if (uni(gen) > 0.0) {
        row.push_back(i);
        col.push_back(j);
        val.push_back(uni(gen));
      }
  P.H = fromTriplets(ndof, m, row, col, val, "H");
  // Pick v, then f and w so that M v = H r + f and u = H' v + w.
  std::vector<double> v(ndof), Mv, Hr, Htv;
  for (double& x : v) x = uni(gen);
  P.M.multiply(v, Mv);
  P.H.multiply(e.r, Hr);
  P.H.multiplyTranspose(v, Htv);
  P.f.resize(ndof);
  for (int i = 0; i < ndof; ++i) P.f[i] = Mv[i] - Hr[i];
  P.w.resize(m);
  for (int j = 0; j < m; ++j) P.w[j] = e.u[j] - Htv[j];
  validate(P, "constructed global problem");

  const fclib_test::DenseCholesky chol(P.M);
  const SolveM solve = [&](const std::vector<double>& b, std::vector<double>& x) {
    chol.solve(b, x);
  };
  const NaturalMapError exact = naturalMapError(P, e.r, solve);
  std::cout << "global exact: err/||q|| = " << exact.relativeToQ
            << ", err/max = " << exact.relativeToMax << std::endl;
  TEST_COMPARE(exact.relativeToQ, <=, 1e-13);
  const GlobalReduction red = reduceGlobal(P, e.r, solve);
  double dv = 0.0;
  for (int i = 0; i < ndof; ++i) dv = std::max(dv, std::abs(red.v[i] - v[i]));
  TEST_COMPARE(dv, <=, 1e-12);  // recovered v differs

  std::vector<double> r = e.r;
  r[4] *= 1.01;  // slip force pushed outside the cone
  TEST_COMPARE(naturalMapError(P, r, solve).relativeToQ, >, 1e-6);  // perturbed global
}

}  // namespace

TEUCHOS_UNIT_TEST(Accuracy, Projection) { checkProjection(out, success); }
TEUCHOS_UNIT_TEST(Accuracy, LocalExactSolution) { checkLocalExactSolution(out, success); }
TEUCHOS_UNIT_TEST(Accuracy, GlobalExactSolution) { checkGlobalExactSolution(out, success); }
