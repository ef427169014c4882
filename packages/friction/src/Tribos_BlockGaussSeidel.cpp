#include "Tribos_BlockGaussSeidel.hpp"

#include <Tpetra_Vector.hpp>

#include "Tribos_QP_ConstraintSet.hpp"

namespace Tribos {
namespace Friction {

BlockGaussSeidel::BlockGaussSeidel(RCP<QP::QPSolver> mprgp, RCP<QP::QPSolver> mpgp, int sweeps,
                                   std::vector<char> normalMask, std::vector<char> tangentMask)
    : mprgp_(mprgp), mpgp_(mpgp), sweeps_(sweeps), normalMask_(std::move(normalMask)), tangentMask_(std::move(tangentMask)) {}

void BlockGaussSeidel::setTolerance(SC atol) {
  tol_ = atol;
  mprgp_->setTolerance(atol);
  mpgp_->setTolerance(atol);
}

void BlockGaussSeidel::setHessianNorm(SC normA) {
  mprgp_->setHessianNorm(normA);
  mpgp_->setHessianNorm(normA);
}

void BlockGaussSeidel::setOutputStream(RCP<Teuchos::FancyOStream> out) {
  mprgp_->setOutputStream(out);
  mpgp_->setOutputStream(out);
}

RCP<const Teuchos::ParameterList> BlockGaussSeidel::getValidParameters() const {
  return Teuchos::parameterList("Block Gauss-Seidel");
}

QP::QPStatus BlockGaussSeidel::solve(const Operator& A, const Vector& b, const QP::ConstraintSet& Omega, Vector& x) {
  const QP::ConstraintSet normalSet = Omega.fixedOutside(normalMask_);
  const QP::ConstraintSet tangentSet = Omega.fixedOutside(tangentMask_);
  QP::QPStatus st;
  g_ = rcp(new Vector(x.getMap()));
  Vector gP(x.getMap());
  for (int sweep = 0; sweep < sweeps_; ++sweep) {
    const QP::QPStatus sc = mprgp_->solve(A, b, normalSet, x);
    const QP::QPStatus st2 = mpgp_->solve(A, b, tangentSet, x);
    n_A_qpp_ += sc.n_A;
    n_A_qpq_ += st2.n_A;
    st.n_A += sc.n_A + st2.n_A;
    st.iterations += sc.iterations + st2.iterations;
    st.cg_steps += sc.cg_steps + st2.cg_steps;
    st.expansion_steps += sc.expansion_steps + st2.expansion_steps;
    st.proportioning_steps += sc.proportioning_steps + st2.proportioning_steps;
    // The MPGP gradient is g = Ax - b at the final x on every component.
    Tpetra::deep_copy(*g_, *mpgp_->gradient());
    Omega.projectedGradient(x, *g_, gP);
    st.norm_gP = gP.norm2();
    if (st.norm_gP <= tol_) {
      st.converged = true;
      st.reason = "||g^P|| <= tolerance after " + std::to_string(sweep + 1) + " sweeps";
      return st;
    }
  }
  st.reason = "sweeps done";
  return st;
}

}  // namespace Friction
}  // namespace Tribos
