// Tribos_DualTransform.hpp: transforms of the dual contact problem, after
// PERMON's QP transform chain: forward maps a ContactDual to an equivalent
// one, back maps a solution x of the transformed problem to a solution of
// the problem given to forward. A chain applies its transforms forward in
// the order they were added and back in the reverse order, so FETI contact,
// FCLIB and any user of ContactDual prepare their problem by the same code:
//   Homogenization  lambda = lambda~ + x with G lambda~ = e: G x = 0, bounds
//                   and disk centres shifted, b <- b - A lambda~; x <- x + lambda~.
//   Projection      A <- PAP, b <- Pb with P the orthogonal projector onto
//                   ker G (after homogenization); x unchanged.
//   Scaling         A <- s A, b <- s b with s = 1/||A||, so that ||A|| = 1, as
//                   the defaults of rho and M assume; x unchanged.
// Each maps bReference as it maps b, so relative tolerances keep referring
// to the same part of the right-hand side.
#pragma once

#include <vector>

#include "Tribos_ContactDual.hpp"

namespace Tribos {
namespace Friction {

class DualTransform {
 public:
  virtual ~DualTransform() = default;
  // The transformed problem replaces dual.
  virtual void forward(ContactDual& dual) = 0;
  // x: a solution of the transformed problem on input, of the original on output.
  virtual void back(Vector& x) const = 0;
};

class DualTransformChain {
 public:
  DualTransformChain& add(RCP<DualTransform> t);
  void forward(ContactDual& dual) const;
  void back(Vector& x) const;

 private:
  std::vector<RCP<DualTransform>> transforms_;
};

// lambda = lambda~ + x for the problem whose equality constraint reads
// G lambda = e, with lambda~ a particular solution (G lambda~ = e; ContactDual
// has no e: lambda~ carries it). The transformed problem
//   min 1/2 x'Ax - x'(b - A lambda~)  s.t.  G x = 0,
//   x_N,k >= l_k - lambda~_N,k,  ||x_T,k - (c_k - lambda~_T,k)|| <= g_k
// has the normal force x_N,k + (normalOffset_k + lambda~_N,k). forward costs
// one application of A (the caller's to count or not). A lambda~ that
// vanishes on the contact rows leaves bounds and centres as they are.
class HomogenizationTransform : public DualTransform {
 public:
  explicit HomogenizationTransform(RCP<const Vector> lambdaTilde);
  void forward(ContactDual& dual) override;
  void back(Vector& x) const override;  // x <- x + lambda~

 private:
  RCP<const Vector> lambdaTilde_;
};

// A <- PAP, b <- Pb, bReference <- P bReference with P the orthogonal
// projector onto ker G (PERMON: enforcing the equality by a projector). For
// x in ker G, x'Ax = x'PAPx and b'x = (Pb)'x, so a homogenized problem does
// not change; PAP is what FETI's projected Hessian is, and its spectrum on
// ker G is what the solvers' rates see. Each application of PAP costs one of
// A. back is the identity.
//
// complementIsGtG: the caller's G has orthonormal rows and P = I - G'G (FETI's
// orthonormalized coarse constraint); then the transformed dual carries
// jointHessian, which applies PAP + rho G'G with one projection less.
class ProjectionTransform : public DualTransform {
 public:
  explicit ProjectionTransform(RCP<const Operator> P, bool complementIsGtG = false)
      : P_(P), complementIsGtG_(complementIsGtG) {}
  void forward(ContactDual& dual) override;
  void back(Vector&) const override {}

 private:
  RCP<const Operator> P_;
  bool complementIsGtG_;
};

// x = D y with D = diag(d) > 0, one d for the three rows of a contact:
// A <- DAD, b <- Db (and bReference), and the constraints in y:
//   y_N,k >= l_k / d_k,  ||y_T,k - c_k / d_k|| <= g_k / d_k,
// the normal force d_k (y_N,k + normalOffset_k / d_k), Coulomb's cone
// ||y_T - c/d|| <= F (y_N + offset/d) with the same F (a cone is invariant
// under a uniform scaling of its node's rows). With d_i = 1 / sqrt(A_ii)
// (or an estimate of it) the diagonal of DAD is about 1: multipliers whose
// rows belong to nodes of very different mass or stiffness (a graded mesh:
// A_ii spreads as the cube of the element size) no longer spread A's
// spectrum, and the gradient steps of MPRGP, MPGP and Newton's CG see the
// conditioning of the scaled operator (Jacobi preconditioning that keeps
// bounds and cones what they are). Only for a dual without an equality
// constraint (G null): G D would replace G, and FETI's projector would no
// longer be orthogonal. back: x <- D x. d: this rank's rows.
class DiagonalScalingTransform : public DualTransform {
 public:
  explicit DiagonalScalingTransform(std::vector<SC> d) : d_(std::move(d)) {}
  void forward(ContactDual& dual) override;
  void back(Vector& x) const override;

 private:
  std::vector<SC> d_;
  RCP<const Vector> d_vector_;  // d on the dual's map (set by forward)
};

// A <- s A, b <- s b, bReference <- s bReference, s = 1/||A|| from
// powerSteps power iterations on A (their applications of A are the
// caller's to count or not). The minimizer does not change: back is the
// identity. F of FETI is of the order 1/E: without the scaling SMALBE
// compares ||g^P|| (displacement units) and ||G x|| (force units) with one
// tolerance; with ||A|| = 1 both are forces.
class ScalingTransform : public DualTransform {
 public:
  explicit ScalingTransform(int powerSteps) : powerSteps_(powerSteps) {}
  // A known ||A|| (the same operator scaled before, e.g. at another load):
  // no power steps.
  static RCP<ScalingTransform> withNorm(SC norm) {
    auto t = rcp(new ScalingTransform(0));
    t->norm_ = norm;
    return t;
  }
  void forward(ContactDual& dual) override;
  void back(Vector&) const override {}
  SC norm() const { return norm_; }    // ||A|| before the scaling (estimate)
  SC scale() const { return scale_; }  // s = 1/||A||

 private:
  int powerSteps_;
  SC norm_ = 1, scale_ = 1;
};

}  // namespace Friction
}  // namespace Tribos
