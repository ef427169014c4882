#include "Tribos_ParameterReader.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_FileKind.hpp"

namespace Tribos {
namespace IO {

using Teuchos::Array;
using Teuchos::ParameterList;

namespace {

// ---------------------------------------------------------------- text

// One character decoded from bytes, or why the bytes at that place are not one.
struct Decoded {
  char32_t c = 0;
  size_t length = 1;              // bytes taken (at least one, also on error)
  const char* error = nullptr;    // nullptr: c is a character of the encoding
};

unsigned char byteAt(const std::string& s, size_t i) { return static_cast<unsigned char>(s[i]); }

// The UTF-8 sequence at text[at], held to Unicode's well-formed sequences
// (no overlong form, no surrogate, nothing above U+10FFFF). An incomplete
// sequence takes only its lead and continuation bytes, so that the next
// character is read from the byte that cut it short.
Decoded decodeUtf8(const std::string& text, size_t at) {
  const unsigned char b = byteAt(text, at);
  if (b < 0x80) return {b, 1, nullptr};
  if (b < 0xC0) return {b, 1, "a continuation byte without a lead byte"};
  if (b >= 0xF8) return {b, 1, "a byte that never occurs in UTF-8"};
  const size_t length = b >= 0xF0 ? 4 : b >= 0xE0 ? 3 : 2;
  char32_t c = b & (0x7F >> length);
  for (size_t k = 1; k < length; ++k) {
    if (at + k >= text.size()) return {c, k, "a sequence cut short by the end of the text"};
    const unsigned char next = byteAt(text, at + k);
    if ((next & 0xC0) != 0x80) return {c, k, "a lead byte without all its continuation bytes"};
    c = (c << 6) | (next & 0x3F);
  }
  static const char32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
  if (c < least[length]) return {c, length, "an overlong encoding"};
  if (c >= 0xD800 && c <= 0xDFFF) return {c, length, "a UTF-16 surrogate (U+D800..U+DFFF), which UTF-8 does not encode"};
  if (c > 0x10FFFF) return {c, length, "a code point above U+10FFFF"};
  return {c, length, nullptr};
}

// The UTF-16 unit or surrogate pair at bytes[at].
Decoded decodeUtf16(const std::string& bytes, size_t at, bool bigEndian) {
  auto unit = [&](size_t i) -> char32_t {
    return bigEndian ? (byteAt(bytes, i) << 8 | byteAt(bytes, i + 1)) : (byteAt(bytes, i + 1) << 8 | byteAt(bytes, i));
  };
  if (at + 2 > bytes.size()) return {0, 1, "an odd byte at the end (UTF-16 has 2-byte units)"};
  const char32_t u = unit(at);
  if (u >= 0xDC00 && u <= 0xDFFF) return {u, 2, "a low surrogate without a high surrogate before it"};
  if (u < 0xD800 || u > 0xDBFF) return {u, 2, nullptr};
  if (at + 4 > bytes.size()) return {u, bytes.size() - at, "a high surrogate cut short by the end of the text"};
  const char32_t v = unit(at + 2);
  if (v < 0xDC00 || v > 0xDFFF) return {u, 2, "a high surrogate without a low surrogate after it"};
  return {0x10000 + ((u - 0xD800) << 10) + (v - 0xDC00), 4, nullptr};
}

enum class Encoding { Utf8, Utf16LE, Utf16BE, Latin1, Ascii };

const char* encodingName(Encoding e) {
  switch (e) {
    case Encoding::Utf8: return "UTF-8";
    case Encoding::Utf16LE: return "UTF-16LE";
    case Encoding::Utf16BE: return "UTF-16BE";
    case Encoding::Latin1: return "ISO-8859-1";
    case Encoding::Ascii: return "US-ASCII";
  }
  return "";
}

Decoded decodeAt(const std::string& bytes, size_t at, Encoding e) {
  const unsigned char b = byteAt(bytes, at);
  switch (e) {
    case Encoding::Utf8: return decodeUtf8(bytes, at);
    case Encoding::Utf16LE: return decodeUtf16(bytes, at, false);
    case Encoding::Utf16BE: return decodeUtf16(bytes, at, true);
    case Encoding::Latin1: return {b, 1, nullptr};  // ISO-8859-1 is the first 256 code points
    case Encoding::Ascii: return {b, 1, b < 0x80 ? nullptr : "a byte above 0x7F, which US-ASCII does not have"};
  }
  return {b, 1, "an unknown encoding"};
}

// Why c is not a Char of XML 1.0 (production [2]), or nullptr.
const char* notXmlChar(char32_t c) {
  if (c == 0) return "a NUL character, which XML 1.0 text cannot hold";
  if (c < 0x20 && c != 0x9 && c != 0xA && c != 0xD)
    return "a control character, which XML 1.0 text cannot hold (of the controls below U+0020 only tab, LF and CR)";
  if (c >= 0xD800 && c <= 0xDFFF) return "a UTF-16 surrogate, not a character";
  if (c == 0xFFFE || c == 0xFFFF) return "a noncharacter, which XML 1.0 text cannot hold";
  if (c > 0x10FFFF) return "beyond U+10FFFF, the last code point";
  return nullptr;
}

void appendUtf8(std::string& out, char32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

std::string hex(unsigned value, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*X", digits, value);
  return buf;
}

std::string codePoint(char32_t c) { return "U+" + hex(c, 4); }

// "byte 0xC3" or "bytes 0xC3 0x28"
std::string hexBytes(const std::string& bytes, size_t at, size_t length) {
  std::string out = length == 1 ? "byte" : "bytes";
  for (size_t k = 0; k < length && at + k < bytes.size(); ++k) out += " 0x" + hex(byteAt(bytes, at + k), 2);
  return out;
}

// Line and column (in characters, from 1) of the characters passed so far.
// CR LF is one line end, and so is a CR alone (XML 1.0, 2.11).
class Cursor {
 public:
  void advance(char32_t c) {
    if (c == '\n' && afterCR_) {
      afterCR_ = false;
      return;
    }
    afterCR_ = c == '\r';
    if (c == '\n' || c == '\r') ++line_, column_ = 1;
    else ++column_;
  }
  std::string at(size_t byte) const {
    return "line " + std::to_string(line_) + ", column " + std::to_string(column_) + " (byte " + std::to_string(byte) + ")";
  }

 private:
  size_t line_ = 1, column_ = 1;
  bool afterCR_ = false;
};

// Walks bytes[start..] in encoding e and calls take(c) for each character;
// returns the first problem ("line 3, column 7 (byte 41): ...") or "".
template <class Take>
std::string walk(const std::string& bytes, size_t start, Encoding e, Take take) {
  Cursor cursor;
  for (size_t at = start; at < bytes.size();) {
    const Decoded d = decodeAt(bytes, at, e);
    if (d.error)
      return cursor.at(at) + ": invalid " + encodingName(e) + " (" + hexBytes(bytes, at, d.length) + "): " + d.error;
    if (const char* why = notXmlChar(d.c))
      return cursor.at(at) + ": " + codePoint(d.c) + " (" + hexBytes(bytes, at, d.length) + "), " + why;
    take(d.c);
    cursor.advance(d.c);
    at += d.length;
  }
  return "";
}

// Line and column (in characters) of text[at], for messages about decoded text.
std::string lineAndColumn(const std::string& text, size_t at) {
  Cursor cursor;
  for (size_t i = 0; i < at;) {
    const Decoded d = decodeUtf8(text, i);
    cursor.advance(d.c);
    i += d.length;
  }
  const std::string where = cursor.at(0);
  return where.substr(0, where.find(" (byte"));
}

// The encoding an XML declaration at the start of text names ("" without one).
std::string declaredEncoding(const std::string& text) {
  if (text.compare(0, 5, "<?xml") != 0 || text.size() < 6 || !std::isspace(byteAt(text, 5))) return "";
  const std::string declaration = text.substr(0, text.find("?>"));
  size_t at = declaration.find("encoding");
  if (at == std::string::npos) return "";
  at += 8;
  auto skipSpace = [&] {
    while (at < declaration.size() && std::isspace(byteAt(declaration, at))) ++at;
  };
  skipSpace();
  if (at >= declaration.size() || declaration[at] != '=') return "";
  ++at;
  skipSpace();
  if (at >= declaration.size() || (declaration[at] != '"' && declaration[at] != '\'')) return "";
  const size_t end = declaration.find(declaration[at], at + 1);
  return end == std::string::npos ? "" : declaration.substr(at + 1, end - at - 1);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

bool oneOf(const std::string& name, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (name == n) return true;
  return false;
}

const char* const kAcceptedEncodings = "supported: UTF-8 (with or without byte order mark), UTF-16 (with byte "
                                       "order mark), ISO-8859-1 (Latin-1), US-ASCII";

// The encoding a declared name stands for (IANA names and common aliases).
bool knownEncoding(const std::string& declared, Encoding& e) {
  const std::string name = upper(declared);
  if (oneOf(name, {"UTF-8", "UTF8"})) return e = Encoding::Utf8, true;
  if (oneOf(name, {"ISO-8859-1", "ISO_8859-1", "ISO8859-1", "ISO_8859-1:1987", "LATIN1", "LATIN-1", "L1",
                   "ISO-IR-100", "IBM819", "CP819", "CSISOLATIN1"}))
    return e = Encoding::Latin1, true;
  if (oneOf(name, {"US-ASCII", "ASCII", "ANSI_X3.4-1968", "ISO646-US", "US", "IBM367", "CP367", "CSASCII"}))
    return e = Encoding::Ascii, true;
  if (oneOf(name, {"UTF-16LE"})) return e = Encoding::Utf16LE, true;
  if (oneOf(name, {"UTF-16BE"})) return e = Encoding::Utf16BE, true;
  return false;
}

[[noreturn]] void unsupportedEncoding(const std::string& where, const std::string& what) {
  throw Error(where + ": " + what + ", which is not supported; " + kAcceptedEncodings +
              " (convert the file, e.g. with iconv -t UTF-8)");
}

// What the first bytes say (XML 1.0, appendix F): the encoding family and
// the length of a byte order mark. UTF-32 and EBCDIC are refused here.
struct Detected {
  Encoding encoding = Encoding::Utf8;
  size_t bom = 0;         // bytes of the byte order mark
  bool utf16 = false;
};

Detected detect(const std::string& b, const std::string& where) {
  auto starts = [&](std::initializer_list<int> prefix) {
    size_t k = 0;
    for (int x : prefix)
      if (k >= b.size() || byteAt(b, k++) != x) return false;
    return true;
  };
  if (starts({0x00, 0x00, 0xFE, 0xFF}) || starts({0xFF, 0xFE, 0x00, 0x00}))
    unsupportedEncoding(where, "is UTF-32 (from its byte order mark)");
  if (starts({0x00, 0x00, 0x00, 0x3C}) || starts({0x3C, 0x00, 0x00, 0x00}) || starts({0x00, 0x00, 0x3C, 0x00}) ||
      starts({0x00, 0x3C, 0x00, 0x00}))
    unsupportedEncoding(where, "is UTF-32 (UCS-4: its first bytes are '<' in 4-byte units)");
  if (starts({0x4C, 0x6F, 0xA7, 0x94}))
    unsupportedEncoding(where, "is EBCDIC (its first bytes are \"<?xm\" in EBCDIC)");
  if (starts({0xEF, 0xBB, 0xBF})) return {Encoding::Utf8, 3, false};
  if (starts({0xFE, 0xFF})) return {Encoding::Utf16BE, 2, true};
  if (starts({0xFF, 0xFE})) return {Encoding::Utf16LE, 2, true};
  if (starts({0x00, 0x3C, 0x00, 0x3F})) return {Encoding::Utf16BE, 0, true};
  if (starts({0x3C, 0x00, 0x3F, 0x00})) return {Encoding::Utf16LE, 0, true};
  return {};
}

std::string describe(const Detected& d) {
  const std::string how = d.bom ? "from its byte order mark" : "from its first bytes";
  return std::string(encodingName(d.encoding)) + " (" + how + ")";
}

// The encoding of an 8-bit document: the declared one, which must agree with
// a UTF-8 byte order mark. A declaration of UTF-16 in a document whose first
// bytes are 8-bit contradicts itself.
Encoding eightBitEncoding(const std::string& bytes, const Detected& d, const std::string& where) {
  const std::string declared = declaredEncoding(bytes.substr(d.bom, 256));
  if (declared.empty()) return Encoding::Utf8;
  Encoding e;
  const std::string quoted = "encoding=\"" + visibleText(declared) + "\"";
  if (upper(declared) == "UTF-16" || upper(declared) == "UTF16" || (knownEncoding(declared, e) &&
                                                                    (e == Encoding::Utf16LE || e == Encoding::Utf16BE)))
    throw Error(where + ": declares " + quoted + " but its first bytes are 8-bit text (a UTF-16 document starts "
                "with a byte order mark or with \"<?\" in 2-byte units)");
  if (!knownEncoding(declared, e)) unsupportedEncoding(where, "declares " + quoted);
  if (d.bom && e != Encoding::Utf8)
    throw Error(where + ": starts with a UTF-8 byte order mark but declares " + quoted);
  return e;
}

// A UTF-16 document may declare UTF-16, or the byte order it has.
void checkUtf16Declaration(const std::string& text, const Detected& d, const std::string& where) {
  const std::string declared = declaredEncoding(text);
  Encoding e;
  if (declared.empty() || upper(declared) == "UTF-16" || upper(declared) == "UTF16" ||
      (knownEncoding(declared, e) && e == d.encoding))
    return;
  throw Error(where + ": is " + describe(d) + " but declares encoding=\"" + visibleText(declared) + "\"");
}

// Character references (&#233;, &#x1F600;) resolved before Teuchos' parser
// sees them: it decodes &#N; to the single byte N (not UTF-8) and refuses
// hexadecimal forms and values above 255. ASCII ones stay references in
// decimal (they may be markup: &#60; is '<'); the others become their UTF-8
// bytes; a reference to a character XML does not allow is refused. Text of
// comments, CDATA sections and processing instructions is literal.
std::string resolveCharacterReferences(const std::string& text, const std::string& where) {
  std::string out;
  out.reserve(text.size());
  static const std::pair<const char*, const char*> literal[] = {{"<!--", "-->"}, {"<![CDATA[", "]]>"}, {"<?", "?>"}};
  for (size_t i = 0; i < text.size();) {
    bool skipped = false;
    for (const auto& [open, close] : literal)
      if (text.compare(i, std::strlen(open), open) == 0) {
        const size_t end = text.find(close, i + std::strlen(open));
        const size_t stop = end == std::string::npos ? text.size() : end + std::strlen(close);
        out.append(text, i, stop - i);
        i = stop;
        skipped = true;
        break;
      }
    if (skipped) continue;
    if (text.compare(i, 2, "&#") != 0) {
      out += text[i++];
      continue;
    }
    const bool hexadecimal = i + 2 < text.size() && text[i + 2] == 'x';
    size_t j = i + (hexadecimal ? 3 : 2), digits = 0;
    char32_t value = 0;
    for (; j < text.size() && (hexadecimal ? std::isxdigit(byteAt(text, j)) : std::isdigit(byteAt(text, j)));
         ++j, ++digits) {
      const char d = text[j];
      const char32_t v = std::isdigit(static_cast<unsigned char>(d)) ? d - '0' : std::tolower(d) - 'a' + 10;
      value = std::min<char32_t>(value * (hexadecimal ? 16 : 10) + v, 0x110000);  // capped: beyond is refused anyway
    }
    // The place only on failure: counting lines is a pass over the text.
    const auto here = [&] { return where + ", " + lineAndColumn(text, i); };
    TRIBOS_REQUIRE(digits > 0 && j < text.size() && text[j] == ';',
                   here() << ": a malformed character reference (\"&#\" then decimal digits, or \"&#x\" then "
                             "hexadecimal digits, then \";\")");
    if (const char* why = notXmlChar(value))
      throw Error(here() + ": the character reference " + text.substr(i, j + 1 - i) + " is " +
                  (value > 0x10FFFF ? std::string("beyond U+10FFFF, the last code point")
                                    : codePoint(value) + ", " + why));
    if (value < 0x80) out += "&#" + std::to_string(value) + ";";
    else appendUtf8(out, value);
    i = j + 1;
  }
  return out;
}

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

// Every attribute read is checked again after parsing: whatever the parser
// made of the text, no value reaches the parameters that XML does not allow.
std::string attribute(const Teuchos::XMLObject& xml, const char* name, const std::string& where) {
  TRIBOS_REQUIRE(xml.hasAttribute(name), where << ": <" << xml.getTag() << "> has no attribute \"" << name << "\"");
  const std::string& value = xml.getAttribute(name);
  checkText(value, where + ": <" + xml.getTag() + "> attribute \"" + name + "\" = \"" + visibleText(value) + "\"");
  return value;
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

// The whole file, which must be a regular file of at most
// kMaxParameterFileBytes: a FIFO or a device (/dev/zero, /dev/stdin) would
// block the read or feed it without end.
std::string readText(const std::string& file) {
  struct stat st;
  TRIBOS_REQUIRE(stat(file.c_str(), &st) == 0, "cannot open input file \"" << file << "\": " << std::strerror(errno));
  TRIBOS_REQUIRE(!S_ISDIR(st.st_mode), "input file \"" << file << "\" is a directory");
  TRIBOS_REQUIRE(S_ISREG(st.st_mode), "input file \"" << file << "\" is " << fileKind(st.st_mode)
                                                       << ", not a regular file");
  const auto tooLarge = [&](std::uintmax_t size) {
    return Error("input file \"" + file + "\" has " + std::to_string(size) + " bytes; a parameter file is read up to " +
                 std::to_string(kMaxParameterFileBytes >> 20) + " MiB (it has a few kB)");
  };
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxParameterFileBytes) throw tooLarge(st.st_size);
  // Non-blocking: a path replaced by a FIFO after the stat must not block the open.
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  TRIBOS_REQUIRE(fd >= 0, "cannot open input file \"" << file << "\": " << std::strerror(errno));
  std::string text;
  std::string error;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) error = "input file \"" + file + "\" is not a regular file";
  char buffer[65536];
  while (error.empty()) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) error = "cannot read input file \"" + file + "\": " + std::strerror(errno);
    if (n <= 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > kMaxParameterFileBytes) error = tooLarge(text.size()).what();  // it grew after the stat
  }
  ::close(fd);
  if (!error.empty()) throw Error(error);
  return text;
}

}  // namespace

std::string textProblem(const std::string& text) {
  return walk(text, 0, Encoding::Utf8, [](char32_t) {});
}

void checkText(const std::string& text, const std::string& where) {
  const std::string problem = textProblem(text);
  if (!problem.empty()) throw Error(where + ", " + problem);
}

std::string visibleText(const std::string& text) {
  std::string out;
  for (size_t at = 0; at < text.size();) {
    const Decoded d = decodeUtf8(text, at);
    if (d.error || notXmlChar(d.c) || d.c < 0x20 || d.c == 0x7F)
      for (size_t k = 0; k < d.length; ++k) out += "\\x" + hex(byteAt(text, at + k), 2);
    else
      out.append(text, at, d.length);
    at += d.length;
  }
  return out;
}

std::string validUtf8(const std::string& text) {
  std::string out;
  for (size_t at = 0; at < text.size();) {
    const Decoded d = decodeUtf8(text, at);
    if (d.error) out += "\xEF\xBF\xBD";  // U+FFFD REPLACEMENT CHARACTER
    else out.append(text, at, d.length);
    at += d.length;
  }
  return out;
}

std::string decodeXmlDocument(const std::string& bytes, const std::string& where) {
  const Detected detected = detect(bytes, where);
  const Encoding encoding = detected.utf16 ? detected.encoding : eightBitEncoding(bytes, detected, where);
  std::string text;
  text.reserve(bytes.size());
  bool afterCR = false;  // line ends become LF: CR LF and a CR alone (XML 1.0, 2.11)
  const std::string problem = walk(bytes, detected.bom, encoding, [&](char32_t c) {
    if (!(c == '\n' && afterCR)) appendUtf8(text, c == '\r' ? U'\n' : c);
    afterCR = c == '\r';
  });
  if (!problem.empty())
    throw Error(where + ", " + problem + (problem.find("invalid UTF-8") != std::string::npos && detected.bom == 0
                                              ? " (a file in another encoding must declare it, e.g. <?xml "
                                                "version=\"1.0\" encoding=\"ISO-8859-1\"?>)"
                                              : ""));
  if (detected.utf16) checkUtf16Declaration(text, detected, where);
  return resolveCharacterReferences(text, where);
}

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
  // The name first: its directory becomes part of Mesh/File, which the
  // parameters file and the summary hold.
  checkText(file, "the name of the input file \"" + visibleText(file) + "\"");
  const std::string text = decodeXmlDocument(readText(file), "input file \"" + file + "\"");
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
  auto list = Teuchos::parameterList(root.hasAttribute("name") ? attribute(root, "name", "input file \"" + file + "\"")
                                                                : std::string("ANONYMOUS"));
  fill(*list, root, file, "");
  return list;
}

}  // namespace IO
}  // namespace Tribos
