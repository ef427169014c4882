// Tribos_TestSupport.hpp: what the test programs share: relative differences.
#pragma once

#include <algorithm>
#include <cmath>
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

}  // namespace Test
}  // namespace Tribos
