// Tribos_ComponentsValidator.hpp: the displacement components a Dirichlet
// condition fixes, a string of the letters x, y, z ("xyz", "z", "xz"), as a
// parameter-list validator (the input's Boundary Conditions/Dirichlet/NAME/
// Components). Its XML converter is registered by
// registerValidatorConverters() (Tribos_ValidatorXml.hpp).
#pragma once

#include <Teuchos_ParameterEntryValidator.hpp>

#include <ostream>
#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"
#include "Tribos_ValidatorXml.hpp"

namespace Tribos {

// Accepts a non-empty string of x, y and z; refuses anything else with a
// Tribos::Error naming the parameter.
class ComponentsValidator : public Teuchos::ParameterEntryValidator {
 public:
  void validate(const Teuchos::ParameterEntry& entry, const std::string& name, const std::string& list) const override {
    const std::string v = Teuchos::any_cast<std::string>(entry.getAny());
    bool ok = !v.empty();
    for (char c : v) ok = ok && (c == 'x' || c == 'y' || c == 'z');
    TRIBOS_REQUIRE(ok, "parameter \"" << list << "/" << name << "\" = \"" << v
                                      << "\": valid values are non-empty combinations of x, y, z (e.g. \"xyz\", \"z\")");
  }
  const std::string getXMLTypeName() const override { return "Tribos::ComponentsValidator"; }
  void printDoc(const std::string& doc, std::ostream& out) const override { out << "# " << doc << "\n"; }
  ValidStringsList validStringValues() const override { return Teuchos::null; }
};

inline RCP<const ComponentsValidator> componentsValidator() {
  static const auto validator = [] {
    registerValidatorConverters();
    return rcp(new ComponentsValidator);
  }();
  return validator;
}

}  // namespace Tribos
