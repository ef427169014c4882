// NonsmoothGaussSeidel on explicit problems:
// - one contact with W = w I, whose Coulomb solution is known in closed form
//   for each case (take-off q_N >= 0: r = 0; stick ||q_T|| <= mu |q_N|:
//   r = -q / w; slip: r_N = -q_N / w, r_T = -mu r_N q_T / ||q_T||);
// - one contact with a full symmetric positive definite W_cc, where the
//   slip case goes through the local Newton iteration: Coulomb's law checked
//   on (r, u = W r + q);
// - a chain of coupled contacts with a manufactured solution (every case
//   present): r recovered, and u returned equal to W r + q;
// - the stopping measure and the refusal of the FETI dual.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <vector>

#include "Tribos_LocalCsr.hpp"
#include "Tribos_NonsmoothGaussSeidel.hpp"

using namespace Tribos;
using Friction::ExplicitCoulombProblem;
using Friction::NonsmoothGaussSeidel;

namespace {

LocalCsr denseCsr(const std::vector<double>& A, int n) {
  LocalCsr M;
  M.rows = M.cols = n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (A[i * n + j] != 0.0) M.col.push_back(j), M.val.push_back(A[i * n + j]);
    M.rowptr.push_back(static_cast<int>(M.col.size()));
  }
  return M;
}

struct Solved {
  Friction::FrictionStatus status;
  std::vector<double> r, u;
};

Solved solveNsgs(const LocalCsr& W, const std::vector<double>& q, const std::vector<double>& mu, double tol = 1e-12) {
  Teuchos::ParameterList pl;
  pl.set("Relative Tolerance", tol);
  NonsmoothGaussSeidel nsgs(pl);
  Solved s;
  s.r.assign(q.size(), 0.0);
  s.status = nsgs.solve(ExplicitCoulombProblem{W.view(), q.data(), mu.data(), static_cast<int>(mu.size())}, s.r, s.u);
  return s;
}

// Coulomb's law on contact c, relative to the scales R of r and U of u:
// r in the cone, u_N >= 0, r_N u_N = 0, and where u_T != 0, r_T = -mu r_N u_T / ||u_T||.
double coulombViolation(const std::vector<double>& r, const std::vector<double>& u, double mu, int c, double R,
                        double U) {
  const double rN = r[3 * c], uN = u[3 * c];
  const double rT = std::hypot(r[3 * c + 1], r[3 * c + 2]), uT = std::hypot(u[3 * c + 1], u[3 * c + 2]);
  double v = std::max({(rT - mu * rN) / R, -rN / R, -uN / U, std::abs(rN * uN) / (R * U)});
  if (uT > 1e-9 * U)
    for (int j = 1; j <= 2; ++j) v = std::max(v, std::abs(r[3 * c + j] + mu * rN * u[3 * c + j] / uT) / R);
  return v;
}

std::vector<double> velocities(const LocalCsr& W, const std::vector<double>& r, const std::vector<double>& q) {
  std::vector<double> u(q.size());
  W.multiply(r.data(), u.data());
  for (size_t i = 0; i < u.size(); ++i) u[i] += q[i];
  return u;
}

// A chain of 12 coupled contacts with a manufactured solution r*: contacts
// c = 0, 3, 6, ... open, 1, 4, ... stuck, 2, 5, ... sliding.
struct Chain {
  LocalCsr W;
  std::vector<double> q, mu, rStar;
};

// The problem of W = A (n x n, dense, row-major) whose solution is r*:
// contacts c = 0, 3, 6, ... open, 1, 4, ... stuck, 2, 5, ... sliding.
Chain manufactured(const std::vector<double>& A, int nc);

