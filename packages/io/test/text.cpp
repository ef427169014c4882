// The text of inputs (Tribos_ParameterReader.hpp): UTF-8 held to its
// well-formed sequences at every length boundary, the characters of XML 1.0,
// positions in messages, the encodings of an XML document (BOM, UTF-16,
// declarations), character references, and input files that are not regular
// files or too large.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <string>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_ParameterReader.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

std::string decode(const std::string& bytes) { return IO::decodeXmlDocument(bytes, "doc"); }
std::string decodeError(const std::string& bytes) {
  return errorOf([&] { decode(bytes); });
}

// text in UTF-16 with the given byte order (ASCII and the characters below, as UTF-16 units).
std::string utf16(const std::u16string& text, bool bigEndian) {
  std::string out;
  for (char16_t u : text) {
    const char hi = static_cast<char>(u >> 8), lo = static_cast<char>(u & 0xFF);
    out += bigEndian ? std::string{hi, lo} : std::string{lo, hi};
  }
  return out;
}

const std::string kMlyn = "M\xC5\x82yn \xC3\xBC \xF0\x9D\x9C\x87";  // "Młyn ü 𝜇": 2- and 4-byte sequences

}  // namespace

TEUCHOS_UNIT_TEST(Utf8, EveryLengthAtItsBoundaries) {
  // The first and last code point of each length, and around the surrogates.
  for (const std::string ok : {"\x7F", "\xC2\x80", "\xDF\xBF", "\xE0\xA0\x80", "\xED\x9F\xBF", "\xEE\x80\x80",
                               "\xEF\xBF\xBD", "\xF0\x90\x80\x80", "\xF4\x8F\xBF\xBF", "\xC2\x85"}) {
    out << IO::visibleText(ok) << "\n";
    TEST_EQUALITY(IO::textProblem("a" + ok + "b"), "");
    TEST_EQUALITY(IO::validUtf8(ok), ok);
  }
  TEST_EQUALITY(IO::textProblem(kMlyn + "\t\n\r"), "");
}

TEUCHOS_UNIT_TEST(Utf8, IllFormedSequences) {
  const std::pair<std::string, std::string> bad[] = {
      {"\xC0\xAF", "(bytes 0xC0 0xAF): an overlong encoding"},
      {"\xC1\xBF", "(bytes 0xC1 0xBF): an overlong encoding"},
      {"\xE0\x80\xAF", "(bytes 0xE0 0x80 0xAF): an overlong encoding"},
      {"\xE0\x9F\xBF", "(bytes 0xE0 0x9F 0xBF): an overlong encoding"},
      {"\xF0\x8F\xBF\xBF", "(bytes 0xF0 0x8F 0xBF 0xBF): an overlong encoding"},
      {"\xED\xA0\x80", "(bytes 0xED 0xA0 0x80): a UTF-16 surrogate"},
      {"\xED\xBF\xBF", "(bytes 0xED 0xBF 0xBF): a UTF-16 surrogate"},
      {"\xF4\x90\x80\x80", "(bytes 0xF4 0x90 0x80 0x80): a code point above U+10FFFF"},
      {"\xF5\x80\x80\x80", "(bytes 0xF5 0x80 0x80 0x80): a code point above U+10FFFF"},
      {"\xF8\x88\x80\x80\x80", "(byte 0xF8): a byte that never occurs in UTF-8"},
      {"\xFF", "(byte 0xFF): a byte that never occurs in UTF-8"},
      {"\x80", "(byte 0x80): a continuation byte without a lead byte"},
      {"\xC3" "A", "(byte 0xC3): a lead byte without all its continuation bytes"},
      {"\xE2\x82" "A", "(bytes 0xE2 0x82): a lead byte without all its continuation bytes"},
  };
  for (const auto& [text, expected] : bad) {
    const std::string problem = IO::textProblem("ab" + text + "cd");
    out << problem << "\n";
    TEST_ASSERT(contains(problem, "line 1, column 3 (byte 2): invalid UTF-8 " + expected));
    TEST_ASSERT(contains(IO::validUtf8("ab" + text), "ab\xEF\xBF\xBD"));
    TEST_EQUALITY(IO::textProblem(IO::validUtf8("ab" + text + "cd")), "");
  }
}

