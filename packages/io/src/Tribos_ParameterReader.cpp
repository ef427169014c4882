#include "Tribos_ParameterReader.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace IO {

using Teuchos::Array;
using Teuchos::ParameterList;

namespace {

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// Every value parser returns false with a reason instead of guessing.

bool parseBool(const std::string& text, bool& v, std::string& why) {
  std::string s = trim(text);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s != "true" && s != "false") return why = "not true or false", false;
  v = s == "true";
  return true;
}

bool parseString(const std::string& text, std::string& v, std::string&) {
  v = text;
  return true;
}

// "{a, b, c}" as Teuchos writes arrays; "{}" is empty.
template <class T, class Parse>
bool parseArray(const std::string& text, Array<T>& v, std::string& why, Parse parse) {
  const std::string s = trim(text);
  if (s.size() < 2 || s.front() != '{' || s.back() != '}') return why = "not an array \"{a, b, ...}\"", false;
  const std::string inner = s.substr(1, s.size() - 2);
  v.clear();
  if (trim(inner).empty()) return true;
  std::stringstream ss(inner);
  for (std::string item; std::getline(ss, item, ',');) {
    T x;
    if (!parse(item, x, why)) return why = "element " + std::to_string(v.size()) + " (\"" + trim(item) + "\") is " + why, false;
    v.push_back(x);
  }
  if (!inner.empty() && inner.back() == ',') return why = "an array with an empty last element", false;
  return true;
}

template <class T, class Parse>
void setValue(ParameterList& list, const std::string& name, const std::string& text, const std::string& where,
              const std::string& type, Parse parse) {
  T v{};
  std::string why;
  TRIBOS_REQUIRE(parse(text, v, why), where << " = \"" << text << "\": " << why << " (expected " << type << ")");
  list.set(name, v);
}

// Nesting depth of ParameterList elements, counted on the raw text so that a
// hostile file never reaches the recursive parser.
int nestingDepth(const std::string& text) {
  int depth = 0, worst = 0;
  for (size_t pos = text.find('<'); pos != std::string::npos; pos = text.find('<', pos + 1)) {
    if (text.compare(pos, 4, "<!--") == 0) {
      pos = text.find("-->", pos);
      if (pos == std::string::npos) break;
    } else if (text.compare(pos, 14, "<ParameterList") == 0) {
      const size_t close = text.find('>', pos);
      if (close != std::string::npos && text[close - 1] != '/') worst = std::max(worst, ++depth);
    } else if (text.compare(pos, 16, "</ParameterList>") == 0) {
      --depth;
    }
  }
  return worst;
}

std::string attribute(const Teuchos::XMLObject& xml, const char* name, const std::string& where) {
  TRIBOS_REQUIRE(xml.hasAttribute(name), where << ": <" << xml.getTag() << "> has no attribute \"" << name << "\"");
  return xml.getAttribute(name);
}

void fill(ParameterList& list, const Teuchos::XMLObject& xml, const std::string& file, const std::string& path) {
  const std::string here = "input file \"" + file + "\"" + (path.empty() ? "" : ", list \"" + path + "\"");
  for (int i = 0; i < xml.numChildren(); ++i) {
    const Teuchos::XMLObject& child = xml.getChild(i);
    const std::string& tag = child.getTag();
    TRIBOS_REQUIRE(tag == "Parameter" || tag == "ParameterList",
                   here << ": unexpected element <" << tag << "> (only <Parameter> and <ParameterList> are read)");
    const std::string name = attribute(child, "name", here);
    const std::string full = path.empty() ? name : path + "/" + name;
    TRIBOS_REQUIRE(!list.isParameter(name), "input file \"" << file << "\": \"" << full << "\" is given twice");
    if (tag == "ParameterList") {
      fill(list.sublist(name), child, file, full);
    } else {
      const std::string where = "input file \"" + file + "\": parameter \"" + full + "\"";
      setParsedParameter(list, name, attribute(child, "type", where), attribute(child, "value", where), where);
    }
  }
}

