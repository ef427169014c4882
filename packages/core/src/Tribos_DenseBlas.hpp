// Tribos_DenseBlas.hpp: the few dense BLAS/LAPACK kernels Teuchos does not wrap
// (symmetric matrix-vector product, inverse from a Cholesky factor). Column-major,
// lower triangle.
#pragma once

extern "C" {
void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda, const double* x,
            const int* incx, const double* beta, double* y, const int* incy);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace Tribos {
namespace Blas {

// y = alpha A x + beta y, A symmetric n x n, only its lower triangle is read.
inline void symv(int n, double alpha, const double* A, const double* x, double beta, double* y) {
  const char uplo = 'L';
  const int one = 1;
  dsymv_(&uplo, &n, &alpha, A, &n, x, &one, &beta, y, &one);
}

// A <- (L L')^-1 from the Cholesky factor L in the lower triangle of A; the
// full symmetric inverse is returned (both triangles). Returns LAPACK's info.
inline int choleskyInverse(int n, double* A) {
  const char uplo = 'L';
  int info = 0;
  if (n == 0) return 0;
  dpotri_(&uplo, &n, A, &n, &info);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i) A[static_cast<size_t>(i) * n + j] = A[static_cast<size_t>(j) * n + i];
  return info;
}

}  // namespace Blas
}  // namespace Tribos
