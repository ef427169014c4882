// mpgp.cpp: MPGP on random SPD problems with disks (friction), and with mixes
// of disks, bounds, fixed and free components, on 1 or 2 ranks, against a
// dense projected-gradient reference computed here (rank independent); KKT of
// every solution (disk multipliers lambda >= 0, tangential gradient 0), exact
// n_A, radius 0, inactive disks = A^-1 b, infeasible start, and the
// fixedOutside blocks used by block Gauss-Seidel (MPGP on the disks with the
// bounds frozen, MPRGP on the bounds with the disks frozen).
#include <Teuchos_ParameterList.hpp>

#include "QPTestUtils.hpp"
#include "Tribos_QP_MPGP.hpp"
#include "Tribos_QP_MPRGP.hpp"

using namespace qptest;
using namespace Tribos::QP;

namespace {

int countActiveCircles(const SetSpec& s, const Vec& x) {
  int k = 0;
  for (int i = 0; i < s.n(); i += 2)
    if (s.kind[i] == 'C' && std::hypot(x[i], x[i + 1]) > s.r[i / 2] * (1 - 1e-8)) ++k;
  return k;
}

}  // namespace

// 1. disks only: 6 circles, random radii, some active, some not
TEUCHOS_UNIT_TEST(MPGP, DisksProjectedGradient) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const int n = 12;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -0.4, 0.4);
    SetSpec s{std::string(n, 'C'), {}, {}, randomVec(n / 2, 300 + seed, 0.05, 0.8)};
    const Vec xref = projectedGradientReference(A, b, s, Vec(n, 0.0));
    MPGP solver(params(1e-11));
    Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
    const std::string name = "disks seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    TEST_COMPARE(maxDiff(r.x, xref), <, 1e-8);  // |x - x_PG|
    TEST_COMPARE(kktViolation(s, r.x, gradient(A, b, r.x)), <, 1e-9);  // KKT
    const int active = countActiveCircles(s, xref);
    TEST_COMPARE(active, >, 0);
    TEST_COMPARE(active, <, n / 2);  // reference has active and inactive disks
    checkCounts(r, Tribos::QP::kNormSteps, name, out, success);
  }
}

// 2. mix: disks, lower bounds, boxes, free, fixed, and a disk of radius 0
TEUCHOS_UNIT_TEST(MPGP, MixedSetsProjectedGradient) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 7; seed <= 8; ++seed) {
    const int n = 20;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -1.5, 1.5);
    SetSpec s{"CCCCCCCCLLLLBBBBFFXX", randomVec(n, 400 + seed, -0.3, 0.0), randomVec(n, 500 + seed, 0.05, 0.3),
              randomVec(n / 2, 300 + seed, 0.05, 0.5)};
    s.r[1] = 0.0;
    Vec x0(n, 0.0);
    x0[18] = 0.25;  // fixed components keep their start values
    x0[19] = -0.5;
    const Vec xref = projectedGradientReference(A, b, s, x0);
    MPGP solver(params(1e-11));
    Run r = solve(solver, comm, A, b, s, x0);
    const std::string name = "mix seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    TEST_COMPARE(maxDiff(r.x, xref), <, 1e-8);  // |x - x_PG|
    SetSpec sk = s;  // KKT on the non-fixed part: fixed entries carry any gradient
    TEST_COMPARE(kktViolation(sk, r.x, gradient(A, b, r.x)), <, 1e-9);  // KKT
    TEST_EQUALITY(r.x[2], 0);
    TEST_EQUALITY(r.x[3], 0);  // radius 0 keeps the pair at 0
    TEST_EQUALITY(r.x[18], 0.25);
    TEST_EQUALITY(r.x[19], -0.5);  // fixed entries unchanged
    checkCounts(r, Tribos::QP::kNormSteps, name, out, success);
  }
}

