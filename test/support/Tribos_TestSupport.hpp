// Tribos_TestSupport.hpp: what the test programs share: relative differences,
// and the messages of the errors they provoke.
#pragma once

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

namespace Tribos {
namespace Test {

// ||a - b|| / ||b|| (2-norms).
inline double relDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]) * (a[i] - b[i]), n += b[i] * b[i];
  return std::sqrt(d / std::max(n, 1e-300));
}

// max_i |a_i - b_i| / max_i |b_i|.
inline double maxRelDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i])), n = std::max(n, std::abs(b[i]));
  return d / std::max(n, 1e-300);
}

// True when `text` holds `part` (messages checked for what they must name).
inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The message of the exception f() throws; "" when it throws none.
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace Test
}  // namespace Tribos
