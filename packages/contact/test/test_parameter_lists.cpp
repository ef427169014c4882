// Tribos' valid parameter lists as Teuchos XML files, the way a Trilinos
// application keeps and exchanges them (Teuchos::writeParameterListToXmlFile,
// Teuchos::getParametersFromXmlFile):
//  - every valid list (ContactSolver's, FetiProblem's, FetiContactProblem's,
//    solveFeti's, the driver's input with its item lists, each QP solver's
//    of the QP factory) writes, reads back with the same entries, values,
//    documentation and validators (the same type, choices and ranges), and
//    its defaults pass the validators read back;
//  - the validators read back still refuse: a law "Stribeck", a contact
//    discretization "Surface", components "xw", a number out of range, a
//    string outside any list of choices; and those of Tribos' own types map
//    the names to their enums as before;
//  - ContactSolver as a Teuchos::ParameterListAcceptor: the valid list from
//    the object, a list set, read, refused and unset through the interface.
#include <Teuchos_ParameterListAcceptor.hpp>
#include <Teuchos_ParameterListAcceptorHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Teuchos_dyn_cast.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

#include "Tribos.hpp"
#include "Tribos_ComponentsValidator.hpp"
#include "Tribos_ContactDiscretization.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_QP_Factory.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;
using Teuchos::ParameterEntry;
using Teuchos::ParameterEntryValidator;
using Teuchos::ParameterList;
using Test::contains;
using Test::errorOf;

// Whether validator v refuses value (its validate() throws).
template <class T>
bool refuses(const ParameterEntryValidator& v, const T& value) {
  ParameterEntry probe(value);
  return !errorOf([&] { v.validate(probe, "probe", "list"); }).empty();
}

// What the comparison met: entries, validators, lists of choices, ranges.
struct Counts {
  int entries = 0, validators = 0, choices = 0, ranges = 0;
};

// A number validator's range read back, and a value outside it refused
// (by the original validator too: the probe is a real one).
template <class T>
void sameRange(const ParameterEntryValidator& a, const ParameterEntryValidator& b, const std::string& where,
               Teuchos::FancyOStream& out, bool& success, Counts& counts) {
  const auto* ra = dynamic_cast<const Teuchos::EnhancedNumberValidator<T>*>(&a);
  if (!ra) return;
  const auto* rb = dynamic_cast<const Teuchos::EnhancedNumberValidator<T>*>(&b);
  TEST_ASSERT(rb != nullptr);
  if (!rb) return;
  ++counts.ranges;
  if (rb->getMin() != ra->getMin() || rb->getMax() != ra->getMax()) {
    out << where << ": range [" << ra->getMin() << ", " << ra->getMax() << "] read back as [" << rb->getMin() << ", "
        << rb->getMax() << "]\n";
    success = false;
  }
  if (ra->getMin() > std::numeric_limits<T>::lowest() / 2) {
    const T below = ra->getMin() - (ra->getMin() > 0 ? ra->getMin() : T(1));
    TEST_ASSERT(refuses(a, below));
    if (!refuses(b, below)) out << where << ": " << below << " accepted after the round trip\n", success = false;
  }
}

// valid and back hold the same entries in the same order, with the same
// values, documentation and validators; each validator read back accepts
// the choices of the original and refuses what it refuses.
void sameLists(const ParameterList& valid, const ParameterList& back, const std::string& path,
               Teuchos::FancyOStream& out, bool& success, Counts& counts) {
  TEST_EQUALITY(back.numParams(), valid.numParams());
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const std::string where = path + "/" + name;
    if (!back.isParameter(name)) {
      out << where << ": missing after the round trip\n";
      success = false;
      continue;
    }
    const ParameterEntry& a = valid.entry(it);
    const ParameterEntry& b = back.getEntry(name);
    ++counts.entries;
    if (a.isList()) {
      TEST_ASSERT(b.isList());
      if (b.isList()) sameLists(valid.sublist(name), back.sublist(name), where, out, success, counts);
      continue;
    }
    if (!(a.getAny(false) == b.getAny(false))) out << where << ": " << a << " read back as " << b << "\n", success = false;
    if (b.docString() != a.docString()) out << where << ": documentation changed\n", success = false;
    const auto va = a.validator(), vb = b.validator();
    if (va.is_null() != vb.is_null()) out << where << ": validator lost or gained\n", success = false;
    if (va.is_null() || vb.is_null()) continue;
    ++counts.validators;
    if (vb->getXMLTypeName() != va->getXMLTypeName())
      out << where << ": " << va->getXMLTypeName() << " read back as " << vb->getXMLTypeName() << "\n", success = false;
    const auto sa = va->validStringValues(), sb = vb->validStringValues();
    TEST_EQUALITY(sb.is_null(), sa.is_null());
    if (!sa.is_null() && !sb.is_null()) {
      ++counts.choices;
      TEST_COMPARE_ARRAYS(*sb, *sa);
      for (const auto& s : *sa) TEST_ASSERT(!refuses(*vb, s));
      TEST_ASSERT(refuses(*va, std::string("Stribeck")));
      if (!refuses(*vb, std::string("Stribeck"))) out << where << ": \"Stribeck\" accepted after the round trip\n", success = false;
    }
    sameRange<double>(*va, *vb, where, out, success, counts);
    sameRange<int>(*va, *vb, where, out, success, counts);
  }
}