Chain manufacturedChain() {
  const int nc = 12, n = 3 * nc;
  std::vector<double> A(n * n, 0.0);
  for (int c = 0; c < nc; ++c) {
    for (int a = 0; a < 3; ++a) A[(3 * c + a) * n + 3 * c + a] = 2.0 + 0.1 * a;
    A[(3 * c) * n + 3 * c + 1] = A[(3 * c + 1) * n + 3 * c] = 0.2;
    if (c + 1 < nc)
      for (int a = 0; a < 3; ++a) A[(3 * c + a) * n + 3 * (c + 1) + a] = A[(3 * (c + 1) + a) * n + 3 * c + a] = -0.3;
  }
  return manufactured(A, nc);
}

// Every contact coupled to every other (W full, as W = H'M^-1 H of a body
// with many contacts): W = 2 I + C, C_ij = 0.4 / (3 + |i - j|) sqrt(1 + (i + j)
// mod 7) / n, symmetric and diagonally dominant, entries that float does
// not hold exactly.
Chain manufacturedFull(int nc) {
  const int n = 3 * nc;
  std::vector<double> A(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      A[static_cast<size_t>(i) * n + j] =
          (i == j ? 2.0 : 0.0) + 0.4 / (3.0 + std::abs(i - j)) * std::sqrt(1.0 + (i + j) % 7) / n * 10.0;
  return manufactured(A, nc);
}

Chain manufactured(const std::vector<double>& A, int nc) {
  const int n = 3 * nc;
  const LocalCsr W = denseCsr(A, n);
  std::vector<double> rStar(n, 0.0), uStar(n, 0.0), mu(nc);
  for (int c = 0; c < nc; ++c) {
    mu[c] = 0.2 + 0.05 * (c % 4);
    const double angle = 0.7 * c;
    switch (c % 3) {
      case 0:  // open: r = 0, u_N > 0
        uStar[3 * c] = 0.5 + 0.1 * c, uStar[3 * c + 1] = 0.3 * std::cos(angle), uStar[3 * c + 2] = 0.3 * std::sin(angle);
        break;
      case 1:  // stick: u = 0, r strictly inside the cone
        rStar[3 * c] = 1.0 + 0.1 * c, rStar[3 * c + 1] = 0.5 * mu[c] * rStar[3 * c] * std::cos(angle),
        rStar[3 * c + 2] = 0.5 * mu[c] * rStar[3 * c] * std::sin(angle);
        break;
      default: {  // slip: u_N = 0, r_T = -mu r_N u_T / ||u_T||
        const double rN = 0.8 + 0.05 * c, uT = 0.4;
        rStar[3 * c] = rN;
        uStar[3 * c + 1] = uT * std::cos(angle), uStar[3 * c + 2] = uT * std::sin(angle);
        rStar[3 * c + 1] = -mu[c] * rN * std::cos(angle), rStar[3 * c + 2] = -mu[c] * rN * std::sin(angle);
      }
    }
  }
  std::vector<double> Wr(n), q(n);
  W.multiply(rStar.data(), Wr.data());
  for (int i = 0; i < n; ++i) q[i] = uStar[i] - Wr[i];
  return {W, q, mu, rStar};
}

}  // namespace

TEUCHOS_UNIT_TEST(NSGS, OneContactClosedForm) {
  const double w = 2.0, mu = 0.5;
  const LocalCsr W = denseCsr({w, 0, 0, 0, w, 0, 0, 0, w}, 3);
  struct Case {
    const char* name;
    std::vector<double> q, r;
  };
  const double slipN = 4.0 / w;  // q_N = -4, ||q_T|| = 5 > mu |q_N| = 2
  const std::vector<Case> cases = {
      {"take-off", {1.0, 3.0, -2.0}, {0, 0, 0}},
      {"grazing", {0.0, 3.0, -2.0}, {0, 0, 0}},
      {"stick", {-4.0, 0.6, -0.8}, {2.0, -0.3, 0.4}},
      {"slip", {-4.0, 3.0, -4.0}, {slipN, -mu * slipN * 0.6, mu * slipN * 0.8}},
  };
  for (const auto& c : cases) {
    const Solved s = solveNsgs(W, c.q, {mu});
    out << c.name << ": r = (" << s.r[0] << ", " << s.r[1] << ", " << s.r[2] << "), " << s.status.reason << "\n";
    TEST_ASSERT(s.status.converged);
    for (int i = 0; i < 3; ++i) TEST_COMPARE(std::abs(s.r[i] - c.r[i]), <=, 1e-13);
  }
}

