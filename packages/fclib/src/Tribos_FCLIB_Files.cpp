#include "Tribos_FCLIB_Files.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace FCLIB {

namespace {

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string baseNameOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The directory resolved (symbolic links, "..") followed by the base name.
std::string resolvedName(const std::string& path) {
  char buffer[PATH_MAX];
  const std::string dir = directoryOf(path);
  const std::string resolved = ::realpath(dir.c_str(), buffer) ? buffer : dir;
  return resolved + "/" + baseNameOf(path);
}

}  // namespace

std::string temporaryPath(const std::string& path) {
  const std::string dir = directoryOf(path);
  return (dir == "/" ? "" : dir) + "/." + baseNameOf(path) + "." +
         std::to_string(static_cast<long long>(::getpid())) + ".tmp";
}

void checkOutputPath(const std::string& path, const std::string& what) {
  auto fail = [&](const std::string& why) { throw Error(what + ": " + why); };
  if (path.empty()) fail("empty file name");
  struct stat st;
  if (path.back() == '/' || (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)))
    fail(path + " is a directory, expected a file name");
  const std::string dir = directoryOf(path);
  if (::stat(dir.c_str(), &st) != 0) fail("directory " + dir + " of " + path + " does not exist");
  if (!S_ISDIR(st.st_mode)) fail(dir + " (in " + path + ") is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail("directory " + dir + " of " + path + " is not writable");
}

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  const bool hasA = ::stat(a.c_str(), &sa) == 0, hasB = ::stat(b.c_str(), &sb) == 0;
  if (hasA && hasB) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (hasA || hasB) return false;
  return resolvedName(a) == resolvedName(b);
}

void writeTextAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = temporaryPath(path);
  try {
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    if (!os) throw Error("cannot create " + tmp);
    os << text;
    os.close();
    if (!os) throw Error("cannot write " + tmp);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw Error("cannot rename " + tmp + " onto " + path);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace FCLIB
}  // namespace Tribos