TEUCHOS_UNIT_TEST(Utf8, TruncatedAtTheEnd) {
  for (const std::string cut : {"\xC3", "\xE2\x82", "\xF0\x9F\x98"}) {
    const std::string problem = IO::textProblem("x" + cut);
    out << problem << "\n";
    TEST_ASSERT(contains(problem, "column 2 (byte 1): invalid UTF-8"));
    TEST_ASSERT(contains(problem, "a sequence cut short by the end of the text"));
    TEST_EQUALITY(IO::validUtf8("x" + cut), "x\xEF\xBF\xBD");
  }
}

TEUCHOS_UNIT_TEST(XmlChars, ControlsNulAndNoncharacters) {
  TEST_ASSERT(contains(IO::textProblem(std::string("a\0b", 3)), "(byte 1): U+0000 (byte 0x00), a NUL character"));
  TEST_ASSERT(contains(IO::textProblem("a\x01"), "U+0001 (byte 0x01), a control character"));
  TEST_ASSERT(contains(IO::textProblem("\x1F"), "U+001F (byte 0x1F), a control character"));
  TEST_ASSERT(contains(IO::textProblem("\x0B"), "U+000B"));
  TEST_ASSERT(contains(IO::textProblem("\xEF\xBF\xBE"), "U+FFFE (bytes 0xEF 0xBF 0xBE), a noncharacter"));
  TEST_ASSERT(contains(IO::textProblem("\xEF\xBF\xBF"), "U+FFFF"));
  // DEL and the C1 controls are characters of XML 1.0.
  TEST_EQUALITY(IO::textProblem("\x7F\xC2\x80\xC2\x9F"), "");
}

TEUCHOS_UNIT_TEST(XmlChars, PositionsInCharactersAndLines) {
  TEST_ASSERT(contains(IO::textProblem("ab\ncd\x01"), "line 2, column 3 (byte 5)"));
  TEST_ASSERT(contains(IO::textProblem("a\r\nb\x01"), "line 2, column 2 (byte 4)"));  // CR LF: one line end
  TEST_ASSERT(contains(IO::textProblem("a\rb\x01"), "line 2, column 2 (byte 3)"));    // a CR alone: one too
  TEST_ASSERT(contains(IO::textProblem(kMlyn + "\x01"), "line 1, column 9 (byte 13)"));
}

TEUCHOS_UNIT_TEST(XmlChars, CheckTextAndVisibleText) {
  const std::string message = errorOf([] { IO::checkText("Name=a\x01", "--set"); });
  out << message << "\n";
  TEST_ASSERT(contains(message, "--set, line 1, column 7 (byte 6): U+0001"));
  TEST_EQUALITY(errorOf([] { IO::checkText(kMlyn, "x"); }), "");
  TEST_EQUALITY(IO::visibleText("a\x01" "b\xFF\tc" + kMlyn), "a\\x01b\\xFF\\x09c" + kMlyn);
}

TEUCHOS_UNIT_TEST(XmlDocument, Utf8WithAndWithoutBom) {
  const std::string doc = "<a b=\"" + kMlyn + "\"/>";
  TEST_EQUALITY(decode(doc), doc);
  TEST_EQUALITY(decode("\xEF\xBB\xBF" + doc), doc);
  TEST_EQUALITY(decode("\xEF\xBB\xBF<?xml version=\"1.0\" encoding=\"utf-8\"?>" + doc),
                "<?xml version=\"1.0\" encoding=\"utf-8\"?>" + doc);
  const std::string latin = decodeError("<a b=\"\xE9\"/>");
  out << latin << "\n";
  TEST_ASSERT(contains(latin, "doc, line 1, column 7 (byte 6): invalid UTF-8 (byte 0xE9)"));
  TEST_ASSERT(contains(latin, "encoding=\"ISO-8859-1\""));  // the hint
}

