#include "Tribos_GeoScript.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "Tribos_CleanupOnSignal.hpp"
#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

extern char** environ;

namespace Tribos {
namespace Mesh {

namespace {

// Without a memory limit, what Gmsh may write: far beyond any mesh a run
// can solve, short of filling a disk.
constexpr double kUnboundedFileBytes = 64.0 * 1024 * 1024 * 1024;

bool isExecutableFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// A child's end, as waitpid tells it, or that the deadline came first.
struct Ending {
  bool timedOut = false;
  bool known = true;  // false: the status was not ours to read (someone else reaped the child)
  int status = 0;
};

// The limits and the program of the child, prepared before fork(): the
// child may only make async-signal-safe calls until exec.
struct ChildSetup {
  std::vector<std::string> args, env;
  std::vector<char*> argv, envp;
  std::string log;
  rlim_t memory = RLIM_INFINITY, cpu = RLIM_INFINITY, fileSize = RLIM_INFINITY;
  pid_t parent = 0;

  void finish() {
    for (auto& a : args) argv.push_back(&a[0]);
    argv.push_back(nullptr);
    for (auto& e : env) envp.push_back(&e[0]);
    envp.push_back(nullptr);
  }
};

void setLimit(int resource, rlim_t soft, rlim_t hard) {
  const struct rlimit limit = {soft, hard};
  setrlimit(resource, &limit);
}

// In the child, between fork and exec. A failure is written to the log
// (as Gmsh's own output would be) and ends the child with 127.
[[noreturn]] void runChild(const ChildSetup& s) {
  setpgid(0, 0);                      // its own group: the deadline kills whatever the script started
  prctl(PR_SET_PDEATHSIG, SIGKILL);   // and it dies with the run
  if (getppid() != s.parent) _exit(127);  // the run ended before the line above
  // What the run's threads block or ignore is not the script's: the limits'
  // signals (SIGXCPU, SIGXFSZ) must end it.
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);
  for (int sig : {SIGXCPU, SIGXFSZ, SIGPIPE, SIGTERM, SIGINT, SIGHUP}) signal(sig, SIG_DFL);
  const int in = open("/dev/null", O_RDONLY);
  const int out = open(s.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (in < 0 || out < 0 || dup2(in, 0) < 0 || dup2(out, 1) < 0 || dup2(out, 2) < 0) _exit(127);
#ifdef SYS_close_range
  syscall(SYS_close_range, 3u, ~0u, 0u);  // the run's sockets and files are not the script's
#endif
  if (s.memory != RLIM_INFINITY) setLimit(RLIMIT_AS, s.memory, s.memory);
  setLimit(RLIMIT_CPU, s.cpu, s.cpu + 5);  // SIGXCPU first, SIGKILL 5 s later
  setLimit(RLIMIT_FSIZE, s.fileSize, s.fileSize);
  setLimit(RLIMIT_CORE, 0, 0);
  execve(s.argv[0], s.argv.data(), s.envp.data());
  static const char failed[] = "tribos: cannot run gmsh (execve failed)\n";
  if (write(2, failed, sizeof failed - 1) < 0) _exit(127);
  _exit(127);
}

// Waits for the child until the deadline; then kills its process group.
Ending waitFor(pid_t child, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  auto pause = std::chrono::milliseconds(2);
  Ending ending;
  for (;;) {
    const pid_t r = waitpid(child, &ending.status, WNOHANG);
    if (r == child) break;
    if (r < 0 && errno != EINTR) {
      ending.known = false;
      break;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(-child, SIGKILL);
      while (waitpid(child, &ending.status, 0) < 0 && errno == EINTR) {
      }
      ending.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  // Commands the script left running in the background end with it.
  kill(-child, SIGKILL);
  return ending;
}

// Deeper than Gmsh writes (its HOME, the directory: .fltk/fltk.org/fltk.prefs).
constexpr int kRemovalDepth = 8;

// What the directory `fd` holds, subdirectories `depth` levels deep
// included, by system calls alone (a signal handler's); closes `fd`.
void removeContents(int fd, int depth) {
  alignas(8) char buffer[2048];
  for (long n; (n = syscall(SYS_getdents64, fd, buffer, sizeof buffer)) > 0;)
    for (long at = 0; at < n;) {
      const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + at);
      const char* name = entry->d_name;
      const bool dots = name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0));
      if (!dots && unlinkat(fd, name, 0) != 0 && errno == EISDIR && depth > 0) {
        const int sub = openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (sub >= 0) removeContents(sub, depth - 1);
        unlinkat(fd, name, AT_REMOVEDIR);
      }
      at += entry->d_reclen;
    }
  close(fd);
}

// `dir` and everything in it, in a signal handler.
void removeDirectoryAtOnce(const char* dir) {
  const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) removeContents(fd, kRemovalDepth);
  rmdir(dir);
}

// The child's group killed, and the child gone: it writes no more into its
// directory. Its status is left to waitFor (WNOWAIT).
void stopChild(pid_t child) {
  if (child <= 0) return;
  kill(-child, SIGKILL);
  siginfo_t info{};
  while (waitid(P_PID, child, &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
}

// Directories of a run are named "tribos-geo-HOST-PID-XXXXXX": a run killed
// by SIGKILL (no handler runs) leaves its own, which the next run on that
// host finds by the pid (kill(pid, 0): no such process) and by the lock the
// live run holds on it (flock, released with the process; it also covers a
// run whose pid this process cannot see).
std::string directoryPrefix() {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  std::string prefix = "tribos-geo-";
  for (const char* c = host; *c && prefix.size() < 80; ++c)
    prefix += std::isalnum(static_cast<unsigned char>(*c)) || *c == '.' || *c == '-' ? *c : '_';
  return prefix + "-";
}

// The pid in `name`, a directory of this host's runs, or 0.
pid_t ownerOf(const std::string& name, const std::string& prefix) {
  if (name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string rest = name.substr(prefix.size());  // PID-XXXXXX (mkdtemp's letters and digits)
  const size_t dash = rest.find('-');
  if (dash == 0 || dash > 9 || dash == std::string::npos || rest.size() != dash + 7) return 0;
  for (size_t i = 0; i < rest.size(); ++i)
    if (i != dash && !(i < dash ? std::isdigit(static_cast<unsigned char>(rest[i]))
                                : std::isalnum(static_cast<unsigned char>(rest[i]))))
      return 0;
  return static_cast<pid_t>(std::stol(rest.substr(0, dash)));
}

bool processExists(pid_t pid) { return kill(pid, 0) == 0 || errno == EPERM; }

// A leftover of this host's runs in `tmp`: its owner gone, nobody holding its
// lock, this user's own directory (not a link).
bool isLeftover(const std::string& tmp, const std::string& name, const std::string& prefix) {
  const pid_t owner = ownerOf(name, prefix);
  if (owner <= 0 || processExists(owner)) return false;
  const std::string path = tmp + "/" + name;
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != geteuid()) return false;
  const int fd = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  const bool unlocked = flock(fd, LOCK_EX | LOCK_NB) == 0;
  close(fd);
  return unlocked;
}

// Removes the leftovers of this host's runs in `tmp`; what cannot be read
// or removed is left as it was.
void sweepLeftovers(const std::string& tmp, const std::string& prefix) {
  std::vector<std::string> names;
  if (DIR* d = opendir(tmp.c_str())) {
    while (const struct dirent* e = readdir(d))
      if (std::strncmp(e->d_name, prefix.c_str(), prefix.size()) == 0) names.push_back(e->d_name);
    closedir(d);
  }
  for (const auto& name : names)
    if (isLeftover(tmp, name, prefix)) {
      std::error_code ec;
      std::filesystem::remove_all(tmp + "/" + name, ec);
    }
}

// The end of Gmsh's log: at most its last 64 kB, in lines.
std::vector<std::string> logTail(const std::string& log) {
  std::ifstream in(log, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - 65536));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

bool mentions(const std::vector<std::string>& lines, const std::vector<std::string>& words) {
  for (const auto& line : lines)
    for (const auto& w : words)
      if (line.find(w) != std::string::npos) return true;
  return false;
}

// Gmsh's last error lines ("Error   : ..." without the prefix), else its
// last lines; at most three, each cut to 300 characters.
std::string lastLines(const std::vector<std::string>& lines) {
  std::vector<std::string> errors;
  for (const auto& line : lines)
    if (line.rfind("Error", 0) == 0) {
      const size_t colon = line.find(':');
      errors.push_back(colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1)));
    }
  const std::vector<std::string>& from = errors.empty() ? lines : errors;
  std::string text;
  for (size_t i = from.size() > 3 ? from.size() - 3 : 0; i < from.size(); ++i)
    text += (text.empty() ? "" : "; ") + (from[i].size() > 300 ? from[i].substr(0, 300) + "..." : from[i]);
  return text.empty() ? "(no output)" : text;
}

std::string seconds(double s) {
  std::ostringstream os;
  os << s << " s";
  return os.str();
}

// The message for a child that did not leave a mesh, or "" when it did.
// runSignal: the signal that told the run to end (and killed the child), or 0.
std::string failure(const Ending& e, const std::vector<std::string>& log, const MeshFileOptions& options,
                    double fileBound, int runSignal) {
  if (runSignal != 0)
    return "Gmsh was stopped: the run received signal " + std::to_string(runSignal) + " (" + strsignal(runSignal) + ")";
  const std::string timeLimit = "its time limit of " + seconds(options.geoTimeLimit) + " (Mesh/Geo Time Limit)";
  if (e.timedOut)
    return "Gmsh did not finish meshing the script within " + timeLimit +
           " and was stopped; raise the limit for a script known to end, or mesh it once with gmsh and give the .msh";
  const bool signaled = e.known && WIFSIGNALED(e.status);
  const int signal = signaled ? WTERMSIG(e.status) : 0;
  if (signal == SIGXCPU)
    return "Gmsh used up the CPU time of " + timeLimit + " and was stopped";
  if (signal == SIGXFSZ)
    return "Gmsh wrote a file larger than " + detail::describeBytes(fileBound) +
           (options.memoryLimit > 0 ? " (the run's memory limit, which a mesh read whole must fit)" : "") + " and was stopped";
  // An allocation that fails under RLIMIT_AS: std::bad_alloc (Gmsh aborts),
  // or a library that cannot even be mapped when Gmsh starts.
  const bool outOfMemory = mentions(log, {"bad_alloc", "failed to map segment", "Cannot allocate memory", "out of memory",
                                          "Out of memory"});
  if (outOfMemory || (signal == SIGKILL && options.memoryLimit <= 0)) {
    std::string text = "Gmsh ran out of memory meshing the script";
    if (options.memoryLimit > 0)
      text += ": it may use " + detail::describeBytes(options.memoryLimit) +
              " (the run's memory limit: --max-memory, or the memory available on the machine); use a coarser mesh, "
              "or raise --max-memory";
    return text;
  }
  if (signaled)
    return "Gmsh ended by signal " + std::to_string(signal) + " (" + strsignal(signal) + ") meshing the script; its last " +
           "lines: " + lastLines(log);
  if (e.known && WIFEXITED(e.status) && WEXITSTATUS(e.status) != 0)
    return "Gmsh could not mesh the script: " + lastLines(log);
  // Its status reaped elsewhere (SIGCHLD ignored): Gmsh's errors are in its log.
  if (!e.known && mentions(log, {"Error   :"})) return "Gmsh could not mesh the script: " + lastLines(log);
  return "";
}

}  // namespace

