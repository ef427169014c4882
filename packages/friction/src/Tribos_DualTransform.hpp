// Tribos_DualTransform.hpp: transforms of the dual contact problem, after
// PERMON's QP transform chain: forward maps a ContactDual to an equivalent
// one, back maps a solution x of the transformed problem to a solution of
// the problem given to forward. A chain applies its transforms forward in
// the order they were added and back in the reverse order, so FETI contact,
// FCLIB and any user of ContactDual prepare their problem by the same code:
//   Scaling  A <- s A, b <- s b with s = 1/||A||, so that ||A|| = 1, as the
//            defaults of rho and M assume; x unchanged.
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

// A <- s A, b <- s b, referenceNorm <- s referenceNorm, s = 1/||A|| from
// powerSteps power iterations on A (their applications of A are the
// caller's to count or not). The minimizer does not change: back is the
// identity. F of FETI is of the order 1/E: without the scaling SMALBE
// compares ||g^P|| (displacement units) and ||G x|| (force units) with one
// tolerance; with ||A|| = 1 both are forces.
class ScalingTransform : public DualTransform {
 public:
  explicit ScalingTransform(int powerSteps) : powerSteps_(powerSteps) {}
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
