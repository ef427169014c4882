// Tribos_FileDigest.hpp: the SHA-256 digest of a file, which the summary of a
// load history records for every step file it lists, so that a restart
// continues only from step files that are byte for byte those the run wrote.
#pragma once

#include <string>

namespace Tribos {
namespace IO {

// The SHA-256 of the file's content as 64 lower-case hex digits; on failure
// "" and `error` names the file and the system's reason. Not collective.
std::string sha256OfFile(const std::string& path, std::string& error);

}  // namespace IO
}  // namespace Tribos