// valid written as an XML file and read back; the comparison above, and
// the defaults validated by what was read. Returns what was read.
RCP<ParameterList> roundTrip(const ParameterList& valid, const std::string& label, Teuchos::FancyOStream& out,
                             bool& success, int minimumValidators = 1) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("tribos_parameter_lists_" + std::to_string(::getpid()) + "_" + label + ".xml");
  RCP<ParameterList> back;
  const std::string error = errorOf([&] {
    Teuchos::writeParameterListToXmlFile(valid, file.string());
    back = Teuchos::getParametersFromXmlFile(file.string());
  });
  std::filesystem::remove(file);
  out << label << ": " << (error.empty() ? "written and read back" : error) << "\n";
  TEST_ASSERT(error.empty());
  if (back.is_null()) return back;
  Counts counts;
  sameLists(valid, *back, label, out, success, counts);
  TEST_ASSERT(Teuchos::haveSameValues(valid, *back));
  out << label << ": " << counts.entries << " entries, " << counts.validators << " validators (" << counts.choices
      << " lists of choices, " << counts.ranges << " ranges)\n";
  TEST_ASSERT(counts.validators >= minimumValidators);
  ParameterList defaults(valid);
  const std::string refused = errorOf([&] { defaults.validateParameters(*back); });
  if (!refused.empty()) out << label << ": the defaults do not pass the validators read back: " << refused << "\n";
  TEST_ASSERT(refused.empty());
  return back;
}

TEUCHOS_UNIT_TEST(ParameterLists, ContactSolverAsXml) {
  const auto back = roundTrip(*Contact::ContactSolver::validParameters(), "ContactSolver", out, success, 20);
  if (back.is_null()) return;
  // The law's validator read back refuses a law Tribos does not have,
  // naming it, and maps the names to the enum.
  ParameterList bad;
  bad.sublist("Friction").set("Law", "Stribeck");
  const std::string e = errorOf([&] { bad.validateParameters(*back); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "Stribeck") && contains(e, "Law"));
  const auto law = Teuchos::rcp_dynamic_cast<const Teuchos::StringToIntegralParameterEntryValidator<FrictionLaw>>(
      back->sublist("Friction").getEntry("Law").validator());
  TEST_ASSERT(!law.is_null());
  if (!law.is_null()) TEST_ASSERT(law->getIntegralValue("Coulomb") == FrictionLaw::Coulomb);
  // NSGS, which solves no FETI dual, is no choice there either.
  ParameterList nsgs;
  nsgs.set("Outer Algorithm", "NSGS");
  TEST_ASSERT(contains(errorOf([&] { nsgs.validateParameters(*back); }), "NSGS"));
  // The list read back is a list of parameters the solver takes.
  Contact::ContactSolver solver;
  const std::string taken = errorOf([&] { solver.setParameters(rcp(new ParameterList(*back))); });
  out << "the list read back as parameters: " << (taken.empty() ? "taken" : taken) << "\n";
  TEST_ASSERT(taken.empty());
}

TEUCHOS_UNIT_TEST(ParameterLists, FetiListsAsXml) {
  roundTrip(*Feti::FetiProblem::getValidParameters(), "FetiProblem", out, success, 5);
  roundTrip(*Contact::FetiContactProblem::getValidParameters(), "FetiContactProblem", out, success, 20);
  roundTrip(*Contact::fetiSolveParameters(), "fetiSolveParameters", out, success, 20);
}

TEUCHOS_UNIT_TEST(ParameterLists, QPFactoryListsAsXml) {
  const QP::QPSolverFactory factory;
  const auto names = factory.supportedSolverNames();
  TEST_ASSERT(names.size() >= 3);
  for (const auto& name : names)
    roundTrip(*factory.create(name, Teuchos::null)->getValidParameters(), "QP_" + name, out, success, 3);
}

