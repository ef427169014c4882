// test_vec3.cpp: the 3-vector arithmetic of Tribos_Vec3.hpp on vectors whose
// results are known exactly (the right-handed axes, a 3-4-5 triangle), the
// identities every cross product meets, and the bits of the formulas as
// written out, which the geometry of several packages relies on.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>

#include <random>

#include "Tribos_Vec3.hpp"

namespace {

using Tribos::Vec3;

TEUCHOS_UNIT_TEST(Vec3, Axes) {
  const Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  TEST_COMPARE_ARRAYS(Tribos::cross(x, y), z);
  TEST_COMPARE_ARRAYS(Tribos::cross(y, z), x);
  TEST_COMPARE_ARRAYS(Tribos::cross(z, x), y);
  TEST_COMPARE_ARRAYS(Tribos::cross(y, x), (Vec3{0, 0, -1}));
  TEST_EQUALITY(Tribos::dot(x, y), 0.0);
  TEST_EQUALITY(Tribos::norm(Vec3{3, 4, 12}), 13.0);
  TEST_COMPARE_ARRAYS(Tribos::normalized(Vec3{0, 3, 4}), (Vec3{0, 0.6, 0.8}));
  TEST_COMPARE_ARRAYS(Tribos::minus(Vec3{1, 2, 3}, Vec3{0.5, 2, 4}), (Vec3{0.5, 0, -1}));
}

TEUCHOS_UNIT_TEST(Vec3, Identities) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 100; ++k) {
    const Vec3 a{u(gen), u(gen), u(gen)}, b{u(gen), u(gen), u(gen)};
    const Vec3 c = Tribos::cross(a, b);
    const double scale = Tribos::norm(a) * Tribos::norm(b);
    TEST_COMPARE(std::abs(Tribos::dot(c, a)), <=, 1e-14 * scale * Tribos::norm(a));
    TEST_COMPARE(std::abs(Tribos::dot(c, b)), <=, 1e-14 * scale * Tribos::norm(b));
    // |a x b|^2 + (a.b)^2 = |a|^2 |b|^2 (Lagrange)
    const double ab = Tribos::dot(a, b), cc = Tribos::dot(c, c);
    TEST_FLOATING_EQUALITY(cc + ab * ab, scale * scale, 1e-14);
    TEST_FLOATING_EQUALITY(Tribos::norm(Tribos::normalized(a)), 1.0, 1e-15);
  }
}

// The formulas the packages wrote out before they shared these: the same
// bits, so that contact frames and gaps do not move by a rounding.
TEUCHOS_UNIT_TEST(Vec3, SameBitsAsWrittenOut) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 a{u(gen), u(gen), u(gen)}, b{u(gen), u(gen), u(gen)};
    const Vec3 c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    TEST_COMPARE_ARRAYS(Tribos::cross(a, b), c);
    TEST_EQUALITY(Tribos::dot(a, b), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    TEST_EQUALITY(Tribos::norm(a), len);
    TEST_COMPARE_ARRAYS(Tribos::normalized(a), (Vec3{a[0] / len, a[1] / len, a[2] / len}));
  }
}

}  // namespace

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
