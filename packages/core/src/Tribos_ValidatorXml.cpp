#include "Tribos_ValidatorXml.hpp"

#include <Teuchos_StandardValidatorXMLConverters.hpp>
#include <Teuchos_ValidatorXMLConverter.hpp>
#include <Teuchos_ValidatorXMLConverterDB.hpp>

#include "Tribos_ComponentsValidator.hpp"
#include "Tribos_ContactDiscretization.hpp"
#include "Tribos_FrictionLaw.hpp"

namespace Tribos {

namespace {

// ComponentsValidator has no state: its XML element is its type alone.
class ComponentsValidatorXMLConverter : public Teuchos::ValidatorXMLConverter {
 public:
  RCP<Teuchos::ParameterEntryValidator> convertXML(const Teuchos::XMLObject&,
                                                   const Teuchos::IDtoValidatorMap&) const override {
    return rcp(new ComponentsValidator);
  }
  void convertValidator(const RCP<const Teuchos::ParameterEntryValidator>, Teuchos::XMLObject&,
                        const Teuchos::ValidatortoIDMap&) const override {}
#ifdef HAVE_TEUCHOS_DEBUG
  RCP<const Teuchos::ParameterEntryValidator> getDummyValidator() const override {
    return rcp(new ComponentsValidator);
  }
#endif
};

void addConverters() {
  TEUCHOS_ADD_STRINGTOINTEGRALVALIDATOR_CONVERTER(FrictionLaw);
  TEUCHOS_ADD_STRINGTOINTEGRALVALIDATOR_CONVERTER(Contact::ContactDiscretization);
  Teuchos::ValidatorXMLConverterDB::addConverter(rcp(new ComponentsValidator),
                                                 rcp(new ComponentsValidatorXMLConverter));
}

// When the library is loaded (static initialization; Teuchos' database of
// converters is a function-local static, built on first use).
[[maybe_unused]] const bool registeredAtLoad = (registerValidatorConverters(), true);

}  // namespace

void registerValidatorConverters() {
  static const bool registered = (addConverters(), true);
  (void)registered;
}

}  // namespace Tribos
