// Tribos_DenseBlas.hpp: the few dense BLAS/LAPACK kernels Teuchos does not wrap
// (packed symmetric matrix-vector product, inverse from a Cholesky factor). Column-major,
// lower triangle.
#pragma once

#include <cstddef>
#include <vector>

extern "C" {
void dspmv_(const char* uplo, const int* n, const double* alpha, const double* ap, const double* x, const int* incx,
            const double* beta, double* y, const int* incy);
void sspmv_(const char* uplo, const int* n, const float* alpha, const float* ap, const float* x, const int* incx,
            const float* beta, float* y, const int* incy);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dpptrs_(const char* uplo, const int* n, const int* nrhs, const double* ap, double* b, const int* ldb, int* info);
void dtpsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* ap, double* x,
            const int* incx);
}

namespace Tribos {
namespace Blas {

// y = alpha A x + beta y, A symmetric n x n stored as its packed lower triangle
// (column after column, n(n+1)/2 values: half the memory traffic of symv).
inline void spmv(int n, double alpha, const double* Ap, const double* x, double beta, double* y) {
  const char uplo = 'L';
  const int one = 1;
  dspmv_(&uplo, &n, &alpha, Ap, x, &one, &beta, y, &one);
}

// The same in single precision: half the bytes per stored value.
inline void spmv(int n, float alpha, const float* Ap, const float* x, float beta, float* y) {
  const char uplo = 'L';
  const int one = 1;
  sspmv_(&uplo, &n, &alpha, Ap, x, &one, &beta, y, &one);
}

// y = A x for A stored in single precision (packed lower, as above) and x,
// y in double, every product and sum in double: A is rounded once, when it
// is stored, and then applied as the exact symmetric matrix it is. The
// iterative solvers see one consistent operator (its products agree with
// each other to double round-off), which sspmv's sums in float would not
// give; the bytes read from A are sspmv's. Column j of the packed triangle
// contributes a_jj x_j + sum_i a_ij x_i to y_j (a dot product) and a_ij x_j
// to y_i (an axpy), both from one pass over the column; the dot product
// runs in eight partial sums so that its additions do not wait on each other.
// (Tribos_DenseBlas.cpp: compiled for AVX2 + FMA as well as the baseline,
// the processor choosing at run time.)
void spmvMixed(int n, const float* Ap, const double* x, double* y);

// y_k = a_k . x for the three rows a_0, a_1, a_2 of length n, in one pass
// over x (the three velocity components of a contact from dense rows of W,
// Friction::NonsmoothGaussSeidel). Compiled like spmvMixed; rows stored in
// float are widened as they are read, every product and sum in double.
void dot3(int n, const double* a0, const double* a1, const double* a2, const double* x, double y[3]);
void dot3(int n, const float* a0, const float* a1, const float* a2, const double* x, double y[3]);

// The packed lower triangle of the column-major n x n matrix A, in the
// precision T of the result (double, or float for half the bytes).
template <class T>
std::vector<T> packLower(int n, const std::vector<double>& A) {
  std::vector<T> Ap;
  Ap.reserve(static_cast<size_t>(n) * (n + 1) / 2);
  for (int j = 0; j < n; ++j) Ap.insert(Ap.end(), A.begin() + static_cast<size_t>(j) * n + j, A.begin() + static_cast<size_t>(j + 1) * n);
  return Ap;
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

// B <- (L L')^-1 B for nrhs columns of length n, L the packed lower Cholesky
// factor (packLower's layout).
inline void packedCholeskySolve(int n, int nrhs, const double* Lp, double* B) {
  const char uplo = 'L';
  int info = 0;
  if (n > 0 && nrhs > 0) dpptrs_(&uplo, &n, &nrhs, Lp, B, &n, &info);
}

// x <- L^-1 x, or L^-T x when transpose, L packed lower triangular.
inline void packedTriangularSolve(int n, bool transpose, const double* Lp, double* x) {
  const char uplo = 'L', trans = transpose ? 'T' : 'N', diag = 'N';
  const int one = 1;
  if (n > 0) dtpsv_(&uplo, &trans, &diag, &n, Lp, x, &one);
}

}  // namespace Blas
}  // namespace Tribos
