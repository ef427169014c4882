// Tribos_FCLIB_Files.hpp: output files of the FCLIB writers and of the
// tribos_fclib driver, written atomically under a per-process temporary name.
#pragma once

#include <string>

namespace Tribos {
namespace FCLIB {

// dir/.name.<pid>.tmp for dir/name: hidden, in the target's directory (so the
// rename is atomic), unique per process, so two runs writing the same target
// never share, truncate or remove each other's temporary.
std::string temporaryPath(const std::string& path);

// Throws Tribos::Error (the message starts with 'what', e.g. "--summary")
// unless a file can be written at 'path' by temporary + rename: the path is
// not empty, does not name a directory, and its directory exists and is
// writable. Meant to run before a long computation, so that a mistyped output
// path fails at once instead of after the solve.
void checkOutputPath(const std::string& path, const std::string& what);

// True when both paths name the same file: the same device and inode when
// both exist, else the same name in the same (resolved) directory.
bool sameFile(const std::string& a, const std::string& b);

// Writes 'text' to temporaryPath(path) and renames it onto 'path'; on failure
// the temporary is removed and whatever was at 'path' is left untouched.
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace FCLIB
}  // namespace Tribos
