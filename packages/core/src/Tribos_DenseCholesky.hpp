// Tribos_DenseCholesky.hpp: a dense symmetric positive definite matrix
// factored by Cholesky (LAPACK), with the singularity test every user of it
// shares: FETI's coarse problem, the semismooth* dense Schur complement, the
// Newton reduction of a contact dual.
#pragma once

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <vector>

namespace Tribos {

class DenseCholesky {
 public:
  // Cholesky of A (n x n, column-major); false when A is singular (a pivot
  // below 1e-12 of the largest, squared).
  bool tryFactor(std::vector<double> A, int n) {
    n_ = n;
    L_ = std::move(A);
    if (n == 0) return true;
    info_ = 0;
    Teuchos::LAPACK<int, double>().POTRF('L', n, L_.data(), n, &info_);
    // A pivot far below the largest diagonal entry is a singular matrix in
    // floating point (Cholesky succeeds on round-off).
    return info_ == 0 && pivotRatio() > 1e-12;
  }
  // X <- A^-1 X for nrhs columns (column-major, n rows each).
  void solve(double* X, int nrhs) const {
    if (n_ == 0 || nrhs == 0) return;
    int info = 0;
    Teuchos::LAPACK<int, double>().POTRS('L', n_, nrhs, L_.data(), n_, X, n_, &info);
  }
  void solve(std::vector<double>& x) const { solve(x.data(), 1); }  // x <- A^-1 x
  void solveLower(std::vector<double>& x) const { triangular('N', x); }   // x <- L^-1 x
  void solveUpperT(std::vector<double>& x) const { triangular('T', x); }  // x <- L^-T x
  int size() const { return n_; }
  // LAPACK's Cholesky went through (A positive definite in floating point),
  // whatever tryFactor's stricter pivot test said.
  bool positiveDefinite() const { return info_ == 0; }
  // The factor: n x n column-major, L in the lower triangle (the strict
  // upper triangle holds what A had there).
  const std::vector<double>& factor() const { return L_; }
  // (min_i L_ii / max_i L_ii)^2.
  double pivotRatio() const {
    double dmax = 0, dmin = 1e300;
    for (int i = 0; i < n_; ++i) {
      const double d = L_[static_cast<size_t>(i) * n_ + i];
      dmax = std::max(dmax, d * d), dmin = std::min(dmin, d * d);
    }
    return n_ == 0 ? 1.0 : dmin / dmax;
  }

 private:
  void triangular(char trans, std::vector<double>& x) const {
    if (n_ == 0) return;
    int info = 0;
    Teuchos::LAPACK<int, double>().TRTRS('L', trans, 'N', n_, 1, L_.data(), n_, x.data(), n_, &info);
  }

  std::vector<double> L_;
  int n_ = 0, info_ = 0;
};

}  // namespace Tribos
