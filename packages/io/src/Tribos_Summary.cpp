#include "Tribos_Summary.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "Tribos_ParameterReader.hpp"

namespace Tribos {
namespace IO {

namespace {
std::string number(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no inf/nan
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}
// A JSON string (RFC 8259, section 7): quotation mark, reverse solidus and the
// control characters below 0x20 must be escaped, and the text must be UTF-8
// (section 8.1). Inputs are checked (IO::checkText), but a summary also
// reports text that never was, such as an output path from the command line,
// which may hold any bytes: an ill-formed UTF-8 sequence is replaced by
// U+FFFD here rather than refused, the summary being a report.
std::string quote(const std::string& text) {
  const std::string s = validUtf8(text);
  std::string out = "\"";
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else if (c == '\b') out += "\\b";
    else if (c == '\f') out += "\\f";
    else if (u < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else out += c;
  }
  return out + "\"";
}
}  // namespace

void Summary::put(const std::string& key, std::string json) {
  for (auto& e : entries_)
    if (e.first == key) {
      e.second = std::move(json);
      return;
    }
  entries_.emplace_back(key, std::move(json));
}

Summary& Summary::set(const std::string& key, double v) { put(key, number(v)); return *this; }
Summary& Summary::set(const std::string& key, long long v) { put(key, std::to_string(v)); return *this; }
Summary& Summary::set(const std::string& key, bool v) { put(key, v ? "true" : "false"); return *this; }
Summary& Summary::set(const std::string& key, const std::string& v) { put(key, quote(v)); return *this; }
Summary& Summary::set(const std::string& key, const std::vector<double>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
  put(key, s + "]");
  return *this;
}
Summary& Summary::set(const std::string& key, const Summary& object) { put(key, object.toJson(1)); return *this; }

Summary& Summary::set(const std::string& key, const std::vector<Summary>& objects) {
  std::string json = "[";
  for (size_t i = 0; i < objects.size(); ++i) json += (i ? ", " : "") + objects[i].toJson(2);
  put(key, json + "]");
  return *this;
}

bool Summary::has(const std::string& key) const {
  for (const auto& e : entries_)
    if (e.first == key) return true;
  return false;
}

std::string Summary::toJson(int indent) const {
  const std::string pad(2 * (indent + 1), ' '), end(2 * indent, ' ');
  std::ostringstream os;
  os << "{\n";
  for (size_t i = 0; i < entries_.size(); ++i)
    os << pad << quote(entries_[i].first) << ": " << entries_[i].second << (i + 1 < entries_.size() ? ",\n" : "\n");
  os << end << "}";
  return os.str();
}

double peakRssMb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux reports kB
}

}  // namespace IO
}  // namespace Tribos