TEUCHOS_UNIT_TEST(NSGS, OneContactFullBlockSlip) {
  // W_cc symmetric positive definite with normal-tangential coupling, q
  // pushing hard sideways: the contact slides, found by the local Newton.
  const LocalCsr W = denseCsr({3.0, 0.4, -0.2, 0.4, 2.0, 0.3, -0.2, 0.3, 1.5}, 3);
  const std::vector<double> q = {-2.0, 5.0, 3.0}, mu = {0.3};
  const Solved s = solveNsgs(W, q, mu);
  const auto u = velocities(W, s.r, q);
  const double R = std::max({std::abs(s.r[0]), std::abs(s.r[1]), std::abs(s.r[2])});
  const double U = std::max({std::abs(u[0]), std::abs(u[1]), std::abs(u[2]), 5.0});
  out << "r = (" << s.r[0] << ", " << s.r[1] << ", " << s.r[2] << "), u = (" << u[0] << ", " << u[1] << ", " << u[2]
      << "), local Newton steps " << s.status.inner_iterations << "\n";
  TEST_ASSERT(s.status.converged);
  TEST_COMPARE(s.status.inner_iterations, >, 0);           // the slip case ran Newton
  TEST_COMPARE(std::hypot(u[1], u[2]), >, 1e-3 * U);        // and the contact slides
  TEST_COMPARE(coulombViolation(s.r, u, mu[0], 0, R, U), <=, 1e-12);
}

// A chain of nc contacts, W = tridiagonal blocks (SPD): block c couples to
// c +- 1 by -0.3 I, diagonal blocks 2 I + a symmetric coupling. The solution
// is manufactured: r* chosen contact by contact (open, stick, slip), u* with
// matching complementarity, q = u* - W r*.
TEUCHOS_UNIT_TEST(NSGS, ManufacturedChain) {
  const Chain chain = manufacturedChain();
  const LocalCsr& W = chain.W;
  const std::vector<double>&q = chain.q, &mu = chain.mu, &rStar = chain.rStar;
  const int n = static_cast<int>(q.size());
  const Solved s = solveNsgs(W, q, mu, 1e-13);
  out << s.status.reason << ", sweeps " << s.status.outer_iterations << "\n";
  TEST_ASSERT(s.status.converged);
  double dr = 0, du = 0;
  const auto u = velocities(W, s.r, q);
  for (int i = 0; i < n; ++i) dr = std::max(dr, std::abs(s.r[i] - rStar[i])), du = std::max(du, std::abs(s.u[i] - u[i]));
  out << "max |r - r*| " << dr << ", max |u_returned - (W r + q)| " << du << "\n";
  TEST_COMPARE(dr, <=, 1e-10);
  TEST_COMPARE(du, <=, 1e-14);
  // More sweeps than the blocked copy's threshold (8): both storages ran.
  TEST_COMPARE(s.status.outer_iterations, >, 8);
}