TEUCHOS_UNIT_TEST(ParameterLists, DriverInputAsXml) {
  const auto valid = Input::validParameters();
  const auto back = roundTrip(*valid, "Input", out, success, 20);
  if (!back.is_null()) {
    ParameterList bad;
    bad.sublist("Contact").set("Friction Law", "Stribeck");
    TEST_ASSERT(contains(errorOf([&] { bad.validateParameters(*back); }), "Stribeck"));
  }
  roundTrip(Input::tractionItem(), "Input_traction", out, success, 0);
  roundTrip(Input::curveItem(), "Input_curve", out, success, 0);
  roundTrip(Input::bodyItem(valid->sublist("Material")), "Input_body", out, success, 0);
  // The Dirichlet item: Tribos' ComponentsValidator.
  const auto dirichlet = roundTrip(Input::dirichletItem(), "Input_dirichlet", out, success, 1);
  if (!dirichlet.is_null()) {
    const auto v = dirichlet->getEntry("Components").validator();
    TEST_ASSERT(!v.is_null() && v->getXMLTypeName() == componentsValidator()->getXMLTypeName());
    if (!v.is_null()) {
      TEST_ASSERT(!refuses(*v, std::string("xz")));
      TEST_ASSERT(refuses(*v, std::string("xw")));
      TEST_ASSERT(refuses(*v, std::string("")));
    }
  }
  // The pair item: the law and the contact discretization.
  const auto pair = roundTrip(Input::pairItem(valid->sublist("Contact")), "Input_pair", out, success, 3);
  if (!pair.is_null()) {
    const auto d = Teuchos::rcp_dynamic_cast<
        const Teuchos::StringToIntegralParameterEntryValidator<Contact::ContactDiscretization>>(
        pair->getEntry("Discretization").validator());
    TEST_ASSERT(!d.is_null());
    if (!d.is_null()) {
      TEST_ASSERT(d->getIntegralValue("Mortar") == Contact::ContactDiscretization::Mortar);
      TEST_ASSERT(d->getIntegralValue("Node To Segment") == Contact::ContactDiscretization::NodeToSegment);
      TEST_ASSERT(refuses(*d, std::string("Surface")));
    }
    TEST_ASSERT(refuses(*pair->getEntry("Friction Law").validator(), std::string("Stribeck")));
  }
}

// The enums in text, as the XML files hold the validators' values: each
// name reads back as its value, and a word that is none is a failed read.
TEUCHOS_UNIT_TEST(ParameterLists, EnumsAsText) {
  for (auto d : {Contact::ContactDiscretization::NodeToSegment, Contact::ContactDiscretization::Mortar}) {
    std::stringstream s;
    s << d;
    Contact::ContactDiscretization back = d == Contact::ContactDiscretization::Mortar
                                              ? Contact::ContactDiscretization::NodeToSegment
                                              : Contact::ContactDiscretization::Mortar;
    s >> back;
    TEST_ASSERT(!s.fail() && back == d);
  }
  std::stringstream word("Surface");
  Contact::ContactDiscretization d = Contact::ContactDiscretization::Mortar;
  word >> d;
  TEST_ASSERT(word.fail());
}

// ContactSolver through the interface any Trilinos solver's parameters are
// handled by.
TEUCHOS_UNIT_TEST(ParameterLists, ContactSolverIsParameterListAcceptor) {
  const RCP<Teuchos::ParameterListAcceptor> acceptor = rcp(new Contact::ContactSolver);
  TEST_ASSERT(acceptor->getValidParameters().get() == Contact::ContactSolver::validParameters().get());
  TEST_ASSERT(acceptor->getParameterList().is_null());
  // Teuchos' documentation of an acceptor's parameters.
  std::ostringstream doc;
  Teuchos::printValidParameters(*acceptor, doc);
  TEST_ASSERT(contains(doc.str(), "Outer Algorithm") && contains(doc.str(), "Friction"));

  auto p = Teuchos::parameterList("solver");
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", 0.3);
  acceptor->setParameterList(p);
  TEST_ASSERT(acceptor->getParameterList().get() == p.get());
  TEST_ASSERT(acceptor->getNonconstParameterList().get() == p.get());
  TEST_EQUALITY(p->get<std::string>("Outer Algorithm"), "Auto");  // the defaults, in the caller's list
  TEST_NOTHROW(p->validateParameters(*acceptor->getValidParameters()));
  const auto& solver = Teuchos::dyn_cast<Contact::ContactSolver>(*acceptor);
  TEST_ASSERT(solver.getFriction()[0].law == FrictionLaw::Coulomb);

  // A refused list leaves the one set.
  auto bad = Teuchos::parameterList("bad");
  bad->sublist("Friction").set("Law", "Stribeck");
  const std::string e = errorOf([&] { acceptor->setParameterList(bad); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "Stribeck") && contains(e, "Law"));
  TEST_ASSERT(acceptor->getParameterList().get() == p.get());
  TEST_ASSERT(solver.getFriction()[0].law == FrictionLaw::Coulomb);

  const auto unset = acceptor->unsetParameterList();
  TEST_ASSERT(unset.get() == p.get());
  TEST_ASSERT(acceptor->getParameterList().is_null());
  TEST_ASSERT(solver.getCurrentParameters().is_null());
  TEST_ASSERT(solver.getFriction()[0].law == FrictionLaw::Frictionless);
}

}  // namespace
