// test_array_scan.cpp: the whole-array scans of Tribos_ArrayScan.hpp
// against entry-by-entry definitions, with the special value at every
// position of arrays of every length up to 13 (the four-way loops and their
// tails), and at the edges of the double range (largest finite, smallest
// subnormal, -0).
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "Tribos_ArrayScan.hpp"

namespace {

using Limits = std::numeric_limits<double>;

// Arrays of length n with 'special' at position p and ordinary values elsewhere.
std::vector<double> withValueAt(std::size_t n, std::size_t p, double special) {
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = 0.5 + static_cast<double>(k % 3) - 1.0;  // -0.5, 0.5, 1.5
  v[p] = special;
  return v;
}

TEUCHOS_UNIT_TEST(ArrayScan, AllFiniteAtEveryPosition) {
  const double nonFinite[] = {Limits::infinity(), -Limits::infinity(), Limits::quiet_NaN(), -Limits::quiet_NaN(),
                              Limits::signaling_NaN()};
  const double finite[] = {Limits::max(), -Limits::max(), Limits::denorm_min(), -0.0, 0.0, Limits::min()};
  TEST_ASSERT(Tribos::allFinite(std::vector<double>{}));
  for (std::size_t n = 1; n <= 13; ++n)
    for (std::size_t p = 0; p < n; ++p) {
      for (double x : nonFinite) TEST_ASSERT(!Tribos::allFinite(withValueAt(n, p, x)));
      for (double x : finite) TEST_ASSERT(Tribos::allFinite(withValueAt(n, p, x)));
    }
}

TEUCHOS_UNIT_TEST(ArrayScan, NormsAtEveryPosition) {
  for (std::size_t n = 1; n <= 13; ++n)
    for (std::size_t p = 0; p < n; ++p) {
      const std::vector<double> v = withValueAt(n, p, -7.25);
      double sum = 0, largest = 0;
      for (double x : v) sum += x * x, largest = std::max(largest, std::abs(x));
      TEST_EQUALITY(Tribos::normInf(v), largest);
      TEST_FLOATING_EQUALITY(Tribos::norm2(v), std::sqrt(sum), 1e-15);
    }
}

}  // namespace

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
