// Tribos_QP_AugmentedLagrangian.hpp: the outer step of SMALBE, shared by
// SMALBE and by the fused loop of Algorithm 2 (packages/friction), whose
// inner step is a different minimization but whose multiplier update is the
// same:
//   L(x, mu, rho) = 1/2 x'(A + rho G'G)x - (b - G'mu)'x
//   inner: minimize L over Omega with the Hessian A + rho G'G and b - G'mu
//   outer: mu <- mu + rho G x; the semi-monotonicity test asks whether L grew
//          by at least rho/2 ||Gx||^2 since the previous outer step (if not,
//          the caller lowers M or raises rho).
#pragma once

#include <Tpetra_Vector.hpp>

#include "Tribos_QP_AugmentedHessian.hpp"
#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_QP_Utils.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

// G'G, to bound ||A + rho G'G|| <= ||A|| + rho ||G'G||.
class NormalOperator : public Operator {
 public:
  NormalOperator(const EqualityConstraint& G, RCP<const Map> xmap)
      : G_(G), xmap_(xmap), Gx_(G.rangeMap()), GtGx_(xmap) {}
  RCP<const Map> getDomainMap() const override { return xmap_; }
  RCP<const Map> getRangeMap() const override { return xmap_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      G_.apply(*X.getVector(j), Gx_);
      G_.applyTranspose(Gx_, GtGx_);
      Y.getVectorNonConst(j)->update(alpha, GtGx_, beta);
    }
  }

 private:
  const EqualityConstraint& G_;
  RCP<const Map> xmap_;
  mutable Vector Gx_, GtGx_;
};

// Residual balancing of the penalty (the rule used for ADMM penalties): rho
// too small leaves G lambda behind the projected gradient, since the
// multiplier update gains only a factor of about 1 + rho sigma per outer
// iteration (sigma: curvature of the dual function); rho too large couples
// the normal and tangential blocks through rho G'G, so that the Gauss-Seidel
// sweeps leave g^P behind. Move rho by a factor towards the lagging residual
// (normGP: the other residual, e.g. Newton's ||Phi||), within [lowest, highest].
struct RhoBalancing {
  SC ratio, factor, lowest, highest;
  SC update(SC rho, SC normGx, SC normGP) const {
    if (ratio == 0) return rho;
    if (normGx > ratio * normGP && rho * factor <= highest) return rho * factor;
    if (normGP > ratio * normGx && rho / factor >= lowest) return rho / factor;
    return rho;
  }
};

class AugmentedLagrangian {
 public:
  // What an outer step leaves: ||Gx||, L(x, mu, rho) before the multiplier
  // update, and whether L grew by less than rho/2 ||Gx||^2.
  struct Step {
    SC normGx = 0, L = 0;
    bool grewTooLittle = false;
  };

  // joint: see AugmentedHessian (null: A, then G and G').
  AugmentedLagrangian(const Operator& A, const EqualityConstraint& G, const ProjectorComplement* joint = nullptr)
      : G_(G), H_(A, G, 0.0, joint), mu_(rcp(new Vector(G.rangeMap()))), Gx_(G.rangeMap()),
        Gtmu_(A.getDomainMap()), bIn_(A.getDomainMap()) {}

  // The multiplier mu (set it for a warm start).
  const RCP<Vector>& multiplier() const { return mu_; }
  // ||G'G|| by power iterations (not Hessian work).
  SC normGtG(int powerIterations) const {
    if (G_.rangeMap()->getGlobalNumElements() == 0) return 0;  // no constraint rows: G'G = 0
    long notCounted = 0;
    return estimateNorm(NormalOperator(G_, bIn_.getMap()), powerIterations, notCounted);
  }
  SC normGx(const Vector& x) const {
    G_.apply(x, Gx_);
    return Gx_.norm2();
  }
  // The inner problem of the current mu: Hessian A + rho G'G, linear term b - G'mu.
  const AugmentedHessian& hessian(SC rho) {
    H_.setRho(rho);
    return H_;
  }
  const Vector& linearTerm(const Vector& b) {
    G_.applyTranspose(*mu_, Gtmu_);
    bIn_.update(1.0, b, -1.0, Gtmu_, 0.0);
    return bIn_;
  }
  // After the inner solve: x and the gradient g = (A + rho G'G)x - (b - G'mu)
  // there; then mu <- mu + rho G x.
  Step update(const Vector& x, const Vector& g, SC rho) {
    Step s;
    G_.apply(x, Gx_);
    s.normGx = Gx_.norm2();
    s.L = 0.5 * (x.dot(g) - x.dot(bIn_));  // L(x, mu, rho) = 1/2 x'(g - b_in)
    mu_->update(rho, Gx_, 1.0);             // now g = Ax - b + G'mu
    s.grewTooLittle = s.L < Lprev_ + 0.5 * rho * s.normGx * s.normGx;
    Lprev_ = s.L;
    return s;
  }

 private:
  const EqualityConstraint& G_;
  AugmentedHessian H_;
  RCP<Vector> mu_;
  mutable Vector Gx_;
  Vector Gtmu_, bIn_;
  SC Lprev_ = 0;
};

}  // namespace QP
}  // namespace Tribos
