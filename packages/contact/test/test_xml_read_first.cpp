// An application that reads a Teuchos XML file of Tribos parameters before
// it builds any Tribos list or validator (its first act): the validators of
// Tribos' own types in it (the friction law, the contact discretization,
// the components of a Dirichlet condition) are read back, because their XML
// converters are registered when the library is loaded
// (Tribos_ValidatorXml.hpp), and refuse what they refused when written.
// Then the same list built by Tribos writes as the file holds it.
// Exit 0 when every check holds.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include <iostream>
#include <sstream>
#include <string>

#include "Tribos_ComponentsValidator.hpp"
#include "Tribos_ContactDiscretization.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;
using Teuchos::ParameterEntry;
using Teuchos::ParameterEntryValidator;
using Teuchos::ParameterList;
using Test::errorOf;

// The file: what list() below writes.
const char* const kXml = R"xml(<ParameterList name="Tribos validators">
  <Parameter docString="friction law" id="0" isDefault="false" isUsed="true" name="Law" type="string" validatorId="0" value="Coulomb"/>
  <Parameter docString="contact discretization" id="1" isDefault="false" isUsed="true" name="Discretization" type="string" validatorId="1" value="Mortar"/>
  <Parameter docString="fixed components" id="2" isDefault="false" isUsed="true" name="Components" type="string" validatorId="2" value="xz"/>
  <Validators>
    <Validator caseSensitive="true" defaultParameterName="Discretization" integralValue="Tribos::Contact::ContactDiscretization" type="StringIntegralValidator(Tribos::Contact::ContactDiscretization)" validatorId="1">
      <String integralValue="NodeToSegment" stringDoc="each slave node projected on the closest master facet" stringValue="Node To Segment"/>
      <String integralValue="Mortar" stringDoc="dual mortar: segments of slave and master facets, consistent weights (passes the patch test)" stringValue="Mortar"/>
    </Validator>
    <Validator caseSensitive="true" defaultParameterName="Friction Law" integralValue="Tribos::FrictionLaw" type="StringIntegralValidator(Tribos::FrictionLaw)" validatorId="0">
      <String integralValue="Frictionless" stringDoc="no tangential force" stringValue="Frictionless"/>
      <String integralValue="Tresca" stringDoc="a given slip bound (a traction times the nodal area)" stringValue="Tresca"/>
      <String integralValue="Coulomb" stringDoc="the slip bound F lambda_N of the normal force" stringValue="Coulomb"/>
    </Validator>
    <Validator type="Tribos::ComponentsValidator" validatorId="2"/>
  </Validators>
</ParameterList>
)xml";

// The list of the file, built from Tribos' validators.
ParameterList list() {
  ParameterList p("Tribos validators");
  p.set("Law", "Coulomb", "friction law", frictionLawValidator());
  p.set("Discretization", "Mortar", "contact discretization", Contact::discretizationValidator());
  p.set("Components", "xz", "fixed components", componentsValidator());
  return p;
}

bool refuses(const ParameterList& list, const std::string& name, const std::string& value) {
  const auto v = list.getEntry(name).validator();
  ParameterEntry probe(value);
  return !v.is_null() && !errorOf([&] { v->validate(probe, name, list.name()); }).empty();
}

}  // namespace

int main(int argc, char** argv) {
  Teuchos::GlobalMPISession mpi(&argc, &argv, nullptr);
  int passed = 0, failed = 0;
  auto check = [&](bool ok, const std::string& what) {
    std::cout << (ok ? "passed: " : "FAILED: ") << what << "\n";
    (ok ? passed : failed)++;
  };

  // First: the file, before any Tribos list exists.
  RCP<ParameterList> back;
  const std::string error = errorOf([&] { back = Teuchos::getParametersFromXmlString(kXml); });
  check(error.empty(), "the file read before any list was built" + (error.empty() ? "" : ": " + error));
  if (!back.is_null()) {
    for (const char* name : {"Law", "Discretization", "Components"})
      check(!back->getEntry(name).validator().is_null(), std::string(name) + " has its validator");
    check(refuses(*back, "Law", "Stribeck") && !refuses(*back, "Law", "Tresca"), "Law: Stribeck refused, Tresca taken");
    check(refuses(*back, "Discretization", "Surface") && !refuses(*back, "Discretization", "Node To Segment"),
          "Discretization: Surface refused, Node To Segment taken");
    check(refuses(*back, "Components", "xw") && !refuses(*back, "Components", "y"), "Components: xw refused, y taken");
    const auto law = Teuchos::rcp_dynamic_cast<const Teuchos::StringToIntegralParameterEntryValidator<FrictionLaw>>(
        back->getEntry("Law").validator());
    check(!law.is_null() && law->getIntegralValue("Coulomb") == FrictionLaw::Coulomb, "Law maps Coulomb to its enum");
  }

  // Then: the list Tribos builds writes as the file holds it.
  std::ostringstream written;
  Teuchos::writeParameterListToXmlOStream(list(), written);
  const auto again = Teuchos::getParametersFromXmlString(written.str());
  bool same = !back.is_null() && Teuchos::haveSameValues(*again, *back);
  if (same)
    for (const char* name : {"Law", "Discretization", "Components"})
      same = same && again->getEntry(name).validator()->getXMLTypeName() ==
                         back->getEntry(name).validator()->getXMLTypeName();
  check(same, "the list built now is the file's");
  if (!same) std::cout << "the list writes as:\n" << written.str();

  std::cout << passed << " passed, " << failed << " failed\n";
  return failed == 0 ? 0 : 1;
}
