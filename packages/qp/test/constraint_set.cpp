// constraint_set.cpp: projection, feasible step, free/chopped/reduced
// gradients and fixedOutside on a hand-made set whose answers follow from the
// definitions (docs/algorithms.md §3); input errors name the parameter.
// Every rank holds the same 6-entry block: [lower 0, box [-1,1], fixed, free, circle r=2].
#include "QPTestUtils.hpp"

using namespace qptest;
using Tribos::QP::ConstraintSet;

namespace {

ConstraintSet block(const RCP<const Map>& map) {
  ConstraintSet Omega(map);
  Omega.setLower(0, 0.0);
  Omega.setBox(1, -1.0, 1.0);
  Omega.setFixed(2);
  Omega.setCircle(4, 5, 0);
  Omega.setRadii({2.0});
  return Omega;
}

RCP<Vector> local(const RCP<const Map>& map, const Vec& v) {
  auto x = rcp(new Vector(map));
  auto xv = x->getDataNonConst();
  for (size_t i = 0; i < v.size(); ++i) xv[i] = v[i];
  return x;
}

double maxDiff(const Vector& x, const Vec& ref) {
  auto xv = x.getData();
  double m = 0;
  for (size_t i = 0; i < ref.size(); ++i) m = std::max(m, std::abs(xv[i] - ref[i]));
  double all = 0;
  Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MAX, m, Teuchos::outArg(all));
  return all;
}

RCP<const Map> blockMap(const RCP<const Comm>& comm) {
  return rcp(new Map(static_cast<Tpetra::global_size_t>(6 * comm->getSize()), 6, 0, comm));
}

}  // namespace

TEUCHOS_UNIT_TEST(ConstraintSet, Projection) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  TEST_ASSERT(!Omega.onlyBounds());  // onlyBounds() is false with a circle
  // projection: clamp, keep fixed and free, scale onto the disk
  auto x = local(map, {-3, 5, 7, 4, 3, 4});
  TEST_ASSERT(!Omega.isFeasible(*x, 1e-12));  // isFeasible rejects an infeasible x
  Omega.project(*x);
  TEST_COMPARE(maxDiff(*x, {0, 1, 7, 4, 1.2, 1.6}), <, 1e-15);  // project
  TEST_ASSERT(Omega.isFeasible(*x, 1e-12));  // projected x is feasible
}

// largest feasible step: lower 1/2, box (0-1)/(-4), disk from 0 along -(1,0): 2
TEUCHOS_UNIT_TEST(ConstraintSet, MaxFeasibleStep) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  auto x = local(map, {1, 0, 7, 4, 0, 0});
  auto p = local(map, {2, -4, 0, 1, 1, 0});
  TEST_COMPARE(std::abs(Omega.maxFeasibleStep(*x, *p) - 0.25), <, 1e-15);  // maxFeasibleStep = 0.25
  p = local(map, {0, 0, 0, 1, 0, 0});
  TEST_ASSERT(std::isinf(Omega.maxFeasibleStep(*x, *p)));  // maxFeasibleStep along a free direction is +inf
  p = local(map, {0, 0, 1e-3, 0, 0, 0});
  TEST_EQUALITY(Omega.maxFeasibleStep(*x, *p), 0);  // maxFeasibleStep is 0 when a fixed component moves
  // from (1.2, 1.6) on the circle along -p = (-3, 0): ||(1.2-3a, 1.6)|| = 2 at a = 0.8
  x = local(map, {1, 0, 7, 4, 1.2, 1.6});
  p = local(map, {0, 0, 0, 0, 3, 0});
  TEST_COMPARE(std::abs(Omega.maxFeasibleStep(*x, *p) - 0.8), <, 1e-14);  // maxFeasibleStep across the disk = 0.8
  p = local(map, {0, 0, 0, 0, -3, 0});
  TEST_EQUALITY(Omega.maxFeasibleStep(*x, *p), 0);  // maxFeasibleStep is 0 outward from the circle
  // a rank-dependent step: the global minimum is taken
  x = local(map, {1, 0, 7, 4, 0, 0});
  p = local(map, {1.0 + comm->getRank(), 0, 0, 0, 0, 0});
  TEST_COMPARE(std::abs(Omega.maxFeasibleStep(*x, *p) - 1.0 / comm->getSize()), <, 1e-15);  // maxFeasibleStep is a global min
}

