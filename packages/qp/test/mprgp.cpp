// mprgp.cpp: MPRGP on random SPD problems with bounds, distributed on 1 or 2
// ranks, against rank-independent dense references computed here:
// enumeration of active sets (n <= 8), projected gradient to 1e-15 (n = 40),
// and the unconstrained solve A x = b when no bound is active. Also: KKT of
// every solution, exact count of Hessian applications, projection of an
// infeasible start, the non-SPD and circle errors, and the iteration limit.
#include <Teuchos_ParameterList.hpp>

#include "QPTestUtils.hpp"
#include "Tribos_QP_MPRGP.hpp"

using namespace qptest;
using namespace Tribos::QP;

// 1. lower bounds, n = 8, several seeds: exact solution by enumeration
TEUCHOS_UNIT_TEST(MPRGP, LowerBoundsEnumerated) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    const int n = 8;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -1, 1);
    SetSpec s{"LLLLLLFL", randomVec(n, 200 + seed, -0.3, 0.1), Vec(n, inf), {}};
    s.lo[6] = -inf;
    Vec xref, mu;
    TEST_ASSERT(enumerateActiveSets(A, b, s.lo, s.up, {}, xref, mu));  // enumeration found the solution
    MPRGP solver(params(1e-11));
    Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
    const std::string name = "lower bounds seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    double err = 0;
    for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r.x[i] - xref[i]));
    TEST_COMPARE(err, <, 1e-8);  // |x - x_enum|
    const double kkt = kktViolation(s, r.x, gradient(A, b, r.x));
    TEST_COMPARE(kkt, <, 1e-9);  // KKT violation
    checkCounts(r, Tribos::QP::kNormSteps, name, out, success);
  }
}

// 2. boxes, n = 6: enumeration over free / lower / upper
TEUCHOS_UNIT_TEST(MPRGP, BoxesEnumerated) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 11; seed <= 13; ++seed) {
    const int n = 6;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -2, 2);
    SetSpec s{"BBBBBB", Vec(n, -0.2), Vec(n, 0.3), {}};
    Vec xref, mu;
    TEST_ASSERT(enumerateActiveSets(A, b, s.lo, s.up, {}, xref, mu));  // box enumeration found the solution
    MPRGP solver(params(1e-11));
    Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
    const std::string name = "box seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    double err = 0;
    for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r.x[i] - xref[i]));
    TEST_COMPARE(err, <, 1e-8);  // |x - x_enum|
    TEST_COMPARE(kktViolation(s, r.x, gradient(A, b, r.x)), <, 1e-9);  // KKT
    checkCounts(r, Tribos::QP::kNormSteps, name, out, success);
  }
}

// 3. n = 40, mix of lower, box and free, given ||A|| bound: projected-gradient reference
TEUCHOS_UNIT_TEST(MPRGP, MixedBoundsProjectedGradient) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 40;
  Dense A = randomSPD(n, 21);
  Vec b = randomVec(n, 22, -1, 1);
  SetSpec s{std::string(n, 'F'), randomVec(n, 23, -0.5, 0.0), Vec(n, inf), {}};
  Vec up = randomVec(n, 24, 0.05, 0.5);
  for (int i = 0; i < n; ++i) {
    s.kind[i] = "LLBF"[i % 4];
    if (s.kind[i] == 'B') s.up[i] = up[i];
    if (s.kind[i] == 'F') s.lo[i] = -inf;
  }
  const Vec xref = projectedGradientReference(A, b, s, Vec(n, 0.0));
  double normF = 0;
  for (double v : A.a) normF += v * v;
  MPRGP solver(params(1e-11));
  solver.setHessianNorm(std::sqrt(normF));  // ||A||_F >= ||A||_2
  Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
  TEST_ASSERT(r.st.converged);  // n=40 mix: converged
  double err = 0;
  for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r.x[i] - xref[i]));
  TEST_COMPARE(err, <, 1e-8);  // n=40 mix: |x - x_PG|
  TEST_COMPARE(kktViolation(s, r.x, gradient(A, b, r.x)), <, 1e-9);  // n=40 mix: KKT
  TEST_COMPARE(r.st.expansion_steps + r.st.proportioning_steps, >, 0);  // n=40 mix: the active set changed (a real test)
  checkCounts(r, 0, "n=40 mix (no power iterations)", out, success);
}

