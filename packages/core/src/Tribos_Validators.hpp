// Tribos_Validators.hpp: the parameter-list validators every package's
// getValidParameters() builds, written once.
#pragma once

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include "Tribos_Types.hpp"

namespace Tribos {

// Accepts numbers of type T in [lo, hi].
template <class T>
RCP<Teuchos::EnhancedNumberValidator<T>> range(T lo, T hi) {
  return rcp(new Teuchos::EnhancedNumberValidator<T>(lo, hi));
}

}  // namespace Tribos
