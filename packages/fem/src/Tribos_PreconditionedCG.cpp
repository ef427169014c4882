#include "Tribos_PreconditionedCG.hpp"

#include <BelosLinearProblem.hpp>
#include <BelosSolverFactory.hpp>
#include <BelosTpetraAdapter.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

RCP<MueLuOperator> mueluPreconditioner(const RCP<CrsMatrix>& A, const ElasticityModes& modes,
                                       Teuchos::ParameterList params) {
  // setCoarseLevelOnOneRank's move of the coarse level asks Zoltan2, which
  // asks for the coordinates even for one part.
  TRIBOS_REQUIRE(!modes.coordinates.is_null() || !params.get<bool>("repartition: enable", false),
                 "MueLu: moving the coarse level to one rank needs the node coordinates");
  params.sublist("user data").set("Nullspace", modes.nullspace);
  if (!modes.coordinates.is_null()) params.sublist("user data").set("Coordinates", modes.coordinates);
  return MueLu::CreateTpetraPreconditioner<SC, LO, GO, Node>(Teuchos::rcp_implicit_cast<Operator>(A), params);
}

void setCoarseLevelOnOneRank(Teuchos::ParameterList& p, int coarseMaxSize, long long rows, int numRanks) {
  p.set("coarse: max size", coarseMaxSize);
  if (numRanks > 1 && rows <= coarseMaxSize) {
    p.set("coarse: type", "RELAXATION");
    p.sublist("coarse: params").set("relaxation: type", "Symmetric Gauss-Seidel");
    p.sublist("coarse: params").set("relaxation: sweeps", 4);
    return;
  }
  p.set("coarse: type", "KLU2");
  if (numRanks == 1) return;
  p.set("repartition: enable", true);
  p.set("repartition: partitioner", "zoltan2");  // asks for the node coordinates
  p.set("repartition: start level", 1);
  // A level with fewer rows than this on some rank goes to rows /
  // coarseMaxSize parts: the coarsest to one. The finer levels keep their
  // distribution (no rebalancing for an imbalance of nonzeros).
  p.set("repartition: min rows per proc", coarseMaxSize);
  p.set("repartition: max imbalance", 1e300);
  p.set("repartition: remap parts", false);
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
