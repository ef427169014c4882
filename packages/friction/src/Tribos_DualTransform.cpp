#include "Tribos_DualTransform.hpp"

#include <Tpetra_Vector.hpp>

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

void ScalingTransform::forward(ContactDual& dual) {
  TRIBOS_REQUIRE(!dual.A.is_null() && !dual.b.is_null(), "ScalingTransform: the problem has no A or no b");
  long ignored = 0;
  norm_ = QP::estimateNorm(*dual.A, powerSteps_, ignored);
  scale_ = 1.0 / norm_;
  dual.A = rcp(new ScaledOperator(dual.A, scale_));
  auto b = rcp(new Vector(*dual.b, Teuchos::Copy));
  b->scale(scale_);
  dual.b = b;
  dual.referenceNorm *= scale_;
}

}  // namespace Friction
}  // namespace Tribos
