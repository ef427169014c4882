// Tribos_ValidatorXml.hpp: Tribos' parameter lists as Teuchos XML files,
// validators included. Teuchos writes a validator (writeParameterListToXmlFile)
// and reads it back (getParametersFromXmlFile, XMLParameterListReader) only
// through a converter registered for its type in Teuchos::ValidatorXMLConverterDB.
// Teuchos registers those of its own validators (StringValidator,
// EnhancedNumberValidator<int>, <double>, ...); registerValidatorConverters()
// registers those of every other validator type a Tribos list holds, in
// this one place:
//   StringToIntegralParameterEntryValidator<FrictionLaw>     frictionLawValidator() (Tribos_FrictionLaw.hpp)
//   StringToIntegralParameterEntryValidator<Contact::ContactDiscretization>
//                                                            discretizationValidator() (Tribos_ContactDiscretization.hpp)
//   ComponentsValidator                                      componentsValidator() (Tribos_ComponentsValidator.hpp)
// A validator type added to a Tribos list is added here.
//
// It runs when the core library is loaded (a shared library) or, linked
// statically, before main() in any program that uses one of these
// validators; each function above calls it too before it builds its
// validator. So every valid list (ContactSolver's, FetiProblem's, the
// driver's input, ...) writes as XML and reads back with its validators,
// also in an application of the installed libraries that reads such a file
// before it builds any list. Calling it again does nothing.
#pragma once

namespace Tribos {

void registerValidatorConverters();

}  // namespace Tribos
