// Tribos_FetiOperators.hpp: the dual FETI operators.
//   F = B K+ B'          (DualOperator, a Tpetra::Operator counting n_A)
//   G = R'B', GG', P = I - G'(GG')^-1 G   (CoarseSpace)
// G has 6S rows (S subdomains); it is kept as sparse rows of G' on this
// rank's dual rows, and coarse vectors of length 6S are replicated on every
// rank. GG' is sparse (block (s,t) is nonzero only when subdomains s and t
// share a row of B): its 6 x 6 blocks are summed on each rank, gathered, and
// GG' is factored by sparse Cholesky (CHOLMOD) on every rank. A dense GG'
// would cost (6S)^2 memory and traffic per projection: 7.7 GB at S = 5184.
#pragma once

#include <string>
#include <vector>

#include "Tribos_DenseCholesky.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_LocalCsr.hpp"
#include "Tribos_LocalSolver.hpp"
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
  // Whether apply() reads dense blocks rounded to single precision on some
  // rank: it then applies F~ = B (K+)~ B', one fixed symmetric operator whose
  // entries lie within about 6e-8 (relative) of F's (docs/feti.md), and
  // applyExact gives F itself. The same on every rank.
  bool rounded() const { return rounded_; }
  // y = F x = B K+ B' x through the sparse factors, in double: a forward and
  // a backward solve per subdomain, whatever apply() reads. Not counted in
  // applications(). Collective.
  void applyExact(const Vector& x, Vector& y) const;
  // Applications since construction; a user's work is the difference of
  // two snapshots.
  long long applications() const { return n_A_; }
  // Wall time spent in apply since construction, on this rank.
  double seconds() const { return seconds_; }

 private:
  RCP<const FetiProblem> problem_;
  mutable RCP<Vector> p_, z_;
  mutable long long n_A_ = 0;
  mutable double seconds_ = 0;
  bool rounded_ = false;
};

using DenseCholesky = Tribos::DenseCholesky;  // Tribos_DenseCholesky.hpp

class CoarseSpace {
 public:
  explicit CoarseSpace(RCP<const FetiProblem> problem);

  int size() const { return n_; }  // total kernel dimension (6S in TFETI)
  // Memory of the sparse Cholesky factors of GG' and G_E G_E' on this rank, MB.
  double factorMemoryMb() const;
  // y = G x (replicated), x = G' y (local rows); rows restricted to a mask when given.
  void applyG(const Vector& x, std::vector<double>& y, const std::vector<char>* rows = nullptr) const;
  void applyGt(const std::vector<double>& y, Vector& x, const std::vector<char>* rows = nullptr) const;
  // Px = x - G'(GG')^-1 G x
  void project(const Vector& x, Vector& Px) const;
  // The orthonormalized constraint G^ = L^-1 G with GG' = LL', so G^'G^ = Q = I - P.
  void applyOrthonormal(const Vector& x, std::vector<double>& y) const;
  void applyOrthonormalTranspose(const std::vector<double>& y, Vector& x) const;
  // lambda~ with G lambda~ = e: G_E'(G_E G_E')^-1 e, supported on equality
  // rows only so that bound and friction constraints stay unshifted, when the
  // equality rows hold every rigid motion; otherwise (a body held by its
  // contact) the general G'(GG')^-1 e, and the constraints are shifted.
  void particularSolution(const std::vector<double>& e, Vector& lambdaTilde) const;
  // Whether the equality rows alone hold every rigid motion (G_E G_E' regular).
  bool equalityRowsHoldKernel() const { return equalityHoldsKernel_; }
  // alpha = (G_S G_S')^-1 G_S r: rigid-body amplitudes from the residual
  // r = F lambda - h, exact on rows S where B u = c holds (by default the
  // equality rows). Throws when the rows S do not fix every rigid motion.
  std::vector<double> amplitudes(const Vector& r, const std::vector<char>* rows = nullptr) const;
  // G_S G_S' for the rows S (all when null): sparse, both triangles, sorted
  // columns, replicated on every rank. Collective.
  LocalCsr gramian(const std::vector<char>* rows) const;
  // "Coarse Problem" = Auto splits the factors among the ranks from this
  // many coarse rows on (SplitCholesky).
  static constexpr int kAutoSplitRows = 3000;
  // Sparse Cholesky factor of G_S G_S', or null when it is singular (some
  // rigid motion touches no row S). Split among the ranks or whole on each
  // as "Coarse Problem" says (SplitCholesky). Collective.
  RCP<LocalSolver> factorGramian(const std::vector<char>* rows) const;
  // G Pi G' = GG' - sum_q (G q)(G q)' for the fixed directions q of a face
  // (the rows of `fixed`, unit vectors over this rank's dual rows; Pi the
  // projector onto their complement), factored; null when it is singular
  // (the free directions do not hold every rigid motion). Collective.
  RCP<LocalSolver> factorFaceGramian(const LocalCsr& fixed) const;
  // Tu = G'(G Pi G')^-1 G u with a factor from factorFaceGramian. Collective.
  void applyFace(const LocalSolver& factor, const Vector& u, Vector& Tu) const;
  // An orthonormal basis of the null space of G_S G_S' (coarse vectors):
  // the rigid motions that no row S touches. Only for error paths and
  // checks (an eigen-decomposition of the dense 6S x 6S Gram matrix: meant
  // for bodies held by contact alone, up to a few thousand subdomains).
  std::vector<std::vector<double>> nullSpace(const std::vector<char>* rows) const;
  // The rigid motions that no row S touches (G_S G_S' singular), named for a
  // person: "translation z", "rotation about x (axis through the centroid)",
  // or a fitted motion; empty when the rows S hold every rigid motion.
  // Collective.
  std::vector<std::string> freeMotions(const std::vector<char>* rows) const;
  // The coarse vector (kernel amplitudes of every subdomain) of the global
  // rigid motion j of the body: translations x, y, z (j = 0..2) and
  // rotations about the axes x, y, z through the centroid (j = 3..5).
  std::vector<double> globalMotion(int j) const;
  // Name of the global motion whose coarse vector is closest to alpha.
  std::string describeMotion(const std::vector<double>& alpha) const;

 private:
  bool equalityHoldsKernel_ = true;
  RCP<const FetiProblem> problem_;
  int n_ = 0;
  // G' on this rank's dual rows, one segment per subdomain a row touches:
  // the segment holds that subdomain's r_s values (the row of B R_s), which
  // are G' entries in the consecutive coarse columns segStart_ ...
  // segStart_ + r_s - 1. Row i has the segments segPtr_[i] .. segPtr_[i+1]-1
  // and its values start at valPtr_[i]. Against a CSR of G' this stores one
  // column index per subdomain instead of one per entry, and the products
  // run over contiguous blocks of r_s (docs/scaling.md).
  std::vector<int> segPtr_, segStart_, valPtr_;
  std::vector<double> segVal_;
  std::vector<int> blockLength_;  // r_s at coarse column ko[s]
  // An unfactored Cholesky solver for a Gram matrix, as "Coarse Problem" says.
  RCP<LocalSolver> newGramFactor() const;
  RCP<LocalSolver> GGt_, GEGEt_;  // factors of GG' and G_E G_E' (null: singular)
  mutable LocalCsr gram_;         // GG', kept once a face asks for it
  mutable std::vector<double> work_;
};

}  // namespace Feti
}  // namespace Tribos
