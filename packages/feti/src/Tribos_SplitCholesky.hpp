// Tribos_SplitCholesky.hpp: the Cholesky factor of a sparse symmetric
// positive definite matrix that every rank holds whole (FETI's Gram matrices
// GG' and G_E G_E'), shared out among the ranks instead of repeated on each.
//
// A's rows are split into one part per rank and a separator s such that no
// entry of A couples two parts. With the parts ordered first and the
// separator last, A = L L' with
//   L_pp L_pp' = A_pp,   L_sp = A_sp L_pp^-T,
//   L_ss L_ss' = A_ss - sum_p A_sp A_pp^-1 A_ps   (the Schur complement on s).
// Rank p factors only M_p = [A_pp A_ps; A_sp A_ss] with s ordered last: the
// trailing block Lt_p of that factor has Lt_p Lt_p' = A_ss - A_sp A_pp^-1 A_ps,
// so the Schur complement is sum_p (Lt_p Lt_p' - A_ss) + A_ss, summed over the
// ranks and factored densely on each. A solve runs the triangular solves of
// M_p's factor (a part of L, not all of it) and meets on the separator:
//   forward   z_p = L_pp^-1 b_p and L_sp z_p = -Lt_p t_p, where t_p is the
//             separator part of M_p's forward solve of [b_p; 0];
//             z_s = L_ss^-1 (b_s - sum_p L_sp z_p);
//   backward  y_s = L_ss^-T z_s, and M_p's backward solve of [z_p; Lt_p' y_s]
//             gives y_p = L_pp^-T (z_p - L_sp' y_s).
// The memory bandwidth one triangular solve needs is what limits FETI's coarse
// problem at a million dofs (docs/feti.md, "The coarse problem split among
// the ranks"), so each rank reading only its part is what pays.
//
// The parts come from METIS on the graph of A's row blocks (a subdomain's
// rigid modes stay together); the separator is every block of a part that
// couples to a block of a later part. When it would have more than
// maxSeparatorRows rows (the dense Schur complement would cost more than the
// split saves), or there are too few blocks, or one rank, every rank factors
// A whole, as before.
//
// Every call is collective: all ranks of the communicator at once, with the
// same A or the same right-hand sides.
#pragma once

#include <vector>

#include "Tribos_DenseCholesky.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

class SplitCholesky : public LocalSolver {
 public:
  static constexpr int kMaxSeparatorRows = 3000;
  // blockStart: rows [blockStart[b], blockStart[b+1]) stay in one part.
  SplitCholesky(RCP<const Comm> comm, std::vector<int> blockStart, int maxSeparatorRows = kMaxSeparatorRows);

  // A: the same on every rank, both triangles, sorted columns. Throws
  // (CollectiveError, on every rank) when A is not positive definite.
  void factor(const LocalCsr& A) override;
  // x = A^-1 b, b and x whole on every rank.
  void solve(const double* b, double* x, int nrhs = 1) const override;
  // x <- L^-1 P x, or P' L^-T x, for the L and P above (P orders each part
  // as its rank's factor does, the parts in rank order, then the separator);
  // the rows of L^-1 P G are orthonormal for A = GG', as with any Cholesky
  // factor. x whole on every rank.
  void solveFactor(double* x, bool transpose) const override;
  double pivotRatio() const override { return pivotRatio_; }
  std::string name() const override { return "CHOLMOD split among ranks"; }
  int size() const override { return n_; }
  double factorMemoryMb() const override;

  // Whether the factor is shared out (false: every rank factored A whole).
  bool isSplit() const { return whole_.is_null() && n_ > 0; }
  int separatorRows() const { return static_cast<int>(separator_.size()); }

 private:
  RCP<const Comm> comm_;
  std::vector<int> blockStart_;
  int maxSeparatorRows_;
  int n_ = 0;
  RCP<LocalSolver> whole_;           // A's factor on every rank (not split)
  RCP<LocalSolver> local_;           // M_p's factor, separator last
  std::vector<int> part_, separator_;  // this rank's part's rows, the separator's rows (increasing)
  std::vector<int> partRows_;        // every rank's part rows, in rank order
  std::vector<int> partCounts_, partOffsets_;  // their numbers and offsets by rank
  std::vector<double> Lt_;           // Lt_p, |s| x |s| column-major lower
  DenseCholesky schur_;              // L_ss
  double pivotRatio_ = 1;
  std::vector<int> partPosition_;    // the part's rows in M_p (its rows increasing)
  mutable std::vector<double> w_, zs_, yp_, gathered_;

  // Per row: the owning rank's number, or -1 for the separator; empty when A
  // is not split.
  std::vector<int> partition(const LocalCsr& A) const;
  void factorSplit(const LocalCsr& A, const std::vector<int>& rowPart);
  // b (whole) -> z_p in w_[0, |part|), z_s in zs_.
  void forward(const double* b) const;
  // z_p in w_[0, |part|), z_s in zs_ -> y_p in yp_, y_s in zs_.
  void backward() const;
  // y_p of every rank and y_s into x (whole).
  void gatherSolution(double* x) const;
};

}  // namespace Feti
}  // namespace Tribos
