#include "Tribos_QP_Factory.hpp"

#include "Tribos_QP_MPGP.hpp"
#include "Tribos_QP_MPRGP.hpp"
#include "Tribos_QP_SMALBE.hpp"

namespace Tribos {
namespace QP {

const QPSolverRegistry& qpSolvers() {
  static const QPSolverRegistry registry = [] {
    QPSolverRegistry r("QP solver");
    r.add("MPRGP", [](RCP<Teuchos::ParameterList> p) -> RCP<QPSolver> { return rcp(new MPRGP(p)); },
          "bound constraints: modified proportioning with reduced gradient projections");
    r.add("MPGP", [](RCP<Teuchos::ParameterList> p) -> RCP<QPSolver> { return rcp(new MPGP(p)); },
          "separable convex constraints (bounds, disks): modified proportioning with gradient projections");
    r.add("SMALBE", [](RCP<Teuchos::ParameterList> p) -> RCP<QPSolver> { return rcp(new SMALBE(p)); },
          "equality constraints by semimonotonic augmented Lagrangians, an inner solver for the rest");
    return r;
  }();
  return registry;
}

Teuchos::Array<std::string> QPSolverFactory::supportedSolverNames() const {
  const auto names = qpSolvers().names();
  return Teuchos::Array<std::string>(names.begin(), names.end());
}

RCP<QPSolver> QPSolverFactory::create(const std::string& name, RCP<Teuchos::ParameterList> params) const {
  return qpSolvers().create(name, params);
}

}  // namespace QP
}  // namespace Tribos