std::string gmshExecutable() {
#ifdef TRIBOS_GMSH_EXECUTABLE
  if (isExecutableFile(TRIBOS_GMSH_EXECUTABLE)) return TRIBOS_GMSH_EXECUTABLE;
#endif
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && isExecutableFile(dir + "/gmsh")) return dir + "/gmsh";
  return "";
}

GeoScriptMesh::GeoScriptMesh(const std::string& script, const std::string& file, const MeshFileOptions& options) {
  TRIBOS_REQUIRE(std::isfinite(options.geoTimeLimit) && options.geoTimeLimit > 0,
                 file << ": the time limit of a .geo script must be a positive number of seconds, not "
                      << options.geoTimeLimit);
  ChildSetup setup;
  const std::string gmsh = gmshExecutable();
  TRIBOS_REQUIRE(!gmsh.empty(), file << ": the gmsh program, which meshes .geo scripts, is not installed (Debian: "
                                        "apt-get install gmsh); or give a .msh file");
  makeDirectory(file);
  msh_ = dir_ + "/mesh.msh";
  log_ = dir_ + "/gmsh.log";
  try {
    onSignal_ = std::make_unique<CleanupOnSignal>(
        [this] {
          stopChild(child_.load());
          removeDirectory();
        },
        stopAtOnce, this);
    // (a relative name as ./NAME: a script named "-3" is not an option)
    const std::string scriptArg = script.rfind('/', 0) == 0 ? script : "./" + script;
    setup.args = {gmsh, scriptArg, "-3", "-format", "msh41", "-o", msh_, "-nt", "1", "-v", "4", "-nopopup"};
    for (char** e = environ; *e; ++e)
      if (std::strncmp(*e, "HOME=", 5) != 0) setup.env.push_back(*e);
    setup.env.push_back("HOME=" + dir_);
    setup.finish();
    setup.log = log_;
    const double fileBound = options.memoryLimit > 0 ? options.memoryLimit : kUnboundedFileBytes;
    if (options.memoryLimit > 0) setup.memory = static_cast<rlim_t>(options.memoryLimit);
    setup.cpu = static_cast<rlim_t>(std::ceil(options.geoTimeLimit)) + 1;
    setup.fileSize = static_cast<rlim_t>(fileBound);
    setup.parent = getpid();

    const pid_t child = fork();
    TRIBOS_REQUIRE(child >= 0, file << ": cannot start gmsh: " << std::strerror(errno));
    if (child == 0) runChild(setup);
    setpgid(child, child);  // also here: the group exists whichever process runs first
    child_.store(child);
    const Ending ending = waitFor(child, options.geoTimeLimit);
    const std::string error = failure(ending, logTail(log_), options, fileBound, onSignal_->signal());
    TRIBOS_REQUIRE(error.empty(), file << ": " << error);
    std::error_code ec;
    TRIBOS_REQUIRE(std::filesystem::is_regular_file(msh_, ec),
                   file << ": Gmsh wrote no mesh; its last lines: " << lastLines(logTail(log_)));
  } catch (...) {
    onSignal_.reset();
    removeDirectory();
    close(lock_);
    throw;
  }
}

