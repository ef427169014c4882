#include "Tribos_History.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "Tribos_Error.hpp"

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

std::string IterationHistory::csvHeader() {
  return "outer_iteration,relative_residual,G_lambda_rel,slip_bound_change,n_A,time_s,step\n";
}

std::string IterationHistory::toCsv() const { return csvHeader() + csvRows(); }

std::string IterationHistory::csvRows() const {
  std::ostringstream os;
  for (const auto& r : rows)
    os << r.iteration << ',' << field(r.relativeResidual) << ',' << field(r.gLambda) << ','
       << field(r.slipBoundChange) << ',' << field(r.n_A) << ',' << field(r.seconds) << ',' << r.step << '\n';
  return os.str();
}

IterationHistory IterationHistory::fromCsv(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  TRIBOS_REQUIRE(std::getline(in, line) && line + "\n" == csvHeader(),
                 "line 1 is not the header of an iteration history");
  IterationHistory h;
  for (int number = 2; std::getline(in, line); ++number) {
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    if (!line.empty() && line.back() == ',') fields.push_back("");
    // A field of the whole text as a number; an empty one is NaN.
    bool ok = fields.size() == 7;
    auto value = [&](const std::string& f) {
      if (f.empty()) return std::numeric_limits<double>::quiet_NaN();
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      ok = ok && *end == '\0';
      return v;
    };
    HistoryRow r;
    if (ok) {
      const double iteration = value(fields[0]), step = value(fields[6]);
      r.relativeResidual = value(fields[1]);
      r.gLambda = value(fields[2]);
      r.slipBoundChange = value(fields[3]);
      r.n_A = value(fields[4]);
      r.seconds = value(fields[5]);
      ok = ok && iteration == std::floor(iteration) && step == std::floor(step) && step >= 1;
      r.iteration = static_cast<long long>(iteration);
      r.step = static_cast<int>(step);
    }
    TRIBOS_REQUIRE(ok, "line " << number << " is not a row of 7 numbers of an iteration history: " << line);
    h.rows.push_back(r);
  }
  return h;
}

}  // namespace IO
}  // namespace Tribos
