// Tribos_BlockGaussSeidel.hpp: the inner minimization of Algorithm 1 split by
// constrained block Gauss-Seidel: MPRGP on the normal/equality block lambda_c
// (tangential block frozen), then MPGP on the tangential block lambda_t
// (lambda_c frozen), repeated "Sweeps" times. Augmented Lagrangian methods
// accept inexact inner solutions, so one sweep is allowed.
#pragma once

#include "Tribos_QP_Solver.hpp"

namespace Tribos {
namespace Friction {

class BlockGaussSeidel : public QP::QPSolver {
 public:
  BlockGaussSeidel(RCP<QP::QPSolver> mprgp, RCP<QP::QPSolver> mpgp, int sweeps, std::vector<char> normalMask,
                   std::vector<char> tangentMask);

  QP::QPStatus solve(const Operator& A, const Vector& b, const QP::ConstraintSet& Omega, Vector& x) override;
  void setTolerance(SC atol) override;
  void setHessianNorm(SC normA) override;
  RCP<const Teuchos::ParameterList> getValidParameters() const override;
  void setParameters(RCP<Teuchos::ParameterList>) override {}
  void setOutputStream(RCP<Teuchos::FancyOStream> out) override;
  RCP<const Vector> gradient() const override { return g_; }

  // Hessian multiplications spent in the bound (QPP) and circle (QPQ) solvers.
  long n_A_qpp() const { return n_A_qpp_; }
  long n_A_qpq() const { return n_A_qpq_; }

 private:
  RCP<QP::QPSolver> mprgp_, mpgp_;
  int sweeps_;
  std::vector<char> normalMask_, tangentMask_;
  SC tol_ = 0;
  RCP<Vector> g_;
  long n_A_qpp_ = 0, n_A_qpq_ = 0;
};

}  // namespace Friction
}  // namespace Tribos
