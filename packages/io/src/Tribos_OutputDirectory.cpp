#include "Tribos_OutputDirectory.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_FileKind.hpp"
#include "Tribos_FileSystem.hpp"

namespace Tribos {
namespace IO {

namespace {

const char* kLockName = ".tribos.lock";

std::string hostName() {
  char name[256] = "";
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

// mkdir -p, saying which component is in the way.
std::string makeDirectories(const std::string& path) {
  for (size_t end = path.find('/', 1);; end = path.find('/', end + 1)) {
    const std::string prefix = path.substr(0, end);
    struct stat st;
    if (!prefix.empty() && ::stat(prefix.c_str(), &st) == 0) {
      const std::string what = prefix == path ? "it" : prefix;
      if (S_ISREG(st.st_mode)) return what + " is a regular file, not a directory";
      if (!S_ISDIR(st.st_mode)) return what + " is not a directory";
    } else if (!prefix.empty() && errno != ENOENT) {
      return "cannot access " + prefix + ": " + systemReason(errno);
    } else if (!prefix.empty() && ::mkdir(prefix.c_str(), 0755) != 0 && errno != EEXIST) {
      return "cannot create directory " + prefix + ": " + systemReason(errno);
    }
    if (end == std::string::npos) return "";
  }
}

// "process P on host H" from the lock file of the run that holds it.
std::string holderOf(int fd) {
  char text[512] = "";
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::istringstream in(std::string(text, n > 0 ? static_cast<size_t>(n) : 0));
  long pid = 0;
  std::string host;
  if (!(in >> pid >> host)) return "another run";
  return "another run (process " + std::to_string(pid) + " on host " + host + ")";
}

// Takes the lock or says why not; on success fd holds it and names this process.
std::string lock(const std::string& dir, int& fd) {
  const std::string path = dir + "/" + kLockName;
  // Not through a link, and only a regular file: the lock file is
  // truncated and written, which must never reach a file it points to.
  fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd < 0 && errno == ELOOP) return "the lock file " + path + " is a symbolic link; remove it";
  if (fd < 0) return "cannot create the lock file " + path + ": " + systemReason(errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const std::string kind = fileKind(st.st_mode);
    ::close(fd), fd = -1;
    return "the lock file " + path + " is not a regular file (" + kind + "); remove it";
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    const std::string why = err == EWOULDBLOCK ? "in use by " + holderOf(fd) : "cannot lock " + path + ": " + systemReason(err);
    ::close(fd), fd = -1;
    return why;
  }
  // Who holds the lock, for the message of a run that is refused. Best effort:
  // the probe below reports a disk that cannot take these few bytes.
  const std::string holder = std::to_string(::getpid()) + " " + hostName() + "\n";
  if (::ftruncate(fd, 0) == 0) {
    const ssize_t written = ::pwrite(fd, holder.data(), holder.size(), 0);
    (void)written;
  }
  return "";
}

// A file can be created, written and removed: the run will need all three.
std::string probe(const std::string& dir) {
  const std::string path = temporaryName(dir, "probe", static_cast<long>(::getpid()));
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return "cannot create a file in " + dir + ": " + systemReason(errno);
  const int err = ::write(fd, "x", 1) == 1 ? 0 : errno;
  ::close(fd);
  const std::string removed = removeIfExists(path);
  if (err != 0) return "cannot write a file in " + dir + ": " + systemReason(err);
  return removed;
}

// Temporaries of earlier runs, killed before they could remove them. Only
// called under the lock: no live run writes here.
std::string removeStaleTemporaries(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (!d) return "cannot list " + dir + ": " + systemReason(errno);
  std::vector<std::string> stale;
  while (const dirent* e = ::readdir(d))
    if (isTemporaryName(e->d_name)) stale.push_back(dir + "/" + e->d_name);
  ::closedir(d);
  for (const std::string& path : stale) {
    const std::string error = removeIfExists(path);
    if (!error.empty()) return error;
  }
  return "";
}

std::string withoutTrailingSlashes(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

}  // namespace

OutputDirectory::OutputDirectory(const std::string& path, const RCP<const Comm>& comm)
    : path_(withoutTrailingSlashes(path)), comm_(comm) {
  if (path_.empty()) throw CollectiveError("no output directory given");
  std::string error;
  if (comm->getRank() == 0) {
    error = makeDirectories(path_);
    if (error.empty()) error = lock(path_, lockFd_);
    if (error.empty()) error = probe(path_);
    if (error.empty()) error = removeStaleTemporaries(path_);
    if (!error.empty() && lockFd_ >= 0) ::close(lockFd_), lockFd_ = -1;
  }
  error = rootError(*comm, error);
  if (!error.empty()) throw CollectiveError("output directory " + path_ + ": " + error);
  rootPid_ = broadcastFromRoot(*comm, static_cast<long>(::getpid()));
}

OutputDirectory::~OutputDirectory() {
  // The lock file stays: removing it would let a run that opened it just
  // before lock a file that the next run no longer sees.
  if (lockFd_ >= 0) ::close(lockFd_);
}

const char* OutputDirectory::lockName() { return kLockName; }

std::string OutputDirectory::temporary(const std::string& name) const { return temporaryName(path_, name, rootPid_); }

void requireWritableFile(const std::string& path, const std::string& what, const RCP<const Comm>& comm) {
  std::string error;
  if (comm->getRank() == 0) {
    const std::string dir = directoryOf(path);
    struct stat st;
    if (path.empty() || path.back() == '/') error = "no file name given";
    else if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) error = "is a directory";
    // The file is replaced by a rename: a device, FIFO or socket in its place
    // (say /dev/null) would be replaced itself, not written to.
    else if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      error = "is not a regular file (" + fileKind(st.st_mode) + "); it would be replaced by a file, not written to";
    else if (::stat(dir.c_str(), &st) != 0)
      error = errno == ENOENT ? "directory " + dir + " does not exist" : "cannot use directory " + dir + ": " + systemReason(errno);
    else if (!S_ISDIR(st.st_mode)) error = dir + " is not a directory";
    else error = probe(dir);
  }
  error = rootError(*comm, error);
  if (!error.empty()) throw CollectiveError(what + " " + path + ": " + error);
}

void requireDistinctFiles(const std::vector<RunFile>& files, const RCP<const Comm>& comm) {
  std::string error;
  if (comm->getRank() == 0) {
    for (size_t i = 0; i < files.size() && error.empty(); ++i)
      for (size_t j = i + 1; j < files.size() && error.empty(); ++j) {
        const RunFile &a = files[i], &b = files[j];
        if (a.path.empty() || b.path.empty() || !(a.written || b.written) || !sameFile(a.path, b.path)) continue;
        const RunFile& w = a.written ? a : b;  // the one that would be overwritten names the fault
        const RunFile& other = a.written ? b : a;
        error = w.role + " " + w.path + " is " + other.role + " (" + other.path + ")" +
                (other.written ? "; two outputs of one run need two files" : "; the run would overwrite it");
      }
  }
  error = rootError(*comm, error);
  if (!error.empty()) throw CollectiveError(error);
}

}  // namespace IO
}  // namespace Tribos
