// smalbe.cpp: SMALBE for G x = 0 plus bounds / disks on 1 or 2 ranks:
// against the exact solution (x, mu) from enumerating active sets of the KKT
// system with equality rows (explicit CrsEqualityConstraint); KKT of the
// returned (x, mu) with an orthonormal G given as a user subclass and
// disks + bounds (MPGP inner); exact n_A through the augmented Hessian; warm
// restart from (x, mu) converges in one outer iteration with a plugged-in
// inner solver; an inconsistent set {Gx = 0, x >= 1} ends with converged =
// false and a reason in bounded time; MPRGP inner with disks is an error.
#include <chrono>
#include <cstdlib>

#include <Teuchos_ParameterList.hpp>

#include "QPTestUtils.hpp"
#include "Tribos_QP_Factory.hpp"
#include "Tribos_QP_MPRGP.hpp"
#include "Tribos_QP_SMALBE.hpp"

using namespace qptest;
using namespace Tribos::QP;

namespace {

// G with rows given densely, coarse vectors replicated on every rank.
class DenseRowsConstraint : public EqualityConstraint {
 public:
  DenseRowsConstraint(const std::vector<Vec>& rows, RCP<const Map> xmap)
      : rows_(rows), xmap_(xmap),
        cmap_(rcp(new Map(rows.size(), 0, xmap->getComm(), Tpetra::LocallyReplicated))) {}
  RCP<const Map> rangeMap() const override { return cmap_; }
  void apply(const Vector& x, Vector& Gx) const override {
    auto xv = x.getData();
    Vec part(rows_.size(), 0.0), sum(rows_.size(), 0.0);
    for (size_t j = 0; j < rows_.size(); ++j)
      for (LO l = 0; l < static_cast<LO>(xv.size()); ++l) part[j] += rows_[j][xmap_->getGlobalElement(l)] * xv[l];
    Teuchos::reduceAll(*xmap_->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(part.size()), part.data(), sum.data());
    auto gv = Gx.getDataNonConst();
    for (size_t j = 0; j < sum.size(); ++j) gv[j] = sum[j];
  }
  void applyTranspose(const Vector& y, Vector& Gty) const override {
    auto yv = y.getData();
    auto tv = Gty.getDataNonConst();
    for (LO l = 0; l < static_cast<LO>(tv.size()); ++l) {
      tv[l] = 0;
      for (size_t j = 0; j < rows_.size(); ++j) tv[l] += rows_[j][xmap_->getGlobalElement(l)] * yv[j];
    }
  }

 private:
  std::vector<Vec> rows_;
  RCP<const Map> xmap_, cmap_;
};

RCP<const CrsMatrix> crsRows(const std::vector<Vec>& rows, const RCP<const Map>& xmap) {
  const int m = static_cast<int>(rows.size()), n = static_cast<int>(rows[0].size());
  auto rowMap = rcp(new Map(static_cast<Tpetra::global_size_t>(m), 0, xmap->getComm()));
  auto G = rcp(new CrsMatrix(rowMap, n));
  std::vector<GO> cols(n);
  for (int j = 0; j < n; ++j) cols[j] = j;
  for (size_t l = 0; l < rowMap->getNodeNumElements(); ++l) {
    const GO r = rowMap->getGlobalElement(l);
    G->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(rows[r]));
  }
  G->fillComplete(xmap, rowMap);
  return G;
}

// L(x) gradient A x - b + G' mu, densely
Vec lagrangianGradient(const Dense& A, const Vec& b, const std::vector<Vec>& G, const Vec& x, const Vec& mu) {
  Vec g = gradient(A, b, x);
  for (size_t j = 0; j < G.size(); ++j)
    for (size_t i = 0; i < g.size(); ++i) g[i] += G[j][i] * mu[j];
  return g;
}

double normGx(const std::vector<Vec>& G, const Vec& x) {
  double s = 0;
  for (const Vec& r : G) s += dot(r, x) * dot(r, x);
  return std::sqrt(s);
}

