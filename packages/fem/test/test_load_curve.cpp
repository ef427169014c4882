// Load curves and the loads of a history (Tribos_LoadCurve.hpp):
//  - a curve gives its values exactly at its knots and the linear
//    interpolation between them, and is refused beyond its range;
//  - without a curve a load is ramped, min(t, 1);
//  - a malformed curve is refused, naming it and the offending point;
//  - loadCaseAt scales each load by its own curve (a Dirichlet field too),
//    and at t = 1 without curves gives the base loads exactly.
#include <Teuchos_UnitTestHarness.hpp>

#include <limits>
#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_LoadCurve.hpp"

namespace {

using namespace Tribos;
using Fem::LoadCurve;

// The message of the Tribos::Error f throws, or "" when it throws none.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEUCHOS_UNIT_TEST(LoadCurve, ExactAtKnotsLinearBetween) {
  // Up, down through zero, and back: a fretting-like cycle with uneven steps.
  const LoadCurve c({0.0, 1.0, 3.0, 3.5}, {0.0, 2.0, -2.0, 0.5}, "Load Curves/cycle");
  TEST_ASSERT(!c.isRamp());
  TEST_EQUALITY(c(0.0), 0.0);
  TEST_EQUALITY(c(1.0), 2.0);
  TEST_EQUALITY(c(3.0), -2.0);
  TEST_EQUALITY(c(3.5), 0.5);
  // Between knots: values representable exactly, so equality is exact.
  TEST_EQUALITY(c(0.5), 1.0);
  TEST_EQUALITY(c(0.25), 0.5);
  TEST_EQUALITY(c(2.0), 0.0);
  TEST_EQUALITY(c(1.5), 1.0);
  TEST_EQUALITY(c(2.5), -1.0);
  TEST_EQUALITY(c(3.25), -0.75);
  // A generic point: the line through its segment's knots.
  TEST_FLOATING_EQUALITY(c(1.3), 2.0 + (1.3 - 1.0) / 2.0 * (-4.0), 1e-15);
}

TEUCHOS_UNIT_TEST(LoadCurve, NotExtrapolated) {
  const LoadCurve c({0.5, 2.0}, {1.0, 3.0}, "Load Curves/late");
  TEST_ASSERT(c.covers(0.5) && c.covers(2.0) && c.covers(1.0));
  TEST_ASSERT(!c.covers(0.25) && !c.covers(2.5));
  const std::string below = errorOf([&] { c(0.25); });
  TEST_ASSERT(contains(below, "Load Curves/late: t = 0.25 lies outside its times [0.5, 2]"));
  TEST_ASSERT(contains(errorOf([&] { c(2.5); }), "t = 2.5 lies outside"));
}

TEUCHOS_UNIT_TEST(LoadCurve, RampIsTheDefault) {
  const LoadCurve ramp;
  TEST_ASSERT(ramp.isRamp());
  TEST_ASSERT(ramp.covers(1e6));
  TEST_EQUALITY(ramp(0.25), 0.25);
  TEST_EQUALITY(ramp(0.75), 0.75);
  TEST_EQUALITY(ramp(1.0), 1.0);
  TEST_EQUALITY(ramp(2.0), 1.0);  // held at full value after t = 1
  TEST_EQUALITY(ramp(1e6), 1.0);
}

TEUCHOS_UNIT_TEST(LoadCurve, MalformedCurvesRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  TEST_ASSERT(contains(errorOf([] { LoadCurve({0, 1, 2}, {0, 1}, "Load Curves/a"); }),
                       "Load Curves/a: Times has 3 points and Values 2; they must have the same length"));
  TEST_ASSERT(contains(errorOf([] { LoadCurve({1}, {1}, "Load Curves/a"); }),
                       "Load Curves/a: has 1 point(s); a piecewise-linear curve needs at least 2"));
  TEST_ASSERT(contains(errorOf([] { LoadCurve({}, {}, "Load Curves/a"); }), "has 0 point(s)"));
  TEST_ASSERT(contains(errorOf([] { LoadCurve({0, 1, 1}, {0, 1, 2}, "Load Curves/a"); }),
                       "Times must be strictly increasing; Times[2] = 1 follows Times[1] = 1"));
  TEST_ASSERT(contains(errorOf([] { LoadCurve({0, 2, 1}, {0, 1, 2}, "Load Curves/a"); }),
                       "Times[2] = 1 follows Times[1] = 2"));
  TEST_ASSERT(contains(errorOf([&] { LoadCurve({0, nan}, {0, 1}, "Load Curves/a"); }), "Times[1] = nan is not finite"));
  TEST_ASSERT(contains(errorOf([&] { LoadCurve({0, 1}, {inf, 1}, "Load Curves/a"); }), "Values[0] = inf is not finite"));
  TEST_ASSERT(errorOf([] { LoadCurve({0, 1}, {5, 5}); }).empty());
}

