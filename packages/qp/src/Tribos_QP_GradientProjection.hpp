// Tribos_QP_GradientProjection.hpp: the common loop of MPRGP (Dostal-Schoeberl,
// simple bounds) and MPGP (Kucera / Dostal-Kozubek, separable convex sets):
// proportioning test ||beta||^2 <= Gamma^2 phit'phi, CG steps while the
// trial step stays feasible, expansion steps with the fixed step alpha_bar
// followed by projection, and proportioning steps that release the active set.
// The two algorithms differ only in the proportioning step.
#pragma once

#include <string>

#include "Tribos_QP_Solver.hpp"
#include "Tribos_QP_Utils.hpp"

namespace Tribos {
namespace QP {

class GradientProjectionSolver : public QPSolver {
 public:
  QPStatus solve(const Operator& A, const Vector& b, const ConstraintSet& Omega, Vector& x) override;
  void setTolerance(SC atol) override { toleranceOverride_ = atol; }
  void setHessianNorm(SC normA) override { hessianNorm_ = normA; }
  RCP<const Teuchos::ParameterList> getValidParameters() const override;
  void setParameters(RCP<Teuchos::ParameterList> params) override;
  void setOutputStream(RCP<Teuchos::FancyOStream> out) override { output_.setStream(out); }
  RCP<const Vector> gradient() const override { return g_; }

 protected:
  explicit GradientProjectionSolver(std::string name);
  // The valid parameters of the solver `name` (MPRGP and MPGP share them).
  static RCP<const Teuchos::ParameterList> validParameters(const std::string& name);

  // Check that this algorithm handles Omega (MPRGP refuses circles).
  virtual void checkSet(const ConstraintSet& Omega) const = 0;
  // One proportioning step: release components whose chopped gradient beta
  // dominates. Must update x and g = Ax - b; returns the number of A applications.
  virtual long proportioningStep(const Operator& A, const Vector& b, const ConstraintSet& Omega,
                                 SC alpha_bar, Vector& x, Vector& g, const Vector& beta) = 0;

  // p'Ap for a nonzero direction p; throws if the Hessian is not positive definite.
  static SC curvature(const Vector& p, const Vector& Ap, const char* where);
  // A work vector on x's map, kept between steps to avoid reallocation.
  Vector& work(const Vector& x);

  std::string name_;
  CommonParameters params_;
  SC toleranceOverride_ = -1;  // < 0: use params_
  SC hessianNorm_ = -1;        // <= 0: estimate
  QPOutput output_;
  RCP<Vector> g_;

 private:
  RCP<Vector> work_;
};

}  // namespace QP
}  // namespace Tribos