GeoScriptMesh::~GeoScriptMesh() {
  onSignal_.reset();
  removeDirectory();
  close(lock_);
}

// The leftovers of killed runs removed first, then this run's directory
// made and locked.
void GeoScriptMesh::makeDirectory(const std::string& file) {
  const std::string tmp = std::filesystem::temp_directory_path().string();
  const std::string prefix = directoryPrefix();
  sweepLeftovers(tmp, prefix);
  std::string pattern = tmp + "/" + prefix + std::to_string(getpid()) + "-XXXXXX";
  TRIBOS_REQUIRE(mkdtemp(&pattern[0]),
                 file << ": cannot create a temporary directory for Gmsh in " << tmp << ": " << std::strerror(errno));
  dir_ = pattern;  // mode 0700: the script's output is the run's alone
  lock_ = open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_ < 0 || flock(lock_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    if (lock_ >= 0) close(lock_);
    lock_ = -1;
    rmdir(dir_.c_str());
    throw Error(file + ": cannot lock the temporary directory " + dir_ + " for Gmsh: " + std::strerror(error));
  }
}

void GeoScriptMesh::stopAtOnce(const void* self) {
  const auto* mesh = static_cast<const GeoScriptMesh*>(self);
  stopChild(mesh->child_.load());
  removeDirectoryAtOnce(mesh->dir_.c_str());
}

void GeoScriptMesh::removeDirectory() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

}  // namespace Mesh
}  // namespace Tribos
