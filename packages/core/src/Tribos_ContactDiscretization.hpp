// Tribos_ContactDiscretization.hpp: how the rows of a contact pair are formed
// (the contact search, Tribos_ContactSearch.hpp, forms them). In a parameter
// list the choice is a string ("Node To Segment", "Mortar"; the input's
// Contact/Pairs/NAME/Discretization) checked and mapped to the enum by
// discretizationValidator(). It lives in core beside the friction law
// (Tribos_FrictionLaw.hpp), where the XML converters of the validators of
// such choices are registered (Tribos_ValidatorXml.hpp).
//   Node To Segment  each slave node projected on the closest master facet
//   Mortar           dual mortar segments
#pragma once

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <istream>
#include <ostream>
#include <string>

#include "Tribos_Types.hpp"
#include "Tribos_ValidatorXml.hpp"

namespace Tribos {
namespace Contact {

enum class ContactDiscretization { NodeToSegment, Mortar };

inline const char* discretizationName(ContactDiscretization d) {
  return d == ContactDiscretization::Mortar ? "Mortar" : "Node To Segment";
}

// The enum as one word in text (NodeToSegment, Mortar): Teuchos' XML files
// write the validator's values so, and read them back.
inline std::ostream& operator<<(std::ostream& out, ContactDiscretization d) {
  return out << (d == ContactDiscretization::Mortar ? "Mortar" : "NodeToSegment");
}
inline std::istream& operator>>(std::istream& in, ContactDiscretization& d) {
  std::string word;
  in >> word;
  if (word == "Mortar") d = ContactDiscretization::Mortar;
  else if (word == "NodeToSegment") d = ContactDiscretization::NodeToSegment;
  else in.setstate(std::ios::failbit);
  return in;
}

// Accepts the two names, documents them and maps them to the enum.
inline RCP<const Teuchos::StringToIntegralParameterEntryValidator<ContactDiscretization>> discretizationValidator() {
  using Teuchos::tuple;
  static const auto validator = [] {
    registerValidatorConverters();
    return rcp(new Teuchos::StringToIntegralParameterEntryValidator<ContactDiscretization>(
        tuple<std::string>("Node To Segment", "Mortar"),
        tuple<std::string>(
            "each slave node projected on the closest master facet",
            "dual mortar: segments of slave and master facets, consistent weights (passes the patch test)"),
        tuple<ContactDiscretization>(ContactDiscretization::NodeToSegment, ContactDiscretization::Mortar),
        "Discretization"));
  }();
  return validator;
}

}  // namespace Contact
}  // namespace Tribos