// gradients at x = [0 (active), 1 (upper active), 7, 4, on circle]
TEUCHOS_UNIT_TEST(ConstraintSet, Gradients) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  auto x = local(map, {0, 1, 7, 4, 1.2, 1.6});
  Vector phi(map), beta(map), gP(map);
  auto g = local(map, {-1, -2, 5, 3, 1, 1});  // n'g = 1.4 > 0: -g points into the disk
  Omega.freeGradient(*x, *g, phi);
  Omega.choppedGradient(*x, *g, beta);
  TEST_COMPARE(maxDiff(phi, {0, 0, 0, 3, 0, 0}), <, 1e-15);  // free gradient
  TEST_COMPARE(maxDiff(beta, {-1, 0, 0, 0, 1, 1}), <, 1e-15);  // chopped gradient (inward circle gradient released)
  Omega.projectedGradient(*x, *g, gP);
  TEST_COMPARE(maxDiff(gP, {-1, 0, 0, 3, 1, 1}), <, 1e-15);  // projected gradient = phi + beta
  g = local(map, {2, 3, 5, 3, -1, -1});  // n'g = -1.4: only the tangential part is chopped
  Omega.choppedGradient(*x, *g, beta);
  TEST_COMPARE(maxDiff(beta, {0, 3, 0, 0, -0.16, 0.12}), <, 1e-14);  // chopped gradient tangential on the circle
}

// reduced free gradient with alpha_bar = 1: (x - P(x - phi))
TEUCHOS_UNIT_TEST(ConstraintSet, ReducedFreeGradient) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  Vector phit(map);
  auto x = local(map, {0.5, 0, 7, 4, 0, 0});
  auto g = local(map, {1, -10, 0, 2, 10, 0});
  Omega.reducedFreeGradient(*x, *g, 1.0, phit);
  TEST_COMPARE(maxDiff(phit, {0.5, -1, 0, 2, 2, 0}), <, 1e-15);  // reduced free gradient
}

// fixedOutside: freeze the bounds, keep the circle
TEUCHOS_UNIT_TEST(ConstraintSet, FixedOutside) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  Vector gP(map);
  ConstraintSet circleOnly = Omega.fixedOutside({0, 0, 0, 0, 1, 1});
  auto x = local(map, {-3, 5, 7, 4, 0, 4});
  circleOnly.project(*x);
  TEST_COMPARE(maxDiff(*x, {-3, 5, 7, 4, 0, 2}), <, 1e-15);  // fixedOutside: frozen entries kept by project
  auto g = local(map, {1, 1, 1, 1, 1, 1});
  circleOnly.projectedGradient(*x, *g, gP);
  TEST_COMPARE(maxDiff(gP, {0, 0, 0, 0, 1, 1}), <, 1e-15);  // fixedOutside: gradients vanish on frozen entries
  // freeze the circle: a bounds-only set for MPRGP
  ConstraintSet boundsOnly = Omega.fixedOutside({1, 1, 1, 1, 0, 0});
  TEST_ASSERT(boundsOnly.onlyBounds());  // fixedOutside with the circle frozen is onlyBounds()
  x = local(map, {-3, 5, 7, 4, 30, 40});
  boundsOnly.project(*x);
  TEST_COMPARE(maxDiff(*x, {0, 1, 7, 4, 30, 40}), <, 1e-15);  // frozen circle kept by project
}

// radius 0: the pair is fixed at 0
TEUCHOS_UNIT_TEST(ConstraintSet, RadiusZero) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  Vector gP(map);
  Omega.setRadii({0.0});
  auto x = local(map, {1, 0, 7, 4, 3, 4});
  Omega.project(*x);
  TEST_COMPARE(maxDiff(*x, {1, 0, 7, 4, 0, 0}), <, 1e-15);  // radius 0 projects onto 0
  auto g = local(map, {0, 0, 0, 0, 5, -5});
  Omega.projectedGradient(*x, *g, gP);
  TEST_COMPARE(maxDiff(gP, {0, 0, 0, 0, 0, 0}), <, 1e-15);  // radius 0: projected gradient is 0
}