TEUCHOS_UNIT_TEST(XmlDocument, Utf16) {
  const std::u16string text = u"<?xml version=\"1.0\" encoding=\"UTF-16\"?>\n<a b=\"M\u0142yn \u00FC \U0001D707\"/>";
  const std::string expected = "<?xml version=\"1.0\" encoding=\"UTF-16\"?>\n<a b=\"" + kMlyn + "\"/>";
  TEST_EQUALITY(decode("\xFF\xFE" + utf16(text, false)), expected);
  TEST_EQUALITY(decode("\xFE\xFF" + utf16(text, true)), expected);
  TEST_EQUALITY(decode(utf16(text, false)), expected);  // detected from "<?" in 2-byte units
  TEST_EQUALITY(decode(utf16(text, true)), expected);
  // A lone surrogate, an odd last byte; positions count characters, bytes are the file's.
  const std::string lone = decodeError("\xFF\xFE" + utf16(u"<a b=\"x", false) + std::string("\x00\xDC", 2) + utf16(u"\"/>", false));
  out << lone << "\n";
  TEST_ASSERT(contains(lone, "line 1, column 8 (byte 16): invalid UTF-16LE (bytes 0x00 0xDC): a low surrogate"));
  const std::string high = decodeError("\xFE\xFF" + utf16(u"<a b=\"", true) + "\xD8\x35" + utf16(u"x\"/>", true));
  TEST_ASSERT(contains(high, "a high surrogate without a low surrogate after it"));
  TEST_ASSERT(contains(decodeError("\xFF\xFE" + utf16(u"<a/>", false) + "x"), "an odd byte at the end"));
  TEST_ASSERT(contains(decodeError("\xFF\xFE" + utf16(std::u16string(u"<a b=\"\0\"/>", 10), false)), "U+0000"));
}

TEUCHOS_UNIT_TEST(XmlDocument, DeclaredEncodings) {
  TEST_EQUALITY(decode("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><a b=\"\xE9\xFC\"/>"),
                "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><a b=\"\xC3\xA9\xC3\xBC\"/>");
  TEST_EQUALITY(decode("<?xml version='1.0' encoding = 'latin1' ?><a/>"), "<?xml version='1.0' encoding = 'latin1' ?><a/>");
  TEST_EQUALITY(decode("<?xml version=\"1.0\" encoding=\"US-ASCII\"?><a/>"), "<?xml version=\"1.0\" encoding=\"US-ASCII\"?><a/>");
  TEST_ASSERT(contains(decodeError("<?xml version=\"1.0\" encoding=\"US-ASCII\"?><a b=\"\xE9\"/>"),
                       "invalid US-ASCII (byte 0xE9)"));
  TEST_ASSERT(contains(decodeError("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><a b=\"\x01\"/>"), "U+0001"));
  const std::string sjis = decodeError("<?xml version=\"1.0\" encoding=\"Shift_JIS\"?><a/>");
  out << sjis << "\n";
  TEST_ASSERT(contains(sjis, "doc: declares encoding=\"Shift_JIS\", which is not supported; supported: UTF-8"));
  TEST_ASSERT(contains(decodeError(std::string("\xFF\xFE\0\0<\0\0\0", 8)), "is UTF-32 (from its byte order mark)"));
  TEST_ASSERT(contains(decodeError(std::string("<\0\0\0?\0\0\0", 8)), "is UTF-32"));
  TEST_ASSERT(contains(decodeError("\x4C\x6F\xA7\x94\x93\x40"), "is EBCDIC"));
}

TEUCHOS_UNIT_TEST(XmlDocument, DeclarationsThatContradictTheBytes) {
  TEST_ASSERT(contains(decodeError("\xEF\xBB\xBF<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><a/>"),
                       "starts with a UTF-8 byte order mark but declares encoding=\"ISO-8859-1\""));
  TEST_ASSERT(contains(decodeError("\xFF\xFE" + utf16(u"<?xml version=\"1.0\" encoding=\"UTF-8\"?><a/>", false)),
                       "is UTF-16LE (from its byte order mark) but declares encoding=\"UTF-8\""));
  TEST_ASSERT(contains(decodeError("\xFF\xFE" + utf16(u"<?xml version=\"1.0\" encoding=\"UTF-16BE\"?><a/>", false)),
                       "but declares encoding=\"UTF-16BE\""));
  TEST_ASSERT(contains(decodeError("<?xml version=\"1.0\" encoding=\"UTF-16\"?><a/>"),
                       "declares encoding=\"UTF-16\" but its first bytes are 8-bit text"));
}

TEUCHOS_UNIT_TEST(XmlDocument, LineEnds) {
  TEST_EQUALITY(decode("<a\r\nb=\"x\ry\"/>\r\n"), "<a\nb=\"x\ny\"/>\n");
}