// W full (every contact coupled): after 8 sweeps NSGS reads W from float
// rows (half the bytes per sweep) and corrects q by the exact W until the
// exact W meets the tolerance. The manufactured r* is recovered to 1e-10 and
// u = W r + q with the exact W, where the float rows alone (W within 6e-8
// of W's entries) would leave r about 1e-8 off.
TEUCHOS_UNIT_TEST(NSGS, ManufacturedFullW) {
  const Chain full = manufacturedFull(40);
  const int n = static_cast<int>(full.q.size());
  const Solved s = solveNsgs(full.W, full.q, full.mu, 1e-13);
  out << s.status.reason << ", sweeps " << s.status.outer_iterations << "\n";
  TEST_ASSERT(s.status.converged);
  double dr = 0, du = 0;
  const auto u = velocities(full.W, s.r, full.q);
  for (int i = 0; i < n; ++i)
    dr = std::max(dr, std::abs(s.r[i] - full.rStar[i])), du = std::max(du, std::abs(s.u[i] - u[i]));
  out << "max |r - r*| " << dr << ", max |u_returned - (W r + q)| " << du << "\n";
  TEST_COMPARE(dr, <=, 1e-10);
  TEST_COMPARE(du, <=, 1e-13);
  TEST_COMPARE(s.status.outer_iterations, >, 8);
}

TEUCHOS_UNIT_TEST(NSGS, StoppingMeasureAndLimits) {
  const LocalCsr W = denseCsr({2, 0, 0, 0, 2, 0, 0, 0, 2}, 3);
  const std::vector<double> q = {-4.0, 3.0, -4.0}, mu = {0.5};
  Teuchos::ParameterList pl;
  NonsmoothGaussSeidel nsgs(pl);
  int calls = 0;
  nsgs.setStoppingMeasure([&](const std::vector<double>&, const std::vector<double>&) {
    ++calls;
    return 1.0;  // never met
  });
  nsgs.setMaximumIterations(3);
  std::vector<double> r(3, 0.0), u;
  const auto st = nsgs.solve(ExplicitCoulombProblem{W.view(), q.data(), mu.data(), 1}, r, u);
  TEST_ASSERT(!st.converged);
  TEST_EQUALITY(st.outer_iterations, 3);
  TEST_COMPARE(calls, >=, 2);  // after the settled sweep and after the last
  TEST_ASSERT(st.reason.find("Maximum Iterations (3) of NSGS") != std::string::npos);
  TEST_THROW(nsgs.setRequestedTolerance(0.0), std::exception);
  TEST_THROW(nsgs.setMaximumIterations(0), std::exception);
  Friction::ContactDual dual;
  Vector x(rcp(new Map(3, 0, Tpetra::getDefaultComm())));
  TEST_THROW(nsgs.solve(dual, x), std::exception);  // the FETI dual is refused
}

// Finite termination: two uncoupled contacts, one stuck and one opening,
// are solved exactly by the first sweep; the second changes no force, so
// its velocities are u = W r + q and no further pass over W is made
// (n_A counts the two sweeps only). The returned u is W r + q all the same.
TEUCHOS_UNIT_TEST(NSGS, UnchangedSweepGivesVelocities) {
  std::vector<double> A(36, 0.0);
  for (int i = 0; i < 6; ++i) A[i * 6 + i] = 2.0;
  A[0 * 6 + 1] = A[1 * 6 + 0] = 0.5;  // contact 0's block is not diagonal
  const LocalCsr W = denseCsr(A, 6);
  const std::vector<double> q = {-4.0, 0.1, 0.0, 3.0, 1.0, -1.0}, mu = {0.8, 0.3};
  const Solved s = solveNsgs(W, q, mu);
  out << s.status.reason << ", sweeps " << s.status.outer_iterations << ", n_A " << s.status.n_A << "\n";
  TEST_ASSERT(s.status.converged);
  TEST_EQUALITY(s.status.outer_iterations, 2);
  TEST_EQUALITY(s.status.n_A, 2L);
  TEST_COMPARE(s.r[0], >, 0.0);                                     // contact 0 pressed (and stuck)
  TEST_ASSERT(s.r[3] == 0.0 && s.r[4] == 0.0 && s.r[5] == 0.0);     // contact 1 opens
  const std::vector<double> u = velocities(W, s.r, q);
  for (int i = 0; i < 6; ++i) TEST_FLOATING_EQUALITY(s.u[i] + 10.0, u[i] + 10.0, 1e-14);
  for (int c = 0; c < 2; ++c) TEST_COMPARE(coulombViolation(s.r, s.u, mu[c], c, 4.0, 4.0), <=, 1e-14);
}

