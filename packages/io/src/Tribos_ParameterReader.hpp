// Tribos_ParameterReader.hpp: Teuchos XML parameter files read strictly.
//
// Teuchos' own reader converts values with an istringstream: "abc" for a
// double becomes 0, "-4e7abc" becomes -4e7 and "2.9" for an int becomes 2,
// silently. Here every value must parse completely as its declared type,
// every number must be finite, a name may appear once per list and lists
// nest at most kMaxDepth deep. Errors name the file, the parameter's path,
// the text and the expected type.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// Deeper nesting is refused before parsing (a hostile file could exhaust the stack).
constexpr int kMaxParameterListDepth = 32;

// Reads a parameter file (the Teuchos XML format: ParameterList and Parameter
// elements with name, type and value). Supported types: int, double, bool,
// string, Array(int), Array(double), Array(string). Throws Tribos::Error.
RCP<Teuchos::ParameterList> readParameterFile(const std::string& file);

// The Teuchos XML name of a value's type ("double", "Array(int)", ...), or ""
// for a type the reader does not support.
std::string parameterTypeName(const Teuchos::any& value);

// `text` (surrounding spaces allowed) as a whole finite double, or a whole
// int: false with the reason ("not a number", "not a finite number ...",
// "not an integer", "an integer out of range") otherwise. The parsers of
// every double and int parameter, also for command-line options and for
// parameters that take a number or a word.
bool parseDouble(const std::string& text, double& v, std::string& why);
bool parseInt(const std::string& text, int& v, std::string& why);

// Parses `text` completely as a value of XML type `type` and sets it as
// list[name]. `where` names the parameter in messages (e.g. the file and
// path, or the --set argument). Throws Tribos::Error.
void setParsedParameter(Teuchos::ParameterList& list, const std::string& name, const std::string& type,
                        const std::string& text, const std::string& where);

}  // namespace IO
}  // namespace Tribos