RCP<Teuchos::ParameterList> smalbeParams(double rtol, const std::string& inner) {
  auto p = Teuchos::rcp(new Teuchos::ParameterList);
  p->set("Relative Tolerance", rtol);
  p->sublist("Inner Solver").set("Type", inner);
  if (const char* v = std::getenv("QP_TEST_VERBOSITY")) p->set("Verbosity", std::string(v));
  return p;
}

struct SmalbeRun {
  QPStatus st;
  Vec x, mu;
  long counted = 0;
};

SmalbeRun solve(SMALBE& solver, const RCP<const Comm>& comm, const Dense& A, const Vec& b, const SetSpec& s,
          const std::vector<Vec>& G, bool explicitG, const Vec& x0, const Vec* mu0 = nullptr) {
  auto map = pairMap(A.n, comm);
  CountingOperator Aop(toCrs(map, A));
  auto bv = toVector(map, b);
  auto x = toVector(map, x0);
  ConstraintSet Omega = makeSet(map, s);
  RCP<const EqualityConstraint> Gc;
  if (explicitG) Gc = rcp(new CrsEqualityConstraint(crsRows(G, map)));
  else Gc = rcp(new DenseRowsConstraint(G, map));
  solver.setEqualityConstraint(Gc);
  if (mu0) solver.setMultiplier(*toVector(Gc->rangeMap(), *mu0));
  SmalbeRun r;
  r.st = solver.solve(Aop, *bv, Omega, *x);
  r.x = gather(*x);
  r.mu = gather(solver.multiplier());
  r.counted = Aop.count;
  return r;
}


}  // namespace

// 1. bounds + 2 equality rows (explicit G): exact (x, mu) by enumeration
TEUCHOS_UNIT_TEST(SMALBE, BoundsAndEqualityEnumerated) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const int n = 8;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -1, 1);
    SetSpec s{"LLLLLLFF", randomVec(n, 200 + seed, -0.3, 0.0), Vec(n, inf), {}};
    s.lo[6] = s.lo[7] = -inf;
    std::vector<Vec> G = {randomVec(n, 300 + seed, -1, 1), randomVec(n, 400 + seed, -1, 1)};
    Vec xref, muref;
    TEST_ASSERT(enumerateActiveSets(A, b, s.lo, s.up, G, xref, muref));  // enumeration with G found the solution
    SMALBE solver(smalbeParams(1e-10, "MPRGP"));
    SmalbeRun r = solve(solver, comm, A, b, s, G, true, Vec(n, 0.0));
    const std::string name = "SMALBE bounds seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    TEST_COMPARE(maxDiff(r.x, xref), <, 1e-7);  // |x - x_enum|
    TEST_COMPARE(maxDiff(r.mu, muref), <, 1e-6);  // |mu - mu_enum|
    const double kkt = kktViolation(s, r.x, lagrangianGradient(A, b, G, r.x, r.mu));
    TEST_COMPARE(kkt, <, 1e-8);  // KKT violation
    TEST_COMPARE(normGx(G, r.x), <, 1e-9);  // ||Gx||
    TEST_EQUALITY(r.counted, r.st.n_A);  // n_A
    TEST_COMPARE(r.st.outer_iterations, >=, 1);  // outer iterations reported

    // warm restart from (x, mu) with a plugged-in inner solver: one outer iteration
    if (seed == 1) {
      SMALBE warm(smalbeParams(1e-8, "MPRGP"));
      warm.setInnerSolver(rcp(new MPRGP()));
      SmalbeRun w = solve(warm, comm, A, b, s, G, true, r.x, &r.mu);
      TEST_ASSERT(w.st.converged);
      TEST_EQUALITY(w.st.outer_iterations, 1);  // warm restart converges in 1 outer iteration
      TEST_COMPARE(maxDiff(w.x, xref), <, 1e-7);  // warm restart keeps the solution
    }
  }
}

