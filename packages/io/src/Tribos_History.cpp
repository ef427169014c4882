#include "Tribos_History.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace Tribos {
namespace IO {

namespace {
std::string field(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}
}  // namespace

HistoryRow::HistoryRow()
    : relativeResidual(std::numeric_limits<double>::quiet_NaN()),
      gLambda(std::numeric_limits<double>::quiet_NaN()),
      slipBoundChange(std::numeric_limits<double>::quiet_NaN()),
      n_A(std::numeric_limits<double>::quiet_NaN()),
      seconds(std::numeric_limits<double>::quiet_NaN()) {}

std::string IterationHistory::toCsv() const {
  std::ostringstream os;
  os << "outer_iteration,relative_residual,G_lambda_rel,slip_bound_change,n_A,time_s,step\n";
  for (const auto& r : rows)
    os << r.iteration << ',' << field(r.relativeResidual) << ',' << field(r.gLambda) << ','
       << field(r.slipBoundChange) << ',' << field(r.n_A) << ',' << field(r.seconds) << ',' << r.step << '\n';
  return os.str();
}

}  // namespace IO
}  // namespace Tribos