TEUCHOS_UNIT_TEST(XmlDocument, CharacterReferences) {
  TEST_EQUALITY(decode("<a b=\"&#233;&#xE9;&#x1F600;&#128512;\"/>"),
                "<a b=\"\xC3\xA9\xC3\xA9\xF0\x9F\x98\x80\xF0\x9F\x98\x80\"/>");
  // ASCII ones stay references (they may be markup), in the decimal form Teuchos reads.
  TEST_EQUALITY(decode("<a b=\"&#60;&#x3C;&#9;&#10;&#13;&amp;\"/>"), "<a b=\"&#60;&#60;&#9;&#10;&#13;&amp;\"/>");
  // Comments are text, not markup.
  TEST_EQUALITY(decode("<!-- &#0; &#x; --><a/>"), "<!-- &#0; &#x; --><a/>");
  const std::string nul = decodeError("<a>\n<b c=\"x&#0;\"/></a>");
  out << nul << "\n";
  TEST_ASSERT(contains(nul, "doc, line 2, column 8: the character reference &#0; is U+0000, a NUL character"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#1;\"/>"), "&#1; is U+0001, a control character"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#x1F;\"/>"), "&#x1F; is U+001F"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#xD800;\"/>"), "&#xD800; is U+D800, a UTF-16 surrogate"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#65535;\"/>"), "U+FFFF, a noncharacter"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#x110000;\"/>"), "&#x110000; is beyond U+10FFFF"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#99999999999999999999;\"/>"), "is beyond U+10FFFF"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#12\"/>"), "a malformed character reference"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#;\"/>"), "a malformed character reference"));
  TEST_ASSERT(contains(decodeError("<a b=\"&#X41;\"/>"), "a malformed character reference"));
}

TEUCHOS_UNIT_TEST(ParameterFile, ValuesComeOutAsUtf8) {
  ScratchDirectory dir(Tpetra::getDefaultComm(), "text");
  const std::string path = dir.path() + "/latin1.xml";
  std::ofstream(path) << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<ParameterList name=\"\xE9\">\n"
                      << "  <Parameter name=\"a\" type=\"string\" value=\"\xFC &#233; &#x1D707; &#60;\"/>\n"
                      << "  <Parameter name=\"b\" type=\"Array(string)\" value=\"{\xE9, x}\"/>\n</ParameterList>\n";
  const auto list = IO::readParameterFile(path);
  TEST_EQUALITY(list->name(), "\xC3\xA9");
  TEST_EQUALITY(list->get<std::string>("a"), "\xC3\xBC \xC3\xA9 \xF0\x9D\x9C\x87 <");
  TEST_EQUALITY(list->get<Teuchos::Array<std::string>>("b")[0], "\xC3\xA9");
}

TEUCHOS_UNIT_TEST(ParameterFile, OnlyRegularFilesOfBoundedSize) {
  ScratchDirectory dir(Tpetra::getDefaultComm(), "text");
  const std::string device = errorOf([] { IO::readParameterFile("/dev/zero"); });
  TEST_EQUALITY(device, "input file \"/dev/zero\" is a character device, not a regular file");
  const std::string fifo = dir.path() + "/fifo.xml";
  const int made = ::mkfifo(fifo.c_str(), 0600);  // (the test macros evaluate their arguments twice)
  TEST_EQUALITY(made, 0);
  TEST_ASSERT(contains(errorOf([&] { IO::readParameterFile(fifo); }), "is a FIFO (named pipe), not a regular file"));
  const std::string large = dir.path() + "/large.xml";
  std::ofstream(large) << "<ParameterList/>";
  const int sized = ::truncate(large.c_str(), IO::kMaxParameterFileBytes + 1);  // sparse: no disk used
  TEST_EQUALITY(sized, 0);
  TEST_ASSERT(contains(errorOf([&] { IO::readParameterFile(large); }),
                       "has " + std::to_string(IO::kMaxParameterFileBytes + 1) + " bytes; a parameter file is read up to 16 MiB"));
  const std::string badName = dir.path() + "/a\xFF.xml";
  std::ofstream(badName) << "<ParameterList/>";
  TEST_ASSERT(contains(errorOf([&] { IO::readParameterFile(badName); }), "a\\xFF.xml\", line 1"));
}
