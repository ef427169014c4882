// Tribos_LoadCurve.hpp: a load history. Loads are solved at a sequence of
// pseudo-times t; each load is its full value times a curve of t, a
// piecewise-linear LoadCurve or, for a load without one, the ramp min(t, 1)
// (so t = 1 is the load at full value, and a single step at t = 1 is the
// static problem).
#pragma once

#include <string>
#include <vector>

#include "Tribos_Loads.hpp"

namespace Tribos {
namespace Fem {

class LoadCurve {
 public:
  // The ramp min(t, 1).
  LoadCurve() = default;
  // Piecewise linear through the points (times[i], values[i]): at least two
  // points, of the same number, times strictly increasing, all finite.
  // `what` names the curve in every message (e.g. its parameter path).
  LoadCurve(std::vector<double> times, std::vector<double> values, std::string what = "load curve");

  bool isRamp() const { return times_.empty(); }
  // Whether the curve is defined at t: the ramp everywhere, a curve between
  // its first and last time (it is never extrapolated).
  bool covers(double t) const;
  // The value at t; a t the curve does not cover is an error naming the
  // curve, t and the curve's range.
  double operator()(double t) const;

  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& values() const { return values_; }
  const std::string& what() const { return what_; }

 private:
  std::vector<double> times_, values_;
  std::string what_ = "the ramp min(t, 1)";
};

// The loads of a history: every load at full value (`base`) and the curve of
// each, in the order of base's loads. A load beyond the end of its curve
// vector (e.g. every load of LoadHistory{loads}) is ramped.
struct LoadHistory {
  LoadCase base;
  std::vector<LoadCurve> dirichletCurves;
  std::vector<LoadCurve> tractionCurves;
  LoadCurve volumeForceCurve;
};

// The loads at time t: each of base's scaled by its curve's value at t (a
// Dirichlet condition given by a field: the field's values scaled). At t = 1
// a history without curves gives base exactly.
LoadCase loadCaseAt(const LoadHistory& history, double t);

}  // namespace Fem
}  // namespace Tribos
