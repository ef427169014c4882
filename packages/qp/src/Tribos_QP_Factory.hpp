// Tribos_QP_Factory.hpp: QP solvers by name, in the style of Belos' factory.
#pragma once

#include <string>

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_QP_Solver.hpp"

namespace Tribos {
namespace QP {

class QPSolverFactory {
 public:
  // name: "MPRGP", "MPGP" or "SMALBE"; params may be null (defaults).
  RCP<QPSolver> create(const std::string& name, RCP<Teuchos::ParameterList> params) const;
  Teuchos::Array<std::string> supportedSolverNames() const;
};

}  // namespace QP
}  // namespace Tribos
