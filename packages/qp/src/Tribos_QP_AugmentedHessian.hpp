// Tribos_QP_AugmentedHessian.hpp: H = A + rho G'G, the Hessian of the
// augmented Lagrangian in x. One application of H costs one application of A;
// the work vectors are allocated once, not per application.
#pragma once

#include <Tpetra_Vector.hpp>

#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

// A Hessian A = s P A0 P built with the orthogonal projector P onto ker G of
// the augmented Lagrangian's own constraint G, with orthonormal rows: then
// G'G = I - P and A + rho G'G = s P A0 P + rho (I - P), and the projection of
// x that P A0 P makes anyway gives the penalty term too. In FETI this saves
// one coarse solve and one product with G and with G' per application (a
// third of the coarse work, docs/scaling.md).
class ProjectorComplement {
 public:
  virtual ~ProjectorComplement() = default;
  // y = A x + rho (I - P) x, which equals A x + rho G'G x.
  virtual void applyWithComplement(const Vector& x, SC rho, Vector& y) const = 0;
};

class AugmentedHessian : public Operator {
 public:
  // joint: A's own way to apply A + rho G'G (null: A, then G and G').
  AugmentedHessian(const Operator& A, const EqualityConstraint& G, SC rho, const ProjectorComplement* joint = nullptr)
      : A_(A), G_(G), joint_(joint), rho_(rho), AX_(A.getRangeMap()), GX_(G.rangeMap()), GtGX_(A.getDomainMap()) {}
  RCP<const Map> getDomainMap() const override { return A_.getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_.getRangeMap(); }
  void setRho(SC rho) { rho_ = rho; }
  SC rho() const { return rho_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      auto Xj = X.getVector(j);
      if (joint_) {
        joint_->applyWithComplement(*Xj, rho_, AX_);
        Y.getVectorNonConst(j)->update(alpha, AX_, beta);
        continue;
      }
      A_.apply(*Xj, AX_);
      G_.apply(*Xj, GX_);
      G_.applyTranspose(GX_, GtGX_);
      AX_.update(rho_, GtGX_, 1.0);
      Y.getVectorNonConst(j)->update(alpha, AX_, beta);
    }
  }

 private:
  const Operator& A_;
  const EqualityConstraint& G_;
  const ProjectorComplement* joint_;
  SC rho_;
  mutable Vector AX_, GX_, GtGX_;
};

}  // namespace QP
}  // namespace Tribos