// 2. disks + bounds + orthonormal G as a user subclass, MPGP inner: KKT of (x, mu)
TEUCHOS_UNIT_TEST(SMALBE, DisksAndUserG) {
  auto comm = Tpetra::getDefaultComm();
  for (uint32_t seed = 5; seed <= 6; ++seed) {
    const int n = 16;
    Dense A = randomSPD(n, seed);
    Vec b = randomVec(n, 100 + seed, -1, 1);
    SetSpec s{"CCCCCCCCLLLLFFFF", Vec(n, 0.0), Vec(n, inf), randomVec(n / 2, 500 + seed, 0.05, 0.4)};
    for (int i = 12; i < 16; ++i) s.lo[i] = -inf;
    std::vector<Vec> G = {randomVec(n, 600 + seed, -1, 1), randomVec(n, 700 + seed, -1, 1), randomVec(n, 800 + seed, -1, 1)};
    for (size_t j = 0; j < G.size(); ++j) {  // Gram-Schmidt: G G' = I
      for (size_t k = 0; k < j; ++k) {
        const double c = dot(G[j], G[k]);
        for (int i = 0; i < n; ++i) G[j][i] -= c * G[k][i];
      }
      const double nr = std::sqrt(dot(G[j], G[j]));
      for (double& v : G[j]) v /= nr;
    }
    SMALBE solver(smalbeParams(1e-9, "MPGP"));
    SmalbeRun r = solve(solver, comm, A, b, s, G, false, Vec(n, 0.0));
    const std::string name = "SMALBE disks seed " + std::to_string(seed);
    out << name << "\n";
    TEST_ASSERT(r.st.converged);  // converged
    const double tolAbs = 1e-9 * std::sqrt(dot(b, b));
    const double kkt = kktViolation(s, r.x, lagrangianGradient(A, b, G, r.x, r.mu), 1e-7);
    TEST_COMPARE(kkt, <, 10 * tolAbs);  // KKT violation
    TEST_COMPARE(normGx(G, r.x), <=, tolAbs);  // ||Gx||
    TEST_EQUALITY(r.counted, r.st.n_A);  // n_A counted exactly
    // the same problem by the explicit matrix gives the same solution
    SMALBE solver2(smalbeParams(1e-9, "MPGP"));
    SmalbeRun r2 = solve(solver2, comm, A, b, s, G, true, Vec(n, 0.0));
    TEST_COMPARE(maxDiff(r.x, r2.x), <, 1e-7);  // explicit and user G agree
  }
}

// 3. inconsistent: sum x = 0 with x_i >= 1
TEUCHOS_UNIT_TEST(SMALBE, InconsistentSet) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 6;
  Dense A = randomSPD(n, 71);
  Vec b = randomVec(n, 72, -1, 1);
  SetSpec s{std::string(n, 'L'), Vec(n, 1.0), Vec(n, inf), {}};
  std::vector<Vec> G = {Vec(n, 1.0)};
  SMALBE solver(smalbeParams(1e-8, "MPRGP"));
  const auto t0 = std::chrono::steady_clock::now();
  SmalbeRun r = solve(solver, comm, A, b, s, G, true, Vec(n, 1.0));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  TEST_ASSERT(!r.st.converged);
  TEST_ASSERT(!r.st.reason.empty());  // inconsistent set: not converged, reason
  TEST_COMPARE(secs, <, 20);  // the inconsistent set is detected within 20 s
  out << "inconsistent set: " << r.st << "\n";
}

// 4. MPRGP as inner solver with disks: error naming the circles
TEUCHOS_UNIT_TEST(SMALBE, Errors) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 4;
  SetSpec s{"CCCC", {}, {}, {1.0, 1.0}};
  SMALBE solver(smalbeParams(1e-8, "MPRGP"));
  std::string msg;
  TEST_ASSERT(throwsWith([&] { solve(solver, comm, randomSPD(n, 2), Vec(n, 1.0), s, {Vec(n, 1.0)}, true, Vec(n, 0.0)); }, "circles", &msg));  // SMALBE with MPRGP inner and disks
  SMALBE noG;
  auto map = pairMap(n, comm);
  Vector x(map), bb(map);
  ConstraintSet Omega(map);
  TEST_ASSERT(throwsWith([&] { noG.solve(*toCrs(map, randomSPD(n, 2)), bb, Omega, x); }, "setEqualityConstraint"));  // SMALBE without G
}