// 4. inactive bounds: the CG solution, by CG steps only
TEUCHOS_UNIT_TEST(MPRGP, InactiveBoundsCG) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 20;
  Dense A = randomSPD(n, 31);
  Vec b = randomVec(n, 32, -1, 1);
  SetSpec s{std::string(n, 'L'), Vec(n, -1e3), Vec(n, inf), {}};
  const Vec xref = denseSolve(A, b);
  MPRGP solver(params(1e-12));
  Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
  double err = 0;
  for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r.x[i] - xref[i]));
  TEST_ASSERT(r.st.converged);
  TEST_COMPARE(err, <, 1e-9);  // inactive bounds: x = A^-1 b
  TEST_EQUALITY(r.st.expansion_steps, 0);
  TEST_EQUALITY(r.st.proportioning_steps, 0);  // inactive bounds: only CG steps
  TEST_COMPARE(r.st.cg_steps, <=, n + 5);  // inactive bounds: CG finite termination
  checkCounts(r, Tribos::QP::kNormSteps, "inactive bounds", out, success);
}

// 5. infeasible start: projected first (0 iterations returns P(x0)), then solved
TEUCHOS_UNIT_TEST(MPRGP, InfeasibleStart) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 8;
  Dense A = randomSPD(n, 41);
  Vec b = randomVec(n, 42, -1, 1);
  SetSpec s{"LLLLBBBB", Vec(n, 0.0), Vec(n, inf), {}};
  for (int i = 4; i < 8; ++i) s.up[i] = 0.5;
  Vec x0 = {-3, 2, -1, 0.5, -7, 9, 0.25, -0.1};
  Vec px0 = x0;
  denseProject(s, px0, x0);
  MPRGP zero(params(1e-11, 0));
  Run r0 = solve(zero, comm, A, b, s, x0);
  double err = 0;
  for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r0.x[i] - px0[i]));
  TEST_EQUALITY(err, 0);  // infeasible start: projected
  TEST_ASSERT(!r0.st.converged);
  TEST_INEQUALITY(r0.st.reason.find("Maximum Iterations"), std::string::npos);  // Maximum Iterations = 0: not converged with reason
  Vec xref, mu;
  enumerateActiveSets(A, b, s.lo, s.up, {}, xref, mu);
  MPRGP solver(params(1e-11));
  Run r = solve(solver, comm, A, b, s, x0);
  err = 0;
  for (int i = 0; i < n; ++i) err = std::max(err, std::abs(r.x[i] - xref[i]));
  TEST_ASSERT(r.st.converged);
  TEST_COMPARE(err, <, 1e-8);  // infeasible start: solution
}

// 6. iteration limit on a larger problem: not converged, with reason
TEUCHOS_UNIT_TEST(MPRGP, IterationLimit) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 40;
  Dense A = randomSPD(n, 51, 0.01);
  Vec b = randomVec(n, 52, -1, 1);
  SetSpec s{std::string(n, 'L'), Vec(n, 0.0), Vec(n, inf), {}};
  MPRGP solver(params(1e-12, 3));
  Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
  TEST_ASSERT(!r.st.converged);
  TEST_EQUALITY(r.st.iterations, 3);
  TEST_ASSERT(!r.st.reason.empty());  // iteration limit
}

// 7. errors: indefinite Hessian, circles
TEUCHOS_UNIT_TEST(MPRGP, Errors) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 6;
  Dense A{n, Vec(n * n, 0.0)};
  for (int i = 0; i < n; ++i) A(i, i) = i % 2 ? -2.0 : 1.0;
  SetSpec s{std::string(n, 'L'), Vec(n, -10.0), Vec(n, inf), {}};
  MPRGP solver(params(1e-10));
  std::string msg;
  TEST_ASSERT(throwsWith([&] { solve(solver, comm, A, Vec(n, 1.0), s, Vec(n, 0.0)); }, "not positive definite", &msg));  // indefinite Hessian: Tribos::Error naming it
  SetSpec c{"CCCCLL", Vec(n, 0.0), Vec(n, inf), {1.0, 1.0, 1.0}};
  TEST_ASSERT(throwsWith([&] { solve(solver, comm, randomSPD(n, 3), Vec(n, 1.0), c, Vec(n, 0.0)); }, "circles", &msg));  // MPRGP with circles: error naming them
}
