// Tribos_FetiOperators.hpp: the dual FETI operators.
//   F = B K+ B'          (DualOperator, a Tpetra::Operator counting n_A)
//   G = R'B', GG', P = I - G'(GG')^-1 G   (CoarseSpace)
// G has 6S rows (S subdomains); it is kept as sparse rows of G' on this
// rank's dual rows, and coarse vectors of length 6S are replicated on every
// rank. GG' is small and dense: it is assembled by one reduction and
// factored (Cholesky) on every rank.
#pragma once

#include <vector>

#include "Tribos_FetiProblem.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

class DualOperator : public Operator {
 public:
  explicit DualOperator(RCP<const FetiProblem> problem);
  RCP<const Map> getDomainMap() const override { return problem_->dualMap(); }
  RCP<const Map> getRangeMap() const override { return problem_->dualMap(); }
  // Y = alpha F X + beta Y; every column is one Hessian multiplication (n_A).
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1.0,
             SC beta = 0.0) const override;
  long long applications() const { return n_A_; }
  void resetCount() { n_A_ = 0; }
  void setCount(long long n) { n_A_ = n; }

 private:
  RCP<const FetiProblem> problem_;
  mutable RCP<Vector> p_, z_;
  mutable long long n_A_ = 0;
};

// Dense symmetric positive definite matrix factored by Cholesky (LAPACK).
class DenseCholesky {
 public:
  void factor(std::vector<double> A, int n, const char* what);
  void solve(std::vector<double>& x) const;        // x <- A^-1 x
  void solveLower(std::vector<double>& x) const;   // x <- L^-1 x
  void solveUpperT(std::vector<double>& x) const;  // x <- L^-T x
  int size() const { return n_; }

 private:
  std::vector<double> L_;
  int n_ = 0;
};

class CoarseSpace {
 public:
  explicit CoarseSpace(RCP<const FetiProblem> problem);

  int size() const { return n_; }  // total kernel dimension (6S in TFETI)
  // y = G x (replicated), x = G' y (local rows); rows restricted to a mask when given.
  void applyG(const Vector& x, std::vector<double>& y, const std::vector<char>* rows = nullptr) const;
  void applyGt(const std::vector<double>& y, Vector& x, const std::vector<char>* rows = nullptr) const;
  // Px = x - G'(GG')^-1 G x
  void project(const Vector& x, Vector& Px) const;
  // The orthonormalized constraint G^ = L^-1 G with GG' = LL', so G^'G^ = Q = I - P.
  void applyOrthonormal(const Vector& x, std::vector<double>& y) const;
  void applyOrthonormalTranspose(const std::vector<double>& y, Vector& x) const;
  // lambda~ = G_E'(G_E G_E')^-1 e: supported on equality rows only, so bound
  // and friction constraints stay unshifted.
  void particularSolution(const std::vector<double>& e, Vector& lambdaTilde) const;
  // alpha = (G_E G_E')^-1 G_E r: rigid-body amplitudes from the residual
  // r = F lambda - h, exact on rows where B u = c holds (the equality rows).
  std::vector<double> amplitudes(const Vector& r) const;

 private:
  std::vector<double> gramian(const std::vector<char>* rows) const;
  RCP<const FetiProblem> problem_;
  int n_ = 0;
  std::vector<int> rowptr_, col_;  // G' rows on this rank's dual rows
  std::vector<double> val_;
  DenseCholesky GGt_, GEGEt_;
};

}  // namespace Feti
}  // namespace Tribos