std::string readText(const std::string& file) {
  struct stat st;
  TRIBOS_REQUIRE(stat(file.c_str(), &st) == 0, "cannot open input file \"" << file << "\": " << std::strerror(errno));
  TRIBOS_REQUIRE(!S_ISDIR(st.st_mode), "input file \"" << file << "\" is a directory");
  std::ifstream in(file);
  TRIBOS_REQUIRE(in.good(), "cannot open input file \"" << file << "\"");
  std::ostringstream os;
  os << in.rdbuf();
  TRIBOS_REQUIRE(!in.bad(), "cannot read input file \"" << file << "\"");
  return os.str();
}

}  // namespace

bool parseDouble(const std::string& text, double& v, std::string& why) {
  const std::string s = trim(text);
  errno = 0;
  char* end = nullptr;
  v = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) return why = "not a number", false;
  if (!std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
    return why = "not a finite number (NaN, infinity and values beyond 1.8e308 are refused)", false;
  return true;
}

bool parseInt(const std::string& text, int& v, std::string& why) {
  const std::string s = trim(text);
  errno = 0;
  char* end = nullptr;
  const long long x = s.empty() ? 0 : std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size()) return why = "not an integer", false;
  if (errno == ERANGE || x < INT_MIN || x > INT_MAX) return why = "an integer out of range", false;
  v = static_cast<int>(x);
  return true;
}


std::string parameterTypeName(const Teuchos::any& value) {
  if (value.type() == typeid(int)) return "int";
  if (value.type() == typeid(double)) return "double";
  if (value.type() == typeid(bool)) return "bool";
  if (value.type() == typeid(std::string)) return "string";
  if (value.type() == typeid(Array<int>)) return "Array(int)";
  if (value.type() == typeid(Array<double>)) return "Array(double)";
  if (value.type() == typeid(Array<std::string>)) return "Array(string)";
  return "";
}

void setParsedParameter(ParameterList& list, const std::string& name, const std::string& type, const std::string& text,
                        const std::string& where) {
  if (type == "int") return setValue<int>(list, name, text, where, type, parseInt);
  if (type == "double") return setValue<double>(list, name, text, where, type, parseDouble);
  if (type == "bool") return setValue<bool>(list, name, text, where, type, parseBool);
  if (type == "string") return setValue<std::string>(list, name, text, where, type, parseString);
  if (type == "Array(int)")
    return setValue<Array<int>>(list, name, text, where, type,
                                [](const std::string& t, Array<int>& v, std::string& why) { return parseArray(t, v, why, parseInt); });
  if (type == "Array(double)")
    return setValue<Array<double>>(list, name, text, where, type, [](const std::string& t, Array<double>& v, std::string& why) {
      return parseArray(t, v, why, parseDouble);
    });
  if (type == "Array(string)")
    return setValue<Array<std::string>>(list, name, text, where, type,
                                        [](const std::string& t, Array<std::string>& v, std::string& why) {
                                          return parseArray(t, v, why, parseString);
                                        });
  throw Error(where + ": unsupported type \"" + type +
              "\" (int, double, bool, string, Array(int), Array(double), Array(string))");
}

RCP<ParameterList> readParameterFile(const std::string& file) {
  const std::string text = readText(file);
  TRIBOS_REQUIRE(!trim(text).empty(), "input file \"" << file << "\" is empty");
  const int depth = nestingDepth(text);
  TRIBOS_REQUIRE(depth <= kMaxParameterListDepth, "input file \"" << file << "\": ParameterList elements nest " << depth
                                                                  << " deep; at most " << kMaxParameterListDepth
                                                                  << " levels are read");
  Teuchos::XMLObject root;
  try {
    root = Teuchos::StringInputSource(text).getObject();
  } catch (const std::exception& e) {
    std::string why = e.what();
    const auto nl = why.find_last_of('\n', why.size() > 1 ? why.size() - 2 : 0);
    if (nl != std::string::npos && nl + 1 < why.size()) why = why.substr(nl + 1);
    throw Error("input file \"" + file + "\" is not well-formed XML: " + trim(why));
  }
  TRIBOS_REQUIRE(!root.isEmpty() && root.getTag() == "ParameterList",
                 "input file \"" << file << "\": the root element must be <ParameterList>");
  auto list = Teuchos::parameterList(root.hasAttribute("name") ? root.getAttribute("name") : std::string("ANONYMOUS"));
  fill(*list, root, file, "");
  return list;
}

}  // namespace IO
}  // namespace Tribos
