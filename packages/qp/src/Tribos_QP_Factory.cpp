#include "Tribos_QP_Factory.hpp"

#include "Tribos_Error.hpp"
#include "Tribos_QP_MPGP.hpp"
#include "Tribos_QP_MPRGP.hpp"
#include "Tribos_QP_SMALBE.hpp"

namespace Tribos {
namespace QP {

Teuchos::Array<std::string> QPSolverFactory::supportedSolverNames() const {
  return Teuchos::tuple<std::string>("MPRGP", "MPGP", "SMALBE");
}

RCP<QPSolver> QPSolverFactory::create(const std::string& name, RCP<Teuchos::ParameterList> params) const {
  if (name == "MPRGP") return Teuchos::rcp(new MPRGP(params));
  if (name == "MPGP") return Teuchos::rcp(new MPGP(params));
  if (name == "SMALBE") return Teuchos::rcp(new SMALBE(params));
  std::string valid;
  for (const auto& n : supportedSolverNames()) valid += (valid.empty() ? "" : ", ") + n;
  TRIBOS_REQUIRE(false, "QPSolverFactory: unknown QP solver name \"" << name << "\"; valid names: " << valid);
  return Teuchos::null;
}

}  // namespace QP
}  // namespace Tribos