// a shifted disk ||x - c|| <= r, c = (1, 2), r = 1: the same answers
// as the disk at 0 translated by c
TEUCHOS_UNIT_TEST(ConstraintSet, ShiftedDisk) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  Vector gP(map);
  ConstraintSet shifted(map);
  shifted.setCircle(4, 5, 0, 1.0, 2.0);
  shifted.setRadii({1.0});
  auto x = local(map, {0, 0, 0, 0, 4, 6});  // x - c = (3, 4): projected to c + (0.6, 0.8)
  shifted.project(*x);
  TEST_COMPARE(maxDiff(*x, {0, 0, 0, 0, 1.6, 2.8}), <, 1e-15);  // shifted disk: projection onto c + r (x - c)/||x - c||
  TEST_ASSERT(shifted.isFeasible(*x, 1e-12));  // shifted disk: the projection is feasible
  auto origin = local(map, {0, 0, 0, 0, 0, 0});
  TEST_ASSERT(!shifted.isFeasible(*origin, 1e-12));  // shifted disk: 0 is outside it
  // from the centre along p = (-1, 0): the boundary is 1 away
  auto centre = local(map, {0, 0, 0, 0, 1, 2});
  auto p = local(map, {0, 0, 0, 0, -1, 0});
  TEST_COMPARE(std::abs(shifted.maxFeasibleStep(*centre, *p) - 1.0), <, 1e-14);  // shifted disk: feasible step from the centre
  // on the boundary at c + (0.6, 0.8) the outward gradient g = -(0.6, 0.8) is chopped to 0...
  auto g = local(map, {0, 0, 0, 0, -0.6, -0.8});
  shifted.projectedGradient(*x, *g, gP);
  TEST_COMPARE(maxDiff(gP, {0, 0, 0, 0, 0, 0}), <, 1e-15);  // shifted disk: outward gradient on the boundary is chopped
  // ... and an inward one is kept
  g = local(map, {0, 0, 0, 0, 0.6, 0.8});
  shifted.projectedGradient(*x, *g, gP);
  TEST_COMPARE(maxDiff(gP, {0, 0, 0, 0, 0.6, 0.8}), <, 1e-15);  // shifted disk: inward gradient on the boundary is kept
}

// input errors name the parameter
TEUCHOS_UNIT_TEST(ConstraintSet, InputErrors) {
  auto comm = Tpetra::getDefaultComm();
  auto map = blockMap(comm);
  ConstraintSet Omega = block(map);
  Vector phit(map);
  auto x = local(map, {0, 1, 7, 4, 1.2, 1.6});
  auto g = local(map, {1, 1, 1, 1, 1, 1});
  TEST_ASSERT(throwsWith([&] { Omega.setRadii({-1.0}); }, "r_0"));  // negative radius rejected naming r_0
  TEST_ASSERT(throwsWith([&] { Omega.setRadii({1.0, 2.0}); }, "radii"));  // wrong number of radii rejected
  TEST_ASSERT(throwsWith([&] { Omega.setBox(3, 2.0, 1.0); }, "l <= u"));  // box with l > u rejected
  TEST_ASSERT(throwsWith([&] { Omega.setLower(6, 0.0); }, "local index i = 6"));  // index out of range rejected
  TEST_ASSERT(throwsWith([&] { Omega.setLower(4, 0.0); }, "circle"));  // bound on a circle component rejected
  TEST_ASSERT(throwsWith([&] { Omega.fixedOutside({1, 1, 1, 1, 1, 0}); }, "circle k = 0"));  // half-kept circle rejected
  TEST_ASSERT(throwsWith([&] { Omega.reducedFreeGradient(*x, *g, 0.0, phit); }, "alpha_bar"));  // alpha_bar <= 0 rejected
}