// 3. inactive disks: the unconstrained solution, by CG steps only
TEUCHOS_UNIT_TEST(MPGP, InactiveDisks) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 16;
  Dense A = randomSPD(n, 31);
  Vec b = randomVec(n, 32, -1, 1);
  SetSpec s{std::string(n, 'C'), {}, {}, Vec(n / 2, 1e3)};
  const Vec xref = denseSolve(A, b);
  MPGP solver(params(1e-12));
  Run r = solve(solver, comm, A, b, s, Vec(n, 0.0));
  TEST_ASSERT(r.st.converged);
  TEST_COMPARE(maxDiff(r.x, xref), <, 1e-9);  // inactive disks: x = A^-1 b
  TEST_EQUALITY(r.st.expansion_steps, 0);
  TEST_EQUALITY(r.st.proportioning_steps, 0);  // inactive disks: only CG steps
}

// 4. infeasible start is projected onto the disks first
TEUCHOS_UNIT_TEST(MPGP, InfeasibleStart) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 8;
  Dense A = randomSPD(n, 41);
  Vec b = randomVec(n, 42, -1, 1);
  SetSpec s{"CCCCLLBB", Vec(n, 0.0), Vec(n, 0.5), {0.3, 0.2}};
  Vec x0 = {3, 4, -0.1, 0.1, -2, 1, 7, -7};
  Vec px0 = x0;
  denseProject(s, px0, x0);
  MPGP zero(params(1e-11, 0));
  Run r0 = solve(zero, comm, A, b, s, x0);
  TEST_COMPARE(maxDiff(r0.x, px0), <, 1e-15);  // MPGP infeasible start projected
  TEST_ASSERT(!r0.st.converged);
  TEST_ASSERT(!r0.st.reason.empty());  // Maximum Iterations = 0: not converged with reason
  MPGP solver(params(1e-11));
  Run r = solve(solver, comm, A, b, s, x0);
  const Vec xref = projectedGradientReference(A, b, s, x0);
  TEST_ASSERT(r.st.converged);
  TEST_COMPARE(maxDiff(r.x, xref), <, 1e-8);  // MPGP from infeasible start
}

// 5. block Gauss-Seidel pieces via fixedOutside
TEUCHOS_UNIT_TEST(MPGP, FixedOutsideBlocks) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 16;
  Dense A = randomSPD(n, 61);
  Vec b = randomVec(n, 62, -1.5, 1.5);
  SetSpec s{"CCCCCCCCLLLLLLLL", Vec(n, 0.0), Vec(n, inf), randomVec(n / 2, 63, 0.1, 0.4)};
  Vec x0 = {0.05, 0, 0, 0.1, -0.1, 0, 0, 0, 0.2, 0, 0.1, 0.3, 0, 0, 0.05, 0.1};
  std::vector<char> keepDisks(n, 0), keepBounds(n, 0);
  for (int i = 0; i < n; ++i) (s.kind[i] == 'C' ? keepDisks : keepBounds)[i] = 1;
  SetSpec sDisks = s, sBounds = s;  // the frozen blocks as fixed entries of the reference
  for (int i = 0; i < n; ++i) (keepDisks[i] ? sBounds : sDisks).kind[i] = 'X';
  MPGP mpgp(params(1e-11));
  Run rd = solve(mpgp, comm, A, b, s, x0, keepDisks);
  const Vec refD = projectedGradientReference(A, b, sDisks, x0);
  TEST_ASSERT(rd.st.converged);
  TEST_COMPARE(maxDiff(rd.x, refD), <, 1e-8);  // MPGP on the disk block
  TEST_EQUALITY(maxDiff(Vec(rd.x.begin() + 8, rd.x.end()), Vec(x0.begin() + 8, x0.end())), 0);  // bound block frozen
  MPRGP mprgp(params(1e-11));
  Run rb = solve(mprgp, comm, A, b, s, x0, keepBounds);
  const Vec refB = projectedGradientReference(A, b, sBounds, x0);
  TEST_ASSERT(rb.st.converged);
  TEST_COMPARE(maxDiff(rb.x, refB), <, 1e-8);  // MPRGP on the bound block
  TEST_EQUALITY(maxDiff(Vec(rb.x.begin(), rb.x.begin() + 8), Vec(x0.begin(), x0.begin() + 8)), 0);  // disk block frozen
  checkCounts(rb, Tribos::QP::kNormSteps, "MPRGP bound block", out, success);
}
