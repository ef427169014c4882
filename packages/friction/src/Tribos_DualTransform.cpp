#include "Tribos_DualTransform.hpp"

#include <Tpetra_Vector.hpp>

#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_QP_Utils.hpp"

namespace Tribos {
namespace Friction {

namespace {

// s A: the scale enters the alpha of the wrapped operator, so s A x costs
// one application of A and no extra pass over the vector.
class ScaledOperator : public Operator {
 public:
  ScaledOperator(RCP<const Operator> A, SC s) : A_(A), s_(s) {}
  RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    A_->apply(X, Y, mode, alpha * s_, beta);
  }

 private:
  RCP<const Operator> A_;
  SC s_;
};

// s C for the joint application C of A + rho G'G: s A + rho G'G = s (A +
// (rho / s) G'G).
class ScaledComplement : public QP::ProjectorComplement {
 public:
  ScaledComplement(RCP<const QP::ProjectorComplement> C, SC s) : C_(C), s_(s) {}
  void applyWithComplement(const Vector& x, SC rho, Vector& y) const override {
    C_->applyWithComplement(x, rho / s_, y);
    y.scale(s_);
  }

 private:
  RCP<const QP::ProjectorComplement> C_;
  SC s_;
};

// PAP x = P(A(P x)): one application of A per column. With a projector whose
// complement is G'G, also PAP x + rho (I - P) x from the same P x.
class ProjectedOperator : public Operator, public QP::ProjectorComplement {
 public:
  ProjectedOperator(RCP<const Operator> A, RCP<const Operator> P)
      : A_(A), P_(P), Px_(A->getDomainMap()), APx_(A->getRangeMap()) {}
  void applyWithComplement(const Vector& x, SC rho, Vector& y) const override {
    P_->apply(x, Px_);
    A_->apply(Px_, APx_);
    P_->apply(APx_, y);
    y.update(rho, x, -rho, Px_, 1.0);  // + rho (x - P x)
  }
  RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      P_->apply(*X.getVector(j), Px_);
      A_->apply(Px_, APx_);
      P_->apply(APx_, Px_);
      Y.getVectorNonConst(j)->update(alpha, Px_, beta);
    }
  }

 private:
  RCP<const Operator> A_, P_;
  mutable Vector Px_, APx_;
};

// v - A lambda~, given A lambda~.
RCP<const Vector> minus(const Vector& v, const Vector& Alambda) {
  auto out = rcp(new Vector(Alambda, Teuchos::Copy));
  out->update(1.0, v, -1.0);
  return out;
}

RCP<const Vector> applied(const Operator& P, const Vector& v) {
  auto out = rcp(new Vector(P.getRangeMap()));
  P.apply(v, *out);
  return out;
}

}  // namespace

DualTransformChain& DualTransformChain::add(RCP<DualTransform> t) {
  TRIBOS_REQUIRE(!t.is_null(), "DualTransformChain::add: the transform is null");
  transforms_.push_back(t);
  return *this;
}

void DualTransformChain::forward(ContactDual& dual) const {
  for (const auto& t : transforms_) t->forward(dual);
}

void DualTransformChain::back(Vector& x) const {
  for (auto t = transforms_.rbegin(); t != transforms_.rend(); ++t) (*t)->back(x);
}

HomogenizationTransform::HomogenizationTransform(RCP<const Vector> lambdaTilde) : lambdaTilde_(lambdaTilde) {
  TRIBOS_REQUIRE(!lambdaTilde_.is_null(), "HomogenizationTransform: the particular solution is null");
}

void HomogenizationTransform::forward(ContactDual& dual) {
  TRIBOS_REQUIRE(!dual.A.is_null() && !dual.b.is_null(), "HomogenizationTransform: the problem has no A or no b");
  Vector Alambda(dual.map());
  dual.A->apply(*lambdaTilde_, Alambda);
  if (!dual.bReference.is_null()) dual.bReference = minus(*dual.bReference, Alambda);
  dual.b = minus(*dual.b, Alambda);
  auto lt = lambdaTilde_->getData();
  const int nc = dual.numLocalContacts();
  std::vector<SC> center = dual.tangentCenter;
  center.resize(2 * nc, 0.0);
  bool shifted = false;
  for (int k = 0; k < nc; ++k) {
    dual.normalLower[k] -= lt[dual.normalRows[k]];
    dual.normalOffset[k] += lt[dual.normalRows[k]];
    for (int j = 0; j < 2; ++j) {
      const LO t = dual.tangentRows[2 * k + j];
      if (t >= 0) center[2 * k + j] -= lt[t];
      shifted = shifted || center[2 * k + j] != 0.0;
    }
  }
  // An empty centre list means all zero (the common case: lambda~ lives on
  // equality rows); keep it empty then.
  if (shifted) dual.tangentCenter = center;
}

void HomogenizationTransform::back(Vector& x) const { x.update(1.0, *lambdaTilde_, 1.0); }

void ProjectionTransform::forward(ContactDual& dual) {
  TRIBOS_REQUIRE(!dual.A.is_null() && !dual.b.is_null(), "ProjectionTransform: the problem has no A or no b");
  TRIBOS_REQUIRE(!P_.is_null(), "ProjectionTransform: the projector is null");
  auto PAP = rcp(new ProjectedOperator(dual.A, P_));
  dual.A = PAP;
  dual.jointHessian = complementIsGtG_ ? RCP<const QP::ProjectorComplement>(PAP) : Teuchos::null;
  dual.b = applied(*P_, *dual.b);
  if (!dual.bReference.is_null()) dual.bReference = applied(*P_, *dual.bReference);
}