// From r = 0 the measure is taken before any sweep only when r = 0 can be
// the solution (every q_N >= 0): then no sweep is made. Otherwise the first
// measure comes after a sweep.
TEUCHOS_UNIT_TEST(NSGS, InitialMeasureOnlyWhenZeroCanSolve) {
  const LocalCsr W = denseCsr({2, 0, 0, 0, 2, 0, 0, 0, 2}, 3);
  const std::vector<double> mu = {0.5};
  for (const double qN : {1.0, -1.0}) {
    const std::vector<double> q = {qN, 3.0, -4.0};
    Teuchos::ParameterList pl;
    NonsmoothGaussSeidel nsgs(pl);
    std::vector<int> measuredAfter;
    int sweepsSeen = 0;
    nsgs.setStoppingMeasure([&](const std::vector<double>& r, const std::vector<double>& u) {
      measuredAfter.push_back(sweepsSeen++);
      double e = 0;
      for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(u[i] - (2.0 * r[i] + q[i])));
      return e;  // 0 once u = W r + q: stops at the first measure
    });
    std::vector<double> r(3, 0.0), u;
    const auto st = nsgs.solve(ExplicitCoulombProblem{W.view(), q.data(), mu.data(), 1}, r, u);
    TEST_ASSERT(st.converged);
    TEST_EQUALITY(measuredAfter.size(), size_t(1));
    TEST_EQUALITY(st.outer_iterations, qN >= 0 ? 0 : 2);  // open: r = 0 at once; pressed: a sweep, then the light test
    if (qN >= 0) TEST_ASSERT(r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0);
  }
}

// Warm starts with forces where the solution has none, on one contact only,
// or the solution itself: NSGS skips a contact's rows only while no contact
// carries a force, a count kept through the sweeps as forces appear and
// vanish. Every start must reach r* with u = W r + q.
TEUCHOS_UNIT_TEST(NSGS, WarmStartsWithForcesAppearingAndVanishing) {
  const Chain chain = manufacturedChain();
  const int nc = static_cast<int>(chain.mu.size()), n = 3 * nc;
  std::vector<std::pair<const char*, std::vector<double>>> starts;
  starts.push_back({"zero", std::vector<double>(n, 0.0)});
  std::vector<double> onOpen(n, 0.0);  // forces on the contacts that open, none elsewhere
  for (int c = 0; c < nc; c += 3) onOpen[3 * c] = 1.0 + c, onOpen[3 * c + 1] = 0.1;
  starts.push_back({"forces on the open contacts only", onOpen});
  std::vector<double> onLast(n, 0.0);
  onLast[3 * (nc - 1)] = 2.0;
  starts.push_back({"a force on the last contact only", onLast});
  starts.push_back({"the solution", chain.rStar});
  for (const auto& [name, r0] : starts) {
    Teuchos::ParameterList pl;
    pl.set("Relative Tolerance", 1e-13);
    NonsmoothGaussSeidel nsgs(pl);
    std::vector<double> r = r0, u;
    const auto st = nsgs.solve(
        ExplicitCoulombProblem{chain.W.view(), chain.q.data(), chain.mu.data(), nc}, r, u);
    const auto Wr = velocities(chain.W, r, chain.q);
    double dr = 0, du = 0;
    for (int i = 0; i < n; ++i)
      dr = std::max(dr, std::abs(r[i] - chain.rStar[i])), du = std::max(du, std::abs(u[i] - Wr[i]));
    out << name << ": " << st.reason << ", max |r - r*| " << dr << ", max |u - (W r + q)| " << du << "\n";
    TEST_ASSERT(st.converged);
    TEST_COMPARE(dr, <=, 1e-10);
    TEST_COMPARE(du, <=, 1e-14);
  }
}
