// The summary's JSON: strings escaped per RFC 8259 (quotation mark, reverse
// solidus, every control character below 0x20, short forms where they
// exist), non-finite numbers as null, nested objects indented.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <limits>

#include "IoTestSupport.hpp"
#include "Tribos_History.hpp"
#include "Tribos_ParameterReader.hpp"
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

}  // namespace

TEUCHOS_UNIT_TEST(SummaryJson, EscapedString) {
  IO::Summary s;
  s.set("text", std::string("a\tb\nc\"d\\e\r\b\f") + '\x01' + '\x1f' + "\x7f" + "\xc3\xa9");
  const std::string json = s.toJson();
  out << json << "\n";
  const std::string expected = "\"text\": \"a\\tb\\nc\\\"d\\\\e\\r\\b\\f\\u0001\\u001f\x7f\xc3\xa9\"";
  TEST_ASSERT(contains(json, expected));
  TEST_ASSERT(noRawControlCharacters(json));
}

TEUCHOS_UNIT_TEST(SummaryJson, EscapedKey) {
  IO::Summary key;
  key.set("tab\tkey", 1);
  out << key.toJson() << "\n";
  TEST_ASSERT(contains(key.toJson(), "\"tab\\tkey\": 1"));
}

TEUCHOS_UNIT_TEST(SummaryJson, EveryControlCharacter) {
  std::string all;
  for (int c = 0; c < 0x20; ++c) all += static_cast<char>(c);
  IO::Summary every;
  every.set("all", all);
  out << every.toJson() << "\n";
  TEST_ASSERT(noRawControlCharacters(every.toJson()));
  TEST_ASSERT(contains(every.toJson(), "\\u0000\\u0001"));
  TEST_ASSERT(contains(every.toJson(), "\\b\\t\\n\\u000b\\f\\r\\u000e"));
}

// JSON text is UTF-8 (RFC 8259, 8.1): a string that was never checked (an
// output path from the command line may hold any bytes) has each ill-formed
// sequence replaced by U+FFFD; valid UTF-8 passes unchanged.
TEUCHOS_UNIT_TEST(SummaryJson, IllFormedUtf8Replaced) {
  IO::Summary s;
  s.set("path", std::string("/tmp/a\xFF" "b\xC0\xAF" "c\xE2\x82")).set("k\xFE", "M\xC5\x82yn \xF0\x9D\x9C\x87");
  const std::string json = s.toJson();
  out << json << "\n";
  TEST_ASSERT(contains(json, "\"/tmp/a\xEF\xBF\xBD" "b\xEF\xBF\xBD" "c\xEF\xBF\xBD\""));
  TEST_ASSERT(contains(json, "\"k\xEF\xBF\xBD\": \"M\xC5\x82yn \xF0\x9D\x9C\x87\""));
  TEST_EQUALITY(IO::textProblem(json), "");
}

TEUCHOS_UNIT_TEST(SummaryJson, NonFiniteNumbers) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  IO::Summary s;
  s.set("nan", nan).set("inf", inf).set("minus_inf", -inf).set("x", 0.25).set("v", std::vector<double>{1, nan, -inf});
  const std::string json = s.toJson();
  out << json << "\n";
  TEST_ASSERT(contains(json, "\"nan\": null"));
  TEST_ASSERT(contains(json, "\"inf\": null"));
  TEST_ASSERT(contains(json, "\"minus_inf\": null"));
  TEST_ASSERT(contains(json, "\"v\": [1, null, null]"));
  TEST_ASSERT(contains(json, "\"x\": 0.25"));
  TEST_ASSERT(!contains(json, "nan") || contains(json, "\"nan\""));  // no bare nan
}

TEUCHOS_UNIT_TEST(SummaryJson, NestedObject) {
  IO::Summary inner, outer;
  inner.set("reason", "tol\treached").set("value", std::nan(""));
  outer.set("kkt", inner).set("ok", true);
  const std::string json = outer.toJson();
  TEST_EQUALITY(json, "{\n  \"kkt\": {\n    \"reason\": \"tol\\treached\",\n    \"value\": null\n  },\n  \"ok\": true\n}");
}

// The iteration history as CSV: the header, one line per row, a value the
// solver does not have (NaN, the default) as an empty field, never "nan".
TEUCHOS_UNIT_TEST(HistoryCsv, RowsAndEmptyFields) {
  IO::IterationHistory h;
  IO::HistoryRow a, b;
  a.iteration = 1, a.relativeResidual = 1e-3, a.gLambda = 2.5e-4, a.slipBoundChange = 1, a.n_A = 79, a.seconds = 0.5;
  b.iteration = 24, b.relativeResidual = 6.5e-11, b.n_A = 25, b.seconds = std::numeric_limits<double>::infinity();
  h.rows = {a, b};
  TEST_EQUALITY(h.toCsv(),
                "outer_iteration,relative_residual,G_lambda_rel,slip_bound_change,n_A,time_s,step\n"
                "1,0.001,0.00025,1,79,0.5,1\n"
                "24,6.5e-11,,,25,,1\n");
  TEST_EQUALITY(IO::IterationHistory().toCsv(),
                "outer_iteration,relative_residual,G_lambda_rel,slip_bound_change,n_A,time_s,step\n");
}
