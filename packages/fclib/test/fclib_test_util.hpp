// fclib_test_util.hpp: small helpers shared by the FCLIB tests: the location
// of the sample files, a unit test case per sample, and a dense Cholesky
// factorization used as the M^{-1} of the small global samples.
#pragma once

#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "Tribos_FCLIB.hpp"

namespace fclib_test {

// Directory of the sample files: test/data of this package, compiled in so
// that the tests need no environment and run from any clone.
inline std::string sampleDir() { return TRIBOS_FCLIB_SAMPLE_DIR; }

struct Sample {
  std::string name;
  Tribos::FCLIB::ProblemKind kind;
  int contacts;
};

// The shipped files and what their README says about them.
inline std::vector<Sample> samples() {
  using Tribos::FCLIB::ProblemKind;
  return {{"local_problem_test.hdf5", ProblemKind::Local, 48},
          {"LMGC_100_PR_PerioBox-i00361-60-03000.hdf5", ProblemKind::Local, 60},
          {"LMGC_GFC3D_CubeH8.hdf5", ProblemKind::Global, 1},
          {"LMGC_GlobalFrictionContactProblem00046.hdf5", ProblemKind::Global, 9},
          {"Box_Stacks-i0122-82-5.hdf5", ProblemKind::Global, 82}};
}

inline std::string samplePath(const Sample& s) { return sampleDir() + "/" + s.name; }

// One TEUCHOS_UNIT_TEST(GROUP, <sample>) per shipped sample, each calling
// CHECK(sample, out, success).
#define FCLIB_SAMPLE_CASES(GROUP, CHECK)                                                   \
  TEUCHOS_UNIT_TEST(GROUP, LocalProblemTest) { CHECK(fclib_test::samples()[0], out, success); } \
  TEUCHOS_UNIT_TEST(GROUP, PerioBox) { CHECK(fclib_test::samples()[1], out, success); }         \
  TEUCHOS_UNIT_TEST(GROUP, CubeH8) { CHECK(fclib_test::samples()[2], out, success); }           \
  TEUCHOS_UNIT_TEST(GROUP, GlobalFrictionContact00046) { CHECK(fclib_test::samples()[3], out, success); } \
  TEUCHOS_UNIT_TEST(GROUP, BoxStacks) { CHECK(fclib_test::samples()[4], out, success); }

// A scratch path in the build tree (tests run there), unique per test.
inline std::string scratchPath(const std::string& test, const std::string& name) {
  return "fclib_scratch_" + test + "_" + name;
}

// Dense Cholesky of a small SPD matrix (test utility only: O(n^3), n <= ~1000).
class DenseCholesky {
 public:
  explicit DenseCholesky(const Tribos::LocalCsr& A) : n_(A.rows), L_(A.rows * A.rows, 0.0) {
    if (A.rows != A.cols) throw std::runtime_error("DenseCholesky: matrix is not square");
    for (int r = 0; r < A.rows; ++r)
      for (int k = A.rowptr[r]; k < A.rowptr[r + 1]; ++k) L_[r * n_ + A.col[k]] += A.val[k];
    for (int j = 0; j < n_; ++j) {
      double d = at(j, j);
      for (int k = 0; k < j; ++k) d -= at(j, k) * at(j, k);
      if (!(d > 0.0))
        throw std::runtime_error("DenseCholesky: matrix is not positive definite at row " +
                                 std::to_string(j));
      at(j, j) = std::sqrt(d);
      for (int i = j + 1; i < n_; ++i) {
        double s = at(i, j);
        for (int k = 0; k < j; ++k) s -= at(i, k) * at(j, k);
        at(i, j) = s / at(j, j);
      }
    }
  }

  void solve(const std::vector<double>& b, std::vector<double>& x) const {
    x = b;
    for (int i = 0; i < n_; ++i) {
      for (int k = 0; k < i; ++k) x[i] -= at(i, k) * x[k];
      x[i] /= at(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      for (int k = i + 1; k < n_; ++k) x[i] -= at(k, i) * x[k];
      x[i] /= at(i, i);
    }
  }

 private:
  double& at(int i, int j) { return L_[i * n_ + j]; }
  double at(int i, int j) const { return L_[i * n_ + j]; }
  int n_;
  std::vector<double> L_;
};

}  // namespace fclib_test
