// Tribos_QP_Factory.hpp: QP solvers by name, in the style of Belos' factory:
// one registry (Tribos_Registry.hpp) holds every solver; the factory and the
// parameter validators that choose a QP solver ask it.
#pragma once

#include <string>

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_QP_Solver.hpp"
#include "Tribos_Registry.hpp"

namespace Tribos {
namespace QP {

// "MPRGP", "MPGP", "SMALBE": maker(params), params may be null (defaults).
using QPSolverRegistry = Registry<QPSolver, RCP<Teuchos::ParameterList>>;
const QPSolverRegistry& qpSolvers();

class QPSolverFactory {
 public:
  // name: "MPRGP", "MPGP" or "SMALBE"; params may be null (defaults).
  RCP<QPSolver> create(const std::string& name, RCP<Teuchos::ParameterList> params) const;
  Teuchos::Array<std::string> supportedSolverNames() const;
};

}  // namespace QP
}  // namespace Tribos
