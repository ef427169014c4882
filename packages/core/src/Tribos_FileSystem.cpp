#include "Tribos_FileSystem.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Teuchos_CommHelpers.hpp>

#include <cctype>
#include <climits>
#include <cstdlib>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace Tribos {

std::string systemReason(int errnoValue) { return std::strerror(errnoValue); }

std::string temporaryName(const std::string& dir, const std::string& name, long pid) {
  return dir + "/." + name + "." + std::to_string(pid) + ".tmp";
}

bool isTemporaryName(const std::string& f) {
  const std::string suffix = ".tmp";
  if (f.size() < 1 + 1 + 1 + 1 + suffix.size() || f[0] != '.') return false;
  if (f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  // The pid: the digits between the last two dots; a name must come before it.
  const size_t pidEnd = f.size() - suffix.size(), dot = f.rfind('.', pidEnd - 1);
  if (dot == std::string::npos || dot < 2 || dot + 1 == pidEnd) return false;
  for (size_t i = dot + 1; i < pidEnd; ++i)
    if (!std::isdigit(static_cast<unsigned char>(f[i]))) return false;
  return true;
}

std::vector<std::string> directoryEntries(const std::string& dir, std::string& error) {
  std::vector<std::string> names;
  DIR* d = ::opendir(dir.c_str());
  if (!d) {
    error = "cannot list " + dir + ": " + systemReason(errno);
    return names;
  }
  while (const dirent* e = ::readdir(d))
    if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) names.push_back(e->d_name);
  ::closedir(d);
  return names;
}

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  return pos == 0 ? "/" : path.substr(0, pos);
}

std::string fileNameOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == std::string::npos ? path : path.substr(pos + 1);
}

std::string writeWholeFile(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return "cannot create " + path + ": " + systemReason(errno);
  const char* p = text.data();
  size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return "cannot write " + path + ": " + systemReason(err);
    }
    p += n, left -= static_cast<size_t>(n);
  }
  // fsync before the caller renames: otherwise a crash can leave the new name
  // on an empty file (delayed allocation).
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    return "cannot write " + path + ": " + systemReason(err);
  }
  // close reports the deferred errors of network file systems.
  if (::close(fd) != 0) return "cannot write " + path + ": " + systemReason(errno);
  return "";
}

std::string syncPath(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "cannot open " + path + " to flush it: " + systemReason(errno);
  // Some file systems cannot fsync a directory (EINVAL): nothing to flush then.
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const int err = errno;
    ::close(fd);
    return "cannot flush " + path + " to the device: " + systemReason(err);
  }
  ::close(fd);
  return "";
}

std::string removeIfExists(const std::string& path) {
  if (::unlink(path.c_str()) == 0 || errno == ENOENT) return "";
  return "cannot remove " + path + ": " + systemReason(errno);
}

std::string renameFile(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) == 0) return "";
  return "cannot rename " + from + " to " + to + ": " + systemReason(errno);
}

std::string rootError(const Comm& comm, const std::string& errorOnRoot) {
  return broadcastFromRoot(comm, comm.getRank() == 0 ? errorOnRoot : std::string());
}

std::string broadcastFromRoot(const Comm& comm, const std::string& value) {
  std::string message = value;
  int length = static_cast<int>(message.size());
  Teuchos::broadcast<int, int>(comm, 0, Teuchos::outArg(length));
  message.resize(static_cast<size_t>(length));
  if (length > 0) Teuchos::broadcast<int, char>(comm, 0, length, &message[0]);
  return message;
}

long broadcastFromRoot(const Comm& comm, long value) {
  long long v = value;
  Teuchos::broadcast<int, long long>(comm, 0, Teuchos::outArg(v));
  return static_cast<long>(v);
}

std::string temporaryPathFor(const std::string& path) {
  return temporaryName(directoryOf(path), fileNameOf(path), static_cast<long>(::getpid()));
}

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  const bool hasA = ::stat(a.c_str(), &sa) == 0, hasB = ::stat(b.c_str(), &sb) == 0;
  if (hasA && hasB) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  // One or neither exists yet (a directory a run is about to create): the
  // paths with their existing part resolved (links, "..") and the rest
  // normalized, so that "new/../input.xml" is the input once "new" is made.
  std::error_code ea, eb;
  const auto ra = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ea), ea);
  const auto rb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, eb), eb);
  return !ea && !eb && ra == rb;
}

}  // namespace Tribos
