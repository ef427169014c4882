// Tribos_QP_AugmentedHessian.hpp: H = A + rho G'G, the Hessian of the
// augmented Lagrangian in x. One application of H costs one application of A;
// the work vectors are allocated once, not per application.
#pragma once

#include <Tpetra_Vector.hpp>

#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

class AugmentedHessian : public Operator {
 public:
  AugmentedHessian(const Operator& A, const EqualityConstraint& G, SC rho)
      : A_(A), G_(G), rho_(rho), AX_(A.getRangeMap()), GX_(G.rangeMap()), GtGX_(A.getDomainMap()) {}
  RCP<const Map> getDomainMap() const override { return A_.getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_.getRangeMap(); }
  void setRho(SC rho) { rho_ = rho; }
  SC rho() const { return rho_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      auto Xj = X.getVector(j);
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
  SC rho_;
  mutable Vector AX_, GX_, GtGX_;
};

}  // namespace QP
}  // namespace Tribos
