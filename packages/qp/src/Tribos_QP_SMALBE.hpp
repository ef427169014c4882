// Tribos_QP_SMALBE.hpp: semi-monotonic augmented Lagrangian (Dostal) for
//   min 1/2 x'Ax - b'x  s.t.  G x = 0,  x in Omega.
// Outer loop on L(x, mu, rho) = f(x) + mu'Gx + rho/2 ||Gx||^2: the inner
// solver minimizes L over Omega (Hessian A + rho G'G, linear term b - G'mu) to
// ||g^P|| <= min(M ||Gx||, eta); then mu <- mu + rho G x, and M <- M/beta
// (or rho <- beta rho) when L did not grow by at least rho/2 ||Gx||^2.
#pragma once

#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_QP_Solver.hpp"
#include "Tribos_QP_Utils.hpp"

namespace Tribos {
namespace QP {

class SMALBE : public QPSolver {
 public:
  SMALBE();
  explicit SMALBE(RCP<Teuchos::ParameterList> params);

  void setEqualityConstraint(RCP<const EqualityConstraint> G);
  // Replaces the inner solver built from the "Inner Solver" sublist.
  void setInnerSolver(RCP<QPSolver> inner);
  RCP<QPSolver> innerSolver() const { return inner_; }
  // Initial multiplier for the next solve (a vector on G's range map).
  void setMultiplier(const Vector& mu0);
  // The multiplier mu of G x = 0 after the last solve.
  const Vector& multiplier() const;

  QPStatus solve(const Operator& A, const Vector& b, const ConstraintSet& Omega, Vector& x) override;
  void setTolerance(SC atol) override { toleranceOverride_ = atol; }
  void setHessianNorm(SC normA) override { hessianNorm_ = normA; }
  RCP<const Teuchos::ParameterList> getValidParameters() const override { return validParameters(); }
  // The same without a solver (as in friction's outer algorithms).
  static RCP<const Teuchos::ParameterList> validParameters();
  void setParameters(RCP<Teuchos::ParameterList> params) override;
  void setOutputStream(RCP<Teuchos::FancyOStream> out) override;
  RCP<const Vector> gradient() const override { return g_; }

  // Safeguards against an inconsistent set {Gx = 0} n Omega (defaults):
  // give up when M < M0 * minMFactor or rho > rho0 * maxRhoFactor.
  static constexpr SC minMFactor = 1e-10;
  static constexpr SC maxRhoFactor = 1e6;
  // ||Gx|| not reduced by 10% over a window of outer iterations whose inner
  // problems were solved: rho <- stagnationRhoFactor * rho.
  static constexpr SC stagnationRhoFactor = 10;

 private:
  struct Settings {
    CommonParameters common;
    SC M = 0, rho = 0, eta = 0.1, beta = 2.0;
    bool updateRho = false;  // "Penalty Update": "M" (default) or "rho"
    int maxOuter = 100;
    int stagnationWindow = 5;
  };
  SC innerTolerance(SC M, SC normGx, SC eta, SC tol) const;

  Settings s_;
  RCP<Teuchos::ParameterList> params_;
  RCP<const EqualityConstraint> G_;
  RCP<QPSolver> inner_;
  bool innerFromParameters_ = true;
  RCP<Vector> mu_, mu0_, g_;
  SC toleranceOverride_ = -1;
  SC hessianNorm_ = -1;
  QPOutput output_;
};

}  // namespace QP
}  // namespace Tribos
