#include "Tribos_InputXml.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListWriter.hpp>

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_Input.hpp"

namespace Tribos {
namespace Input {

using Teuchos::ParameterEntry;
using Teuchos::ParameterList;

namespace {

template <class T>
bool describeRange(const Teuchos::ParameterEntryValidator* v, std::ostream& os) {
  const auto* range = dynamic_cast<const Teuchos::EnhancedNumberValidator<T>*>(v);
  if (!range) return false;
  os << "; valid range [" << range->getMin() << ", " << range->getMax() << "]";
  return true;
}

// The documentation of a valid parameter with what its validator accepts:
// the XML carries no validators (the strict reader reads values only), so
// the choices are written out in words.
std::string describe(const ParameterEntry& valid) {
  std::ostringstream os;
  os << valid.docString();
  const auto v = valid.validator();
  if (v.is_null()) return os.str();
  const auto choices = v->validStringValues();
  if (!choices.is_null()) {
    os << "; valid values: ";
    for (size_t i = 0; i < choices->size(); ++i) os << (i ? ", " : "") << (*choices)[i];
  } else if (!describeRange<int>(v.get(), os)) {
    describeRange<double>(v.get(), os);
  }
  return os.str();
}

// A value of `user` with the documentation of `valid` and no validator.
void copyEntry(const ParameterList& user, const ParameterList& valid, const std::string& name, ParameterList& out) {
  ParameterEntry entry;
  entry.setAnyValue(user.getEntry(name).getAny(), false);
  entry.setDocString(describe(valid.getEntry(name)));
  out.setEntry(name, entry);
}

void documented(const ParameterList& user, const ParameterList& valid, const std::string& path, ParameterList& out);

// Dirichlet and Traction conditions, load curves, contact pairs and bodies:
// sublists of any name, in input order, each checked against one item list.
void documentedItems(const ParameterList& user, const ParameterList& item, ParameterList& out) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    documented(user.sublist(name), item, "", out.sublist(name));
  }
}

void documented(const ParameterList& user, const ParameterList& valid, const std::string& path, ParameterList& out) {
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const std::string full = path.empty() ? name : path + "/" + name;
    // validate() filled every default: a missing entry means the list was not validated.
    TRIBOS_REQUIRE(user.isParameter(name), "Input::toXml: \"" << full << "\" is missing; validate the list first");
    if (!valid.isSublist(name)) {
      copyEntry(user, valid, name, out);
    } else if (full == "Boundary Conditions/Dirichlet") {
      documentedItems(user.sublist(name), dirichletItem(), out.sublist(name));
    } else if (full == "Boundary Conditions/Traction") {
      documentedItems(user.sublist(name), tractionItem(), out.sublist(name));
    } else if (full == "Load Curves") {
      documentedItems(user.sublist(name), curveItem(), out.sublist(name));
    } else if (full == "Contact/Pairs") {
      documentedItems(user.sublist(name), pairItem(user), out.sublist(name));
    } else if (full == "Bodies") {
      documentedItems(user.sublist(name), bodyItem(user.sublist("Material")), out.sublist(name));
    } else {
      documented(user.sublist(name), valid.sublist(name), full, out.sublist(name));
    }
  }
}

// The shortest text that reads back as exactly v (0.3, not Teuchos'
// 2.99999999999999989e-01): the file is for people as well.
std::string shortest(double v) {
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string shortestValue(const std::string& type, const std::string& value) {
  if (type == "double") return shortest(std::strtod(value.c_str(), nullptr));
  if (type != "Array(double)") return value;
  // "{a, b, c}" as Teuchos writes it.
  std::string out = "{";
  std::stringstream items(value.substr(1, value.size() - 2));
  for (std::string item; std::getline(items, item, ',');)
    out += (out.size() > 1 ? ", " : "") + shortest(std::strtod(item.c_str(), nullptr));
  return out + "}";
}

// Teuchos' XML, reduced to what an input file holds: name, type, value and
// docString (no entry ids, no isUsed flags, no <Validators> element, which
// the strict reader refuses), with doubles in their shortest exact form.
Teuchos::XMLObject inputFileXml(const Teuchos::XMLObject& xml) {
  Teuchos::XMLObject out(xml.getTag());
  for (const char* attribute : {"name", "type", "value", "docString"}) {
    if (!xml.hasAttribute(attribute)) continue;
    const std::string& text = xml.getAttribute(attribute);
    out.addAttribute(attribute, std::string(attribute) == "value" && xml.hasAttribute("type")
                                    ? shortestValue(xml.getAttribute("type"), text)
                                    : text);
  }
  for (int i = 0; i < xml.numChildren(); ++i)
    if (xml.getChild(i).getTag() != "Validators") out.addChild(inputFileXml(xml.getChild(i)));
  return out;
}

// Tab, LF and CR in attribute values as character references: written
// literally (as Teuchos' writer leaves them) an XML parser reads them as
// spaces (XML 1.0, 3.3.3) and a CR LF as LF. A value is the text after
// =" or =' up to the same quote (Teuchos quotes a value holding '"' with
// '); the elements have no other text.
std::string referencedWhitespace(const std::string& xml) {
  std::string out;
  char quote = 0;  // the delimiter of the value being copied, 0 outside values
  for (size_t i = 0; i < xml.size(); ++i) {
    const char c = xml[i];
    if (quote && c == quote) quote = 0;
    else if (!quote && (c == '"' || c == '\'') && i > 0 && xml[i - 1] == '=') quote = c;
    if (quote && (c == '\t' || c == '\n' || c == '\r')) out += "&#" + std::to_string(static_cast<int>(c)) + ";";
    else out += c;
  }
  return out;
}

}  // namespace

RCP<ParameterList> defaults(const std::vector<std::string>& overrides) {
  auto params = Teuchos::parameterList("Tribos");
  for (const auto& o : overrides) applyOverride(*params, o);
  validate(*params, "the default parameters");
  return params;
}

std::string toXml(const ParameterList& params) {
  ParameterList out(validParameters()->name());
  documented(params, *validParameters(), "", out);
  // print() (operator<<) escapes attribute values and indents; toString() does neither.
  std::ostringstream os;
  os << inputFileXml(Teuchos::XMLParameterListWriter().toXML(out));
  return referencedWhitespace(os.str());
}

}  // namespace Input
}  // namespace Tribos
