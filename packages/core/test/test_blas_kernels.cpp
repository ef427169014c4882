// test_blas_kernels.cpp: the BLAS kernels a Tribos program runs on
// (Tribos_BlasKernels.hpp; the test main calls prepareProcess as every
// program does). Where OpenBLAS is the BLAS and the processor has AVX-512
// or AVX2 + FMA, the kernels are not the Prescott (SSE3) fallback; and the
// kernels in use, whichever they are, compute a matrix product and a
// Cholesky factorization right: a product of integer matrices exactly, and
// L L' = A to round-off.
#include <Teuchos_BLAS.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <cstdlib>
#include <strings.h>
#include <vector>

#include "Tribos_BlasKernels.hpp"

namespace {

bool hasLaterInstructions() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

TEUCHOS_UNIT_TEST(BlasKernels, NotTheFallbackWhereTheProcessorAllowsMore) {
  const std::string name = Tribos::blasKernelName();
  out << "BLAS kernels: " << (name.empty() ? "(not OpenBLAS)" : name) << "\n";
  if (name.empty() || !hasLaterInstructions()) return;  // another BLAS, or a processor Prescott fits
  // OPENBLAS_CORETYPE, the user's or the one selectBlasKernels set, is what
  // OpenBLAS runs; without it, not the fallback.
  const char* named = std::getenv("OPENBLAS_CORETYPE");
  if (named) {
    TEST_EQUALITY(strcasecmp(named, name.c_str()), 0);
  } else {
    TEST_INEQUALITY(name, std::string("Prescott"));
  }
  // Asked again, nothing changes.
  TEST_EQUALITY(Tribos::selectBlasKernels(), std::string());
}

TEUCHOS_UNIT_TEST(BlasKernels, ProductAndCholeskyAreRight) {
  // C = A B for integer matrices of a size that runs the blocked kernels:
  // every partial sum is an integer below 2^53, so the result is exact.
  const int n = 157;
  std::vector<double> A(n * n), B(n * n), C(n * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) A[i + j * n] = (i * 7 + j * 3) % 11 - 5, B[i + j * n] = (i * 5 + j * 2) % 13 - 6;
  Teuchos::BLAS<int, double>().GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, n, n, n, 1.0, A.data(), n, B.data(), n,
                                    0.0, C.data(), n);
  double worst = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double c = 0;
      for (int k = 0; k < n; ++k) c += A[i + k * n] * B[k + j * n];
      worst = std::max(worst, std::abs(C[i + j * n] - c));
    }
  TEST_EQUALITY(worst, 0.0);
  // S = A A' + n I (positive definite) = L L'.
  std::vector<double> S(n * n, 0.0);
  Teuchos::BLAS<int, double>().SYRK(Teuchos::LOWER_TRI, Teuchos::NO_TRANS, n, n, 1.0, A.data(), n, 0.0, S.data(), n);
  for (int i = 0; i < n; ++i) S[i + i * n] += n;
  std::vector<double> L(S);
  int info = 0;
  Teuchos::LAPACK<int, double>().POTRF('L', n, L.data(), n, &info);
  TEST_EQUALITY(info, 0);
  double err = 0, scale = 0;
  for (int j = 0; j < n; ++j)
    for (int i = j; i < n; ++i) {
      double s = 0;
      for (int k = 0; k <= j; ++k) s += L[i + k * n] * L[j + k * n];
      err = std::max(err, std::abs(s - S[i + j * n])), scale = std::max(scale, std::abs(S[i + j * n]));
    }
  out << "|L L' - S| / |S| = " << err / scale << "\n";
  TEST_COMPARE(err, <, 1e-13 * scale);
}

}  // namespace
