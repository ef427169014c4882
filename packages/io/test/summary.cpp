// The summary's JSON: strings escaped per RFC 8259 (quotation mark, reverse
// solidus, every control character below 0x20, short forms where they
// exist), non-finite numbers as null, nested objects indented.
#include <Tpetra_Core.hpp>

#include <cmath>
#include <iostream>
#include <limits>

#include "IoTestSupport.hpp"
#include "Tribos_Summary.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

// JSON text outside strings may hold only these whitespace characters; inside
// strings no control character at all.
bool noRawControlCharacters(const std::string& json) {
  bool inString = false, escaped = false;
  for (char c : json) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (inString) {
      if (u < 0x20) return false;
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (u < 0x20 && c != '\n' && c != ' ' && c != '\t' && c != '\r') {
      return false;
    }
  }
  return !inString;
}

void escapes() {
  IO::Summary s;
  s.set("text", std::string("a\tb\nc\"d\\e\r\b\f") + '\x01' + '\x1f' + "\x7f" + "\xc3\xa9");
  const std::string json = s.toJson();
  const std::string expected = "\"text\": \"a\\tb\\nc\\\"d\\\\e\\r\\b\\f\\u0001\\u001f\x7f\xc3\xa9\"";
  CHECK(contains(json, expected), "escaped string: " << json);
  CHECK(noRawControlCharacters(json), "no raw control character: " << json);

  IO::Summary key;
  key.set("tab\tkey", 1);
  CHECK(contains(key.toJson(), "\"tab\\tkey\": 1"), "keys escaped too: " << key.toJson());
  std::string all;
  for (int c = 0; c < 0x20; ++c) all += static_cast<char>(c);
  IO::Summary every;
  every.set("all", all);
  CHECK(noRawControlCharacters(every.toJson()), "every control character escaped: " << every.toJson());
  CHECK(contains(every.toJson(), "\\u0000\\u0001") && contains(every.toJson(), "\\b\\t\\n\\u000b\\f\\r\\u000e"),
        "NUL and the rest: " << every.toJson());
}

void numbers() {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  IO::Summary s;
  s.set("nan", nan).set("inf", inf).set("minus_inf", -inf).set("x", 0.25).set("v", std::vector<double>{1, nan, -inf});
  const std::string json = s.toJson();
  CHECK(contains(json, "\"nan\": null") && contains(json, "\"inf\": null") && contains(json, "\"minus_inf\": null"),
        "non-finite numbers are null: " << json);
  CHECK(contains(json, "\"v\": [1, null, null]"), "non-finite in arrays: " << json);
  CHECK(contains(json, "\"x\": 0.25"), "finite numbers: " << json);
  CHECK(!contains(json, "nan") || contains(json, "\"nan\""), "no bare nan: " << json);
}

void nested() {
  IO::Summary inner, outer;
  inner.set("reason", "tol\treached").set("value", std::nan(""));
  outer.set("kkt", inner).set("ok", true);
  const std::string json = outer.toJson();
  CHECK(json == "{\n  \"kkt\": {\n    \"reason\": \"tol\\treached\",\n    \"value\": null\n  },\n  \"ok\": true\n}",
        "nested object: " << json);
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  escapes();
  numbers();
  nested();
  return verdict(*comm, "io_test_summary");
}
