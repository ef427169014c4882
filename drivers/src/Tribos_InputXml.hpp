// Tribos_InputXml.hpp: the parameters of a run written back as a parameter
// file: what `tribos --print-parameters` prints and what every run leaves in
// its result set (BASE.parameters.xml), so that a run can be repeated from
// the list it actually used, defaults included.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace Input {

// The default parameters with "Sublist/Key=value" overrides applied,
// validated as read() validates a file (an input file with no entries).
RCP<Teuchos::ParameterList> defaults(const std::vector<std::string>& overrides);

// A validated list (read(), validate() or defaults(): every default filled)
// as Teuchos XML that read() accepts again and turns into the same list.
// Every value carries the documentation of its valid parameter as
// docString, followed by its valid values or range; entries come in the
// order of validParameters(), the conditions of Boundary Conditions in the
// order of the input.
std::string toXml(const Teuchos::ParameterList& params);

}  // namespace Input
}  // namespace Tribos
