// Tribos_Validators.hpp: the parameter-list validators every package's
// getValidParameters() builds, written once.
#pragma once

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <sstream>
#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// Accepts numbers of type T in [lo, hi].
template <class T>
RCP<Teuchos::EnhancedNumberValidator<T>> range(T lo, T hi) {
  return rcp(new Teuchos::EnhancedNumberValidator<T>(lo, hi));
}

// pl[name] = value after the check of the entry's validator in 'valid' (the
// range documented for the parameter); the message names the parameter.
template <class T>
void setValidated(Teuchos::ParameterList& pl, const Teuchos::ParameterList& valid, const std::string& name, T value,
                  const std::string& context) {
  const auto validator = valid.getEntry(name).validator();
  if (!validator.is_null()) {
    Teuchos::ParameterList probe(valid.name());
    probe.set(name, value);
    try {
      validator->validate(probe.getEntry(name), name, valid.name());
    } catch (const std::exception&) {
      std::ostringstream s;
      s << context << ": " << name << " = " << value << " is outside the valid range ("
        << valid.getEntry(name).docString() << ")";
      throw Error(s.str());
    }
  }
  pl.set(name, value);
}

}  // namespace Tribos
