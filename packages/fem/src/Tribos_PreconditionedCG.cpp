#include "Tribos_PreconditionedCG.hpp"

#include <BelosLinearProblem.hpp>
#include <BelosSolverFactory.hpp>
#include <BelosTpetraAdapter.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

RCP<MueLuOperator> mueluPreconditioner(const RCP<CrsMatrix>& A, const RCP<MultiVector>& nullspace,
                                       Teuchos::ParameterList params) {
  params.sublist("user data").set("Nullspace", nullspace);
  return MueLu::CreateTpetraPreconditioner<SC, LO, GO, Node>(Teuchos::rcp_implicit_cast<Operator>(A), params);
}

CGResult preconditionedCG(const RCP<const Operator>& A, const RCP<Operator>& M, const Vector& b, Vector& x,
                          double tol, bool absolute, int maxIterations) {
  using Problem = Belos::LinearProblem<SC, MultiVector, Operator>;
  auto problem = rcp(new Problem(A, Teuchos::rcpFromRef(static_cast<MultiVector&>(x)),
                                 Teuchos::rcpFromRef(static_cast<const MultiVector&>(b))));
  problem->setLeftPrec(M);
  TRIBOS_REQUIRE(problem->setProblem(), "Belos could not set up the CG problem");
  auto params = Teuchos::parameterList();
  if (absolute) params->set("Implicit Residual Scaling", "None");
  params->set("Convergence Tolerance", tol);
  params->set("Maximum Iterations", maxIterations);
  params->set("Assert Positive Definiteness", false);
  Belos::SolverFactory<SC, MultiVector, Operator> factory;
  auto solver = factory.create("CG", params);
  solver->setProblem(problem);
  CGResult r;
  try {
    r.converged = solver->solve() == Belos::Converged;
  } catch (const std::exception& e) {
    throw Error(std::string("Belos CG failed: ") + e.what());
  }
  r.iterations = solver->getNumIters();
  return r;
}

}  // namespace Fem
}  // namespace Tribos
