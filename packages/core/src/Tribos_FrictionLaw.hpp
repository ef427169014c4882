// Tribos_FrictionLaw.hpp: the friction law of a contact, one enum for every
// package. In a parameter list the law is a string ("Frictionless", "Tresca",
// "Coulomb") checked by frictionLawValidator() and read by frictionLaw();
// code holds the enum.
//   Frictionless  no tangential force (slip bound 0)
//   Tresca        a given slip bound g (a force per contact node)
//   Coulomb       the slip bound F lambda_N of the normal force
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <istream>
#include <ostream>
#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"
#include "Tribos_ValidatorXml.hpp"

namespace Tribos {

enum class FrictionLaw { Frictionless, Tresca, Coulomb };

inline const char* frictionLawName(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::Frictionless: return "Frictionless";
    case FrictionLaw::Tresca: return "Tresca";
    case FrictionLaw::Coulomb: return "Coulomb";
  }
  return "?";
}

// The law as its name in text (Teuchos' XML files write the validator's
// values so, and read them back).
inline std::ostream& operator<<(std::ostream& out, FrictionLaw law) { return out << frictionLawName(law); }
inline std::istream& operator>>(std::istream& in, FrictionLaw& law) {
  std::string name;
  in >> name;
  for (FrictionLaw l : {FrictionLaw::Frictionless, FrictionLaw::Tresca, FrictionLaw::Coulomb})
    if (name == frictionLawName(l)) {
      law = l;
      return in;
    }
  in.setstate(std::ios::failbit);
  return in;
}

// Accepts the three names, documents them and maps them to the enum. A list
// holding it writes as a Teuchos XML file and reads back with it
// (registerValidatorConverters(), Tribos_ValidatorXml.hpp).
inline RCP<const Teuchos::StringToIntegralParameterEntryValidator<FrictionLaw>> frictionLawValidator() {
  using Teuchos::tuple;
  static const auto validator = [] {
    registerValidatorConverters();
    return rcp(new Teuchos::StringToIntegralParameterEntryValidator<FrictionLaw>(
        tuple<std::string>("Frictionless", "Tresca", "Coulomb"),
        tuple<std::string>("no tangential force", "a given slip bound (a traction times the nodal area)",
                           "the slip bound F lambda_N of the normal force"),
        tuple<FrictionLaw>(FrictionLaw::Frictionless, FrictionLaw::Tresca, FrictionLaw::Coulomb), "Friction Law"));
  }();
  return validator;
}

// The law of that name; throws Error naming `what` (the parameter) and the
// three names when it is none of them.
inline FrictionLaw frictionLawNamed(const std::string& value, const std::string& what = "friction law") {
  for (FrictionLaw law : {FrictionLaw::Frictionless, FrictionLaw::Tresca, FrictionLaw::Coulomb})
    if (value == frictionLawName(law)) return law;
  throw Error(what + " = \"" + value + "\" is not a friction law (Frictionless, Tresca, Coulomb)");
}

// The law named by list[name].
inline FrictionLaw frictionLaw(const Teuchos::ParameterList& list, const std::string& name) {
  return frictionLawNamed(list.get<std::string>(name), list.name() + "/" + name);
}

}  // namespace Tribos
