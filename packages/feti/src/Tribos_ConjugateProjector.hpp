// Tribos_ConjugateProjector.hpp: the coarse space of FETI on positive
// definite subdomains (K + c M of an implicit time step, docs/dynamics.md),
// as a projector conjugate with respect to F.
//
// With the mass term every subdomain is invertible and TFETI's equality
// constraint G lambda = e is gone; but where c M is small against K (a step
// long against h / c_wave) each subdomain's rigid motions R_s are held by
// c R_s'M R_s alone, and F = B (K + c M)^-1 B' has 6 S eigenvalues of order
// 1 / (c m_s) far above the elastic part of its spectrum. A gradient step of
// the contact solvers is bounded by 2 / ||F||: it no longer moves the
// contact multipliers, and the solve stalls. The rigid motions' jumps on the
// equality rows (gluing and Dirichlet),
//   U = B_E R,   R = diag(R_s) from the subdomains' coordinates,
// span those directions, and the F-conjugate projector
//   P = I - U (U'FU)^+ U'F
// removes them (Dostal, Kozubek et al., transient TFETI with a conjugate
// projector): with lambda = lambda_U + P mu, lambda_U = U (U'FU)^+ U'h,
//   min 1/2 lambda'F lambda - h'lambda  =  min 1/2 mu'FP mu - (P'h)'mu + const,
// since P'F = FP and P lambda_U = 0. U vanishes on the contact rows, so
// lambda and mu agree there: bounds and friction cones stay as they are.
// U has dependent columns where a body's global rigid motion jumps nowhere
// on the equality rows (a body held by its contact alone): the pseudo-inverse
// keeps the independent combinations (an eigen-decomposition of U'U, whose
// scale is the geometry's, not F's). The contact rows keep those motions'
// outliers.
//
// Storage: U and FU by local dual row, their nonzeros only: a row of U
// touches the subdomains its row of B touches, a row of FU those and their
// neighbours (F couples the rows of a subdomain and of its neighbours), so
// the products with them cost a fraction of an application of F; and the
// factor of the reduced U'FU (replicated). Built with 6 S applications of
// F, in blocks of columns, once for the problem (FetiDual shares it across
// loads).
#pragma once

#include <vector>

#include "Tribos_DenseCholesky.hpp"
#include "Tribos_FetiOperators.hpp"

namespace Tribos {
namespace Feti {

class ConjugateProjector {
 public:
  // The largest coarse dimension 6 S built: U'FU and U'U are dense and
  // replicated, and their eigen-decomposition costs (6 S)^3.
  static constexpr int kMaxColumns = 3000;
  // Whether problem is one the projector serves: no subdomain floating
  // (no kernel, no coarse space), contact, some equality row, and 6 S at
  // most kMaxColumns.
  static bool applies(const FetiProblem& problem);
  // Collective.
  ConjugateProjector(RCP<const FetiProblem> problem, RCP<const DualOperator> F);

  // Independent directions kept (the rank of U).
  int rank() const { return rank_; }
  // The transformed dual works on mu in the complement of Im U (Q, the
  // orthogonal projector onto ker U'): U's directions are in FP's null
  // space, and an iterate that drifted into them by round-off would meet
  // the curvature of F there (1 / (c m)) less its cancellation, of either
  // sign. So lambda = lambda_U + P Q mu, and
  //   y = Q F P Q x   (its Hessian: one application of F),
  //   y = Q P' x      (its right-hand side from the original one),
  //   y = P Q x       (back to the original multipliers: one application of F).
  // Collective.
  void applyHessian(const Vector& x, Vector& y) const;
  void applyRightHandSide(const Vector& x, Vector& y) const;
  void applyBack(const Vector& x, Vector& y) const;
  // lambda_U = U (U'FU)^+ U' h. Collective.
  void particular(const Vector& h, Vector& lambdaU) const;

 private:
  RCP<const FetiProblem> problem_;
  RCP<const DualOperator> F_;
  // A tall matrix on the local dual rows by row: the nonzero columns of
  // row i are col[ptr[i] .. ptr[i+1]), their values val.
  struct Rows {
    std::vector<int> ptr{0}, col;
    std::vector<double> val;
    // Appends the nonzeros of the columns first .. first + block of M's
    // local rows to `pending` (per row), to be compressed by finish().
    void add(const MultiVector& M, int first, std::vector<std::vector<std::pair<int, double>>>& pending) const;
    void finish(std::vector<std::vector<std::pair<int, double>>>& pending);
    // y = M'x (columns entries, replicated); y <- y - M c.
    std::vector<double> transposeTimes(const Vector& x, int columns, const Comm& comm) const;
    void subtractTimes(const std::vector<double>& c, Vector& y) const;
  };
  Rows U_, FU_;
  // V: 6S x r, the independent combinations of U's columns (U V has rank
  // r); the factor of V'U'FU V.
  std::vector<double> V_;
  std::vector<double> inverseEigen_;  // 1 / the kept eigenvalues of U'U
  int columns_ = 0, rank_ = 0;
  DenseCholesky factor_;
  // c = V (V'U'FUV)^-1 V'U' x (6S coefficients, replicated). Collective.
  std::vector<double> coefficients(const Vector& x) const;
  // y = Q x = x - U V diag(1 / eigenvalues) V'U' x. Collective.
  void applyQ(const Vector& x, Vector& y) const;
  // y = P x given Fx. Collective.
  void applyP(const Vector& x, const Vector& Fx, Vector& y) const;
};

}  // namespace Feti
}  // namespace Tribos
