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

#include <cstdint>
#include <string>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// Deeper nesting is refused before parsing (a hostile file could exhaust the stack).
constexpr int kMaxParameterListDepth = 32;

// A parameter file has a few kB (the largest shipped input has less than 4).
// Anything much larger is a wrong argument (a mesh, a log, a device): the
// file is refused before it is read rather than read into memory.
constexpr std::uintmax_t kMaxParameterFileBytes = 16u << 20;

// Reads a parameter file (the Teuchos XML format: ParameterList and Parameter
// elements with name, type and value). Supported types: int, double, bool,
// string, Array(int), Array(double), Array(string). The file must be a
// regular file of at most kMaxParameterFileBytes; its text is decoded by
// decodeXmlDocument and every name and value read is checked by checkText.
// Throws Tribos::Error.
RCP<Teuchos::ParameterList> readParameterFile(const std::string& file);

// ---------------------------------------------------------------- text
// What a parameter may hold: the characters of XML 1.0 (its Char
// production: tab, LF, CR and U+0020 on, except the surrogates U+D800..
// U+DFFF and U+FFFE, U+FFFF) in well-formed UTF-8 (no overlong form, nothing
// above U+10FFFF). Whatever is read (the input file and its name, --set
// arguments) is held to this, so that every output (the summary's JSON, the
// parameters file, the HDF5 attributes) holds only text its format accepts.

// Throws Tribos::Error naming `where`, the line and column (in characters,
// from 1) and the byte offset (from 0) of the first character that is not
// allowed, and its bytes in hex:
//   --set "Problem Name=a\x01", line 1, column 15 (byte 14): U+0001 (byte 0x01), a control character ...
void checkText(const std::string& text, const std::string& where);

// The same check as a message tail ("line 1, column 15 (byte 14): ..."), ""
// when the text is allowed.
std::string textProblem(const std::string& text);

// `text` for a message: every byte that is not part of an allowed character
// shown as \xNN, so that a message never carries a control character or
// broken UTF-8 to the terminal.
std::string visibleText(const std::string& text);

// `text` with every ill-formed UTF-8 sequence replaced by U+FFFD, for text
// that was never checked (e.g. an output path from the command line in a
// report): a reporter replaces what an input check refuses.
std::string validUtf8(const std::string& text);

// An XML document's bytes as UTF-8 text, as XML 1.0 reads them: the encoding
// found from a byte order mark or the first bytes (appendix F) and the
// encoding declaration; UTF-8 (with or without BOM), UTF-16 LE/BE (with a
// BOM, or starting "<?" in 16-bit units), ISO-8859-1 and US-ASCII are
// converted, anything else (UTF-32, EBCDIC, another declared encoding, a
// declaration that contradicts the BOM) is refused naming it. The BOM is
// dropped, line ends become LF (XML 1.0, 2.11), every character is checked
// as by checkText, and character references (&#233;, &#x1F600;) to a
// non-ASCII character are replaced by its UTF-8 bytes (Teuchos' parser
// would make a single byte of &#233; and refuses hexadecimal and values
// above 255); one to a character XML does not allow (&#0;) is refused with
// its line and column. Tab, LF and CR written literally inside an
// attribute value stay as they are (Teuchos' parser does not make them
// spaces as XML 1.0, 3.3.3, would; doing it here would shift the line
// numbers of its messages): the parameters file writes them as references,
// which every reader reads alike. `where` names the document in messages.
// Throws Tribos::Error.
std::string decodeXmlDocument(const std::string& bytes, const std::string& where);


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