Fem::LoadCase baseLoads() {
  Fem::LoadCase loads;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  Fem::DirichletCondition pushed;
  pushed.face = "zmax";
  pushed.fix = {false, false, true};
  pushed.value = {0, 0, -0.5};
  Fem::DirichletCondition sheared;
  sheared.face = "xmax";
  sheared.field = [](const Fem::Point& x) { return Fem::Point{x[2], 2 * x[2], 0}; };
  loads.dirichlet = {clamp, pushed, sheared};
  loads.tractions = {{"ymin", {1, 2, 3}}, {"ymax", {0, -4, 0}}};
  loads.volumeForce = {0, 0, -8};
  return loads;
}

TEUCHOS_UNIT_TEST(LoadCurve, LoadCaseAtScalesEachLoadByItsCurve) {
  Fem::LoadHistory h;
  h.base = baseLoads();
  // Dirichlet: the clamp ramped (no curve given), the push by `press`, the
  // sheared face by `shear`; the first traction by `shear`, the second
  // ramped; the volume force by `press`.
  const LoadCurve press({0, 1, 4}, {0, 1, 1}, "press");
  const LoadCurve shear({0, 1, 2, 3, 4}, {0, 0, 1, -1, 0}, "shear");
  h.dirichletCurves = {LoadCurve(), press, shear};
  h.tractionCurves = {shear};
  h.volumeForceCurve = press;
  const Fem::Point x{0.5, 0.25, 2.0};
  for (double t : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0}) {
    const Fem::LoadCase at = Fem::loadCaseAt(h, t);
    TEST_EQUALITY(at.dirichlet.size(), 3u);
    TEST_EQUALITY(at.tractions.size(), 2u);
    const double ramp = std::min(t, 1.0), p = press(t), s = shear(t);
    // Faces and fixed components are the base's.
    TEST_EQUALITY(at.dirichlet[1].face, "zmax");
    TEST_ASSERT(at.dirichlet[1].fix == h.base.dirichlet[1].fix);
    TEST_EQUALITY(at.tractions[1].face, "ymax");
    TEST_ASSERT(!at.dirichlet[0].field && !at.dirichlet[1].field && at.dirichlet[2].field);
    TEST_EQUALITY(at.dirichlet[1].value[2], -0.5 * p);
    TEST_EQUALITY(at.dirichlet[2].field(x)[0], 2.0 * s);
    TEST_EQUALITY(at.dirichlet[2].field(x)[1], 4.0 * s);
    TEST_EQUALITY(at.tractions[0].traction[0], 1 * s);
    TEST_EQUALITY(at.tractions[0].traction[2], 3 * s);
    TEST_EQUALITY(at.tractions[1].traction[1], -4 * ramp);
    TEST_EQUALITY(at.volumeForce[2], -8 * p);
  }
  // The curves are distinct: at t = 2 the push is on, the shear at its peak,
  // at t = 4 the shear is back to zero and the push still on.
  TEST_EQUALITY(Fem::loadCaseAt(h, 2.0).tractions[0].traction[2], 3.0);
  TEST_EQUALITY(Fem::loadCaseAt(h, 4.0).tractions[0].traction[2], 0.0);
  TEST_EQUALITY(Fem::loadCaseAt(h, 4.0).dirichlet[1].value[2], -0.5);
  // A time beyond a curve is refused, naming the curve.
  TEST_ASSERT(contains(errorOf([&] { Fem::loadCaseAt(h, 5.0); }), "press: t = 5 lies outside its times [0, 4]"));
}

TEUCHOS_UNIT_TEST(LoadCurve, RampedHistoryAtOneIsTheBase) {
  const Fem::LoadHistory h{baseLoads(), {}, {}, {}};
  const Fem::LoadCase at = Fem::loadCaseAt(h, 1.0);
  for (size_t i = 0; i < at.dirichlet.size(); ++i) TEST_ASSERT(at.dirichlet[i].value == h.base.dirichlet[i].value);
  TEST_ASSERT(at.dirichlet[2].field(Fem::Point{1, 2, 3}) == h.base.dirichlet[2].field(Fem::Point{1, 2, 3}));
  for (size_t i = 0; i < at.tractions.size(); ++i) TEST_ASSERT(at.tractions[i].traction == h.base.tractions[i].traction);
  TEST_ASSERT(at.volumeForce == h.base.volumeForce);
  // Four ramped steps: a quarter of every load at t = 0.25.
  const Fem::LoadCase quarter = Fem::loadCaseAt(h, 0.25);
  TEST_EQUALITY(quarter.tractions[0].traction[2], 0.75);
  TEST_EQUALITY(quarter.volumeForce[2], -2.0);
  TEST_EQUALITY(quarter.dirichlet[2].field(Fem::Point{1, 2, 3})[1], 1.5);
  // More curves than loads is a programming error, said as such.
  Fem::LoadHistory extra = h;
  extra.tractionCurves.assign(3, LoadCurve());
  TEST_ASSERT(contains(errorOf([&] { Fem::loadCaseAt(extra, 1.0); }), "3 traction curves for 2 traction loads"));
}

}  // namespace