namespace {

// y = D A D x for D = diag(d), d on the local rows.
class DiagonallyScaledOperator : public Operator {
 public:
  DiagonallyScaledOperator(RCP<const Operator> A, RCP<const Vector> d) : A_(A), d_(d) {}
  RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    // The work vectors are kept: the solvers apply A hundreds of times.
    if (DX_.is_null() || DX_->getNumVectors() != X.getNumVectors()) {
      DX_ = rcp(new MultiVector(X.getMap(), X.getNumVectors()));
      ADX_ = rcp(new MultiVector(Y.getMap(), X.getNumVectors()));
    }
    DX_->elementWiseMultiply(1.0, *d_, X, 0.0);
    A_->apply(*DX_, *ADX_);
    Y.elementWiseMultiply(alpha, *d_, *ADX_, beta);
  }

 private:
  RCP<const Operator> A_;
  RCP<const Vector> d_;
  mutable RCP<MultiVector> DX_, ADX_;
};

RCP<const Vector> timesDiagonal(const Vector& x, const Vector& d) {
  auto y = rcp(new Vector(x.getMap()));
  y->elementWiseMultiply(1.0, d, x, 0.0);
  return y;
}

}  // namespace

void DiagonalScalingTransform::forward(ContactDual& dual) {
  TRIBOS_REQUIRE(!dual.A.is_null() && !dual.b.is_null(), "DiagonalScalingTransform: the problem has no A or no b");
  TRIBOS_REQUIRE(dual.G.is_null(), "DiagonalScalingTransform: a dual with an equality constraint G x = 0");
  TRIBOS_REQUIRE(d_.size() == dual.b->getLocalLength(),
                 "DiagonalScalingTransform: " << d_.size() << " scales for " << dual.b->getLocalLength() << " rows");
  const int nc = dual.numLocalContacts();
  for (int k = 0; k < nc; ++k) {
    const SC dk = d_[dual.normalRows[k]];
    for (int j = 0; j < 2; ++j) {
      const LO t = dual.tangentRows[2 * k + j];
      TRIBOS_REQUIRE(t < 0 || d_[t] == dk, "DiagonalScalingTransform: the rows of contact " << k << " differ in scale");
    }
    dual.normalLower[k] /= dk;
    dual.normalOffset[k] /= dk;
    dual.slipBound[k] /= dk;
    if (!dual.tangentCenter.empty())
      for (int j = 0; j < 2; ++j) dual.tangentCenter[2 * k + j] /= dk;
  }
  for (SC v : d_) TRIBOS_REQUIRE(std::isfinite(v) && v > 0, "DiagonalScalingTransform: a scale that is not positive");
  auto d = rcp(new Vector(dual.map()));
  {
    auto v = d->getDataNonConst();
    for (size_t i = 0; i < d_.size(); ++i) v[i] = d_[i];
  }
  d_vector_ = d;
  dual.A = rcp(new DiagonallyScaledOperator(dual.A, d));
  dual.normAOf = Teuchos::null;
  dual.denseA = nullptr;
  dual.b = timesDiagonal(*dual.b, *d);
  if (!dual.bReference.is_null()) dual.bReference = timesDiagonal(*dual.bReference, *d);
  // (DAD)^-1 = D^-1 A^-1 D^-1.
  if (dual.preconditioner) {
    auto inverse = rcp(new Vector(dual.map()));
    inverse->reciprocal(*d);
    dual.preconditioner = [inner = dual.preconditioner, inverse](const std::string& name) -> RCP<const Operator> {
      const RCP<const Operator> M = inner(name);
      return M.is_null() ? M : RCP<const Operator>(rcp(new DiagonallyScaledOperator(M, inverse)));
    };
  }
}

void DiagonalScalingTransform::back(Vector& x) const {
  TRIBOS_REQUIRE(!d_vector_.is_null(), "DiagonalScalingTransform: back before forward");
  x.elementWiseMultiply(1.0, *d_vector_, x, 0.0);
}

void ScalingTransform::forward(ContactDual& dual) {
  TRIBOS_REQUIRE(!dual.A.is_null() && !dual.b.is_null(), "ScalingTransform: the problem has no A or no b");
  long ignored = 0;
  if (powerSteps_ > 0) norm_ = QP::estimateNorm(*dual.A, powerSteps_, ignored);
  scale_ = 1.0 / norm_;
  dual.A = rcp(new ScaledOperator(dual.A, scale_));
  // ||s A|| <= s norm_ = 1 by the same estimate: the solvers reuse it.
  dual.normAOf = dual.A;
  dual.normAEstimate = scale_ * norm_;
  if (dual.denseA) {
    dual.denseA = [dense = dual.denseA, s = scale_] {
      auto D = dense();
      for (double& d : D) d *= s;
      return D;
    };
  }
  if (!dual.jointHessian.is_null()) dual.jointHessian = rcp(new ScaledComplement(dual.jointHessian, scale_));
  // (s A)^-1 = A^-1 / s.
  if (dual.preconditioner) {
    dual.preconditioner = [inner = dual.preconditioner, s = scale_](const std::string& name) -> RCP<const Operator> {
      const RCP<const Operator> M = inner(name);
      return M.is_null() ? M : RCP<const Operator>(rcp(new ScaledOperator(M, 1.0 / s)));
    };
  }
  auto b = rcp(new Vector(*dual.b, Teuchos::Copy));
  b->scale(scale_);
  dual.b = b;
  if (!dual.bReference.is_null()) {
    auto r = rcp(new Vector(*dual.bReference, Teuchos::Copy));
    r->scale(scale_);
    dual.bReference = r;
  }
}

}  // namespace Friction
}  // namespace Tribos
