// friction_test_transforms.cpp: the transform chain (Tribos_DualTransform.hpp)
// on problems with a manufactured solution x*: a transformed problem solved
// and mapped back gives x*, and each transform maps the problem as its
// formula says.
//  - Homogenization by an arbitrary lambda~: the shifted problem (bounds,
//    disk centres, normal-force offsets, b - A lambda~) has the solution
//    x* - lambda~; back adds lambda~.
//  - Scaling of a problem whose ||A|| is 1000 times larger: ||A|| becomes
//    1 (within the estimate's safety factor), b is scaled alike, the
//    solution is x*.
//  - Projection onto ker G: x'PAPx = x'Ax on ker G, PAP G' = 0.
//  - The chain of all three, forward in order and back in reverse.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>

#include "FrictionTestChecks.hpp"
#include "Tribos_DualTransform.hpp"

namespace {

using namespace frictest;
using namespace Tribos;

const std::vector<ContactState> stickSlipSeparated{{true, true, 0.7}, {true, false, 2.5}, {false, false, -1.0}};

// Solves the (transformed) dual by Algorithm 1 from x = 0.
Vec solveDual(const Friction::ContactDual& dual, const RCP<const Map>& map, const Friction::DualTransformChain& chain) {
  auto solver = Friction::FrictionSolverFactory().create("Tresca", solverParameters(solveTolerance));
  Vector x(map);
  const auto status = solver->solve(dual, x);
  TEUCHOS_TEST_FOR_EXCEPTION(!status.converged, std::runtime_error, "the transformed problem did not converge");
  chain.back(x);
  return gather(x);
}

// lambda~ with entries of the solution's size on every row, contact rows included.
Vec particular(int n) {
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = 0.3 * std::sin(1.0 + 2.0 * i);
  return v;
}

TEUCHOS_UNIT_TEST(Transforms, HomogenizationSolutionIsShiftedBack) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  auto d = buildDual(m.problem, Tpetra::getDefaultComm());
  const Vec lt = particular(m.problem.size());
  Friction::DualTransformChain chain;
  chain.add(rcp(new Friction::HomogenizationTransform(toVector(d.map, lt)))).forward(d.dual);
  // The transformed bounds: x_N >= l - lambda~_N; centres c = -lambda~_T.
  for (int k = 0; k < d.dual.numLocalContacts(); ++k) {
    const int K = d.firstContact + k;
    TEST_FLOATING_EQUALITY(d.dual.normalLower[k], m.problem.lower[K] - lt[m.problem.normal(K)], 1e-14);
    TEST_FLOATING_EQUALITY(d.dual.tangentCenter[2 * k], -lt[m.problem.tangential(K, 0)], 1e-14);
  }
  const Vec x = solveDual(d.dual, d.map, chain);
  checkSolution(m.problem, x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

TEUCHOS_UNIT_TEST(Transforms, ScalingMakesNormOneAndKeepsTheSolution) {
  const auto m = manufacture(stickSlipSeparated, ManufacturedOptions());
  const double s = 1000.0;
  Problem big = m.problem;  // A <- s A, b <- s b: the same minimizer
  for (double& a : big.A.a) a *= s;
  for (double& v : big.b) v *= s;
  auto d = buildDual(big, Tpetra::getDefaultComm());
  auto scaling = rcp(new Friction::ScalingTransform(50));
  Friction::DualTransformChain chain;
  const double bBefore = d.dual.b->norm2();
  const auto unscaled = d.dual.A;
  chain.add(scaling).forward(d.dual);
  TEST_FLOATING_EQUALITY(scaling->scale() * scaling->norm(), 1.0, 1e-15);
  // ||A|| of the dense matrix by many power steps: the transform's estimate
  // is the largest Ritz value of its Lanczos steps (from below) times the
  // safety factor 1.1 of QP::estimateNorm, so ||s A|| lies in [0.9, 1].
  Vec v(m.problem.size(), 1.0);
  double normA = 0;
  for (int step = 0; step < 500; ++step) {
    const Vec Av = multiply(m.problem.A, v);
    normA = norm(Av) / norm(v);
    v = Av;
  }
  TEST_COMPARE(scaling->norm(), <=, 1.1 * s * normA * (1 + 1e-10));
  TEST_COMPARE(scaling->norm(), >=, s * normA);
  TEST_FLOATING_EQUALITY(d.dual.b->norm2(), scaling->scale() * bBefore, 1e-12);
  // The solvers take ||s A|| <= 1 from the transform, without power steps;
  // once A is replaced, the estimate no longer counts and is made again.
  long n_A = 0;
  TEST_FLOATING_EQUALITY(d.dual.hessianNorm(20, n_A), 1.0, 1e-15);
  TEST_EQUALITY(n_A, 0L);
  Friction::ContactDual replaced = d.dual;
  replaced.A = unscaled;
  const double again = replaced.hessianNorm(20, n_A);
  TEST_EQUALITY(n_A, static_cast<long>(std::min<size_t>(20, m.problem.size())));  // Lanczos: at most n steps
  TEST_COMPARE(again, >=, s * normA * 0.9);
  TEST_COMPARE(again, <=, 1.1 * s * normA * (1 + 1e-10));
  const Vec x = solveDual(d.dual, d.map, chain);
  checkSolution(m.problem, x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

// The stick/slip/separated problem with `rows` equality rows.
Manufactured withEqualityRows(int rows, unsigned seed) {
  ManufacturedOptions opt;
  opt.equalityRows = rows;
  opt.seed = seed;
  return manufacture(stickSlipSeparated, opt);
}

// P = I - G'(GG')^-1 G on the dense side, as an operator on the test's map.
class DenseProjector : public Operator {
 public:
  DenseProjector(const Problem& p, RCP<const Map> map) : p_(p), map_(map) {}
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1.0,
             SC beta = 0.0) const override {
    const Vec x = gather(*X.getVector(0));
    const int r = static_cast<int>(p_.G.size());
    Dense GGt(r);
    Vec Gx(r);
    for (int i = 0; i < r; ++i) {
      for (int j = 0; j < r; ++j)
        for (size_t k = 0; k < x.size(); ++k) GGt(i, j) += p_.G[i][k] * p_.G[j][k];
      for (size_t k = 0; k < x.size(); ++k) Gx[i] += p_.G[i][k] * x[k];
    }
    Vec y;
    solveDense(GGt, Gx, y);
    Vec Px = x;
    for (int i = 0; i < r; ++i)
      for (size_t k = 0; k < x.size(); ++k) Px[k] -= p_.G[i][k] * y[i];
    auto out = toVector(map_, Px);
    Y.update(alpha, *out, beta);
  }

 private:
  const Problem& p_;
  RCP<const Map> map_;
};

TEUCHOS_UNIT_TEST(Transforms, ProjectionKeepsTheProblemOnKerG) {
  const auto m = withEqualityRows(2, 5);
  auto d = buildDual(m.problem, Tpetra::getDefaultComm());
  const RCP<const Operator> A = d.dual.A;
  auto P = rcp(new DenseProjector(m.problem, d.map));
  Friction::DualTransformChain chain;
  chain.add(rcp(new Friction::ProjectionTransform(P))).forward(d.dual);
  // x in ker G: x'PAPx = x'Ax; G' rows: PAP G'_i = 0.
  Vector v(d.map), Pv(d.map), Av(d.map), PAPv(d.map);
  v.randomize();
  P->apply(v, Pv);
  A->apply(Pv, Av);
  d.dual.A->apply(Pv, PAPv);
  TEST_FLOATING_EQUALITY(Pv.dot(PAPv), Pv.dot(Av), 1e-12);
  for (const auto& row : m.problem.G) {
    d.dual.A->apply(*toVector(d.map, row), PAPv);
    TEST_COMPARE(PAPv.norm2(), <=, 1e-12 * norm(row));
  }
  const Vec x = solveDual(d.dual, d.map, chain);
  checkSolution(m.problem, x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

// With complementIsGtG the projected and scaled dual carries the joint
// application s PAP x + rho (I - P) x, equal to the chain's A x plus the
// penalty on the projector's complement; without it, none.
TEUCHOS_UNIT_TEST(Transforms, JointHessianIsPAPPlusComplement) {
  const auto m = withEqualityRows(2, 7);
  auto plain = buildDual(m.problem, Tpetra::getDefaultComm());
  Friction::DualTransformChain().add(rcp(new Friction::ProjectionTransform(rcp(new DenseProjector(m.problem, plain.map)))))
      .forward(plain.dual);
  TEST_ASSERT(plain.dual.jointHessian.is_null());
  auto d = buildDual(m.problem, Tpetra::getDefaultComm());
  auto P = rcp(new DenseProjector(m.problem, d.map));
  Friction::DualTransformChain()
      .add(rcp(new Friction::ProjectionTransform(P, true)))
      .add(rcp(new Friction::ScalingTransform(20)))
      .forward(d.dual);
  TEST_ASSERT(!d.dual.jointHessian.is_null());
  const SC rho = 0.7;
  Vector x(d.map), Ax(d.map), Px(d.map), joint(d.map), expected(d.map);
  x.randomize();
  d.dual.A->apply(x, Ax);  // s PAP x
  P->apply(x, Px);
  expected.update(1.0, Ax, rho, x, 0.0);
  expected.update(-rho, Px, 1.0);
  d.dual.jointHessian->applyWithComplement(x, rho, joint);
  joint.update(-1.0, expected, 1.0);
  out << "|joint - (s PAP x + rho (I - P) x)| / |expected| = " << joint.norm2() / expected.norm2() << "\n";
  TEST_COMPARE(joint.norm2(), <=, 1e-13 * expected.norm2());
}

TEUCHOS_UNIT_TEST(Transforms, ChainForwardInOrderBackInReverse) {
  const auto m = withEqualityRows(1, 3);
  Problem big = m.problem;
  for (double& a : big.A.a) a *= 50.0;
  for (double& v : big.b) v *= 50.0;
  auto d = buildDual(big, Tpetra::getDefaultComm());
  // lambda~ in ker G, so that G x = 0 stays the constraint after the shift.
  Vector lt(d.map), Plt(d.map);
  lt.putScalar(0.0);
  {
    auto v = toVector(d.map, particular(m.problem.size()));
    DenseProjector(m.problem, d.map).apply(*v, Plt);
  }
  Friction::DualTransformChain chain;
  chain.add(rcp(new Friction::HomogenizationTransform(rcp(new Vector(Plt, Teuchos::Copy)))))
      .add(rcp(new Friction::ProjectionTransform(rcp(new DenseProjector(m.problem, d.map)))))
      .add(rcp(new Friction::ScalingTransform(50)))
      .forward(d.dual);
  const Vec x = solveDual(d.dual, d.map, chain);
  checkSolution(m.problem, x, m.x, m.mu, m.problem.slipBound, checkTolerance, out, success);
}

}  // namespace
