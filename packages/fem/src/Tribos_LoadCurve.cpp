#include "Tribos_LoadCurve.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

LoadCurve::LoadCurve(std::vector<double> times, std::vector<double> values, std::string what)
    : times_(std::move(times)), values_(std::move(values)), what_(std::move(what)) {
  TRIBOS_REQUIRE(times_.size() == values_.size(), what_ << ": Times has " << times_.size() << " points and Values "
                                                         << values_.size() << "; they must have the same length");
  // Two points at least: one point defines no segment, and a constant load
  // is two equal values.
  TRIBOS_REQUIRE(times_.size() >= 2, what_ << ": has " << times_.size()
                                           << " point(s); a piecewise-linear curve needs at least 2");
  for (size_t i = 0; i < times_.size(); ++i) {
    TRIBOS_REQUIRE(std::isfinite(times_[i]), what_ << ": Times[" << i << "] = " << times_[i] << " is not finite");
    TRIBOS_REQUIRE(std::isfinite(values_[i]), what_ << ": Values[" << i << "] = " << values_[i] << " is not finite");
    TRIBOS_REQUIRE(i == 0 || times_[i] > times_[i - 1], what_ << ": Times must be strictly increasing; Times["
                                                              << i << "] = " << times_[i] << " follows Times[" << i - 1
                                                              << "] = " << times_[i - 1]);
  }
}

bool LoadCurve::covers(double t) const {
  return isRamp() || (t >= times_.front() && t <= times_.back());
}

double LoadCurve::operator()(double t) const {
  if (isRamp()) return std::min(t, 1.0);
  TRIBOS_REQUIRE(covers(t), what_ << ": t = " << t << " lies outside its times [" << times_.front() << ", "
                                  << times_.back() << "]; a load curve is not extrapolated");
  // The segment [times[i], times[i+1]) holding t; t at a knot gives that
  // knot's value exactly, the last time the last value.
  const size_t i = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin() - 1;
  if (i + 1 == times_.size()) return values_.back();
  const double s = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return values_[i] + s * (values_[i + 1] - values_[i]);
}

namespace {

// The curve of load i: its own, or the ramp beyond the end of the vector.
const LoadCurve& curveOf(const std::vector<LoadCurve>& curves, size_t i, size_t loads, const char* kind) {
  static const LoadCurve ramp;
  TRIBOS_REQUIRE(curves.size() <= loads, "LoadHistory: " << curves.size() << " " << kind << " curves for " << loads
                                                         << " " << kind << " loads");
  return i < curves.size() ? curves[i] : ramp;
}

Point scaled(const Point& p, double s) { return {s * p[0], s * p[1], s * p[2]}; }

}  // namespace

LoadCase loadCaseAt(const LoadHistory& history, double t) {
  LoadCase loads = history.base;
  for (size_t i = 0; i < loads.dirichlet.size(); ++i) {
    auto& c = loads.dirichlet[i];
    const double s = curveOf(history.dirichletCurves, i, loads.dirichlet.size(), "Dirichlet")(t);
    c.value = scaled(c.value, s);
    if (c.field) c.field = [field = c.field, s](const Point& x) { return scaled(field(x), s); };
  }
  for (size_t i = 0; i < loads.tractions.size(); ++i) {
    auto& c = loads.tractions[i];
    c.traction = scaled(c.traction, curveOf(history.tractionCurves, i, loads.tractions.size(), "traction")(t));
  }
  loads.volumeForce = scaled(loads.volumeForce, history.volumeForceCurve(t));
  return loads;
}

}  // namespace Fem
}  // namespace Tribos
