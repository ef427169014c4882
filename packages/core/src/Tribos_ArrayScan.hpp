// Tribos_ArrayScan.hpp: the scans of a whole array that every input check
// and every result check makes: are all entries finite, the largest
// magnitude and the Euclidean norm (the scales residuals are measured
// against).
//
// Each keeps four partial results and no branch per entry, so that the
// additions or maxima do not wait on each other: on the small problems a
// multibody code solves at every time step, scanning entry by entry would
// cost as much as the solve.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace Tribos {

// A double is inf or nan exactly when its 11 exponent bits are all set;
// adding 1 to that field then carries into the sign bit. Integer operations
// without a branch, so the loop vectorizes (a floating-point sum of x * 0
// would wait on each addition).
inline bool allFinite(const double* v, std::size_t n) {
  constexpr std::uint64_t exponent = 0x7ff0000000000000ull, one = 0x0010000000000000ull;
  std::uint64_t carry = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t bits;
    std::memcpy(&bits, v + k, sizeof bits);
    carry |= (bits & exponent) + one;
  }
  return (carry >> 63) == 0;
}

inline bool allFinite(const std::vector<double>& v) { return allFinite(v.data(), v.size()); }

// max |v_k| (0 for no entries). A nan entry is ignored (std::max keeps its
// first argument), so callers that must not trust a nan test allFinite first.
inline double normInf(const double* v, std::size_t n) {
  double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
  std::size_t k = 0;
  for (; k + 3 < n; k += 4) {
    m0 = std::max(m0, std::abs(v[k]));
    m1 = std::max(m1, std::abs(v[k + 1]));
    m2 = std::max(m2, std::abs(v[k + 2]));
    m3 = std::max(m3, std::abs(v[k + 3]));
  }
  for (; k < n; ++k) m0 = std::max(m0, std::abs(v[k]));
  return std::max(std::max(m0, m1), std::max(m2, m3));
}

inline double normInf(const std::vector<double>& v) { return normInf(v.data(), v.size()); }

// ||v||_2 (the sum of squares in four partial sums, then one square root).
inline double norm2(const double* v, std::size_t n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  std::size_t k = 0;
  for (; k + 3 < n; k += 4) {
    s0 += v[k] * v[k];
    s1 += v[k + 1] * v[k + 1];
    s2 += v[k + 2] * v[k + 2];
    s3 += v[k + 3] * v[k + 3];
  }
  for (; k < n; ++k) s0 += v[k] * v[k];
  return std::sqrt((s0 + s1) + (s2 + s3));
}

inline double norm2(const std::vector<double>& v) { return norm2(v.data(), v.size()); }

}  // namespace Tribos
