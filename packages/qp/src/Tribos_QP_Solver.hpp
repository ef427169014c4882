// Tribos_QP_Solver.hpp: the interface of every QP solver
//   min 1/2 x'Ax - b'x  subject to  x in Omega.
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_QP_ConstraintSet.hpp"
#include "Tribos_QP_Status.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

class QPSolver {
 public:
  virtual ~QPSolver() = default;

  // Minimizes from the initial x (projected onto Omega first).
  virtual QPStatus solve(const Operator& A, const Vector& b, const ConstraintSet& Omega, Vector& x) = 0;

  // Absolute tolerance on ||g^P|| for the next solves (overrides the
  // parameters' max(rtol ||b||, atol)).
  virtual void setTolerance(SC atol) = 0;
  // Upper estimate of ||A|| for alpha_bar; <= 0 means "estimate by power iterations".
  virtual void setHessianNorm(SC normA) = 0;

  virtual RCP<const Teuchos::ParameterList> getValidParameters() const = 0;
  virtual void setParameters(RCP<Teuchos::ParameterList> params) = 0;
  virtual void setOutputStream(RCP<Teuchos::FancyOStream> out) = 0;

  // The gradient g = Ax - b at the x returned by the last solve, when the
  // solver keeps it (null otherwise); lets SMALBE avoid one more A x.
  virtual RCP<const Vector> gradient() const { return Teuchos::null; }
};

enum class Verbosity { None = 0, Low = 1, Medium = 2, High = 3 };

}  // namespace QP
}  // namespace Tribos
