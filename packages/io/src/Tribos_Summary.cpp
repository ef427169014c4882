#include "Tribos_Summary.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "Tribos_Error.hpp"
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

namespace {

// A reader of JSON text (RFC 8259) that keeps each value as its text.
class JsonScanner {
 public:
  explicit JsonScanner(const std::string& text) : s_(text) {}
  // The members of the object the text is, key (unescaped) and value text.
  std::vector<std::pair<std::string, std::string>> members() {
    std::vector<std::pair<std::string, std::string>> out;
    expect('{');
    if (!take('}')) {
      do {
        skipSpace();
        const size_t k = pos_;
        skipString();
        const std::string key = unquote(s_.substr(k, pos_ - k));
        expect(':');
        out.emplace_back(key, valueText());
      } while (take(','));
      expect('}');
    }
    atEnd();
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("not a JSON text: " + what + " at offset " + std::to_string(pos_));
  }
  void skipSpace() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }
  bool take(char c) {
    skipSpace();
    if (pos_ < s_.size() && s_[pos_] == c) return ++pos_, true;
    return false;
  }
  void expect(char c) {
    if (!take(c)) fail(std::string("'") + c + "' expected");
  }
  void atEnd() {
    skipSpace();
    if (pos_ != s_.size()) fail("text after the end");
  }
  void skipString() {
    if (pos_ >= s_.size() || s_[pos_] != '"') fail("a string expected");
    for (++pos_; pos_ < s_.size() && s_[pos_] != '"'; ++pos_)
      if (s_[pos_] == '\\') ++pos_;
    if (pos_ >= s_.size()) fail("an unterminated string");
    ++pos_;
  }
  // A value of any kind, skipped; its text (without the space around it).
  std::string valueText() {
    skipSpace();
    const size_t start = pos_;
    skipValue(0);
    return s_.substr(start, pos_ - start);
  }
  void skipValue(int depth) {
    if (depth > 64) fail("nesting too deep");
    skipSpace();
    if (pos_ >= s_.size()) fail("a value expected");
    const char c = s_[pos_];
    if (c == '"') return skipString();
    if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++pos_;
      if (take(close)) return;
      do {
        if (c == '{') {
          skipSpace();
          skipString();
          expect(':');
        }
        skipValue(depth + 1);
      } while (take(','));
      return expect(close);
    }
    // A number or a literal (true, false, null): up to a delimiter.
    const size_t start = pos_;
    while (pos_ < s_.size() && std::string(",]} \n\t\r").find(s_[pos_]) == std::string::npos) ++pos_;
    const std::string token = s_.substr(start, pos_ - start);
    if (token == "true" || token == "false" || token == "null") return;
    char* end = nullptr;
    std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0') fail("'" + token + "' is not a value");
  }
  // The text of a key: escapes of the quotation mark and reverse solidus
  // (keys of a summary need no other).
  static std::string unquote(const std::string& quoted) {
    std::string out;
    for (size_t i = 1; i + 1 < quoted.size(); ++i) out += quoted[i] == '\\' ? quoted[++i] : quoted[i];
    return out;
  }

  const std::string& s_;
  size_t pos_ = 0;
};

}  // namespace

Summary Summary::fromJson(const std::string& json) {
  Summary s;
  for (auto& [key, value] : JsonScanner(json).members()) s.put(key, std::move(value));
  return s;
}

std::string Summary::json(const std::string& key) const {
  for (const auto& e : entries_)
    if (e.first == key) return e.second;
  return "";
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

std::string Summary::toJsonLine() const {
  // A JSON text holds a line break only between tokens (one in a string is
  // escaped), so each one with the indentation after it becomes a space.
  const std::string text = toJson();
  std::string line;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n') {
      line += text[i];
      continue;
    }
    while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
    line += ' ';
  }
  return line;
}

double peakRssMb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux reports kB
}

}  // namespace IO
}  // namespace Tribos
