// OutputDirectory and requireWritableFile: a directory is created with its
// parents and locked for the run; a second run on it (a second instance in
// this process, or another process) is refused naming the holder; a killed
// holder leaves no stale lock; a regular file in the way, a read-only file
// system and a missing directory are refused with the cause; temporaries of
// earlier killed runs are removed and nothing else is.
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cstring>
#include <iostream>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

std::string hostName() {
  char name[256] = "";
  ::gethostname(name, sizeof name - 1);
  return name;
}

// The message of the CollectiveError that f throws on every rank ("" and a
// failed check if it does not); the same on every rank.
template <class F>
std::string refusal(const std::string& label, const Comm& comm, F&& f) {
  std::string message;
  bool refused = false;
  try {
    f();
  } catch (const CollectiveError& e) {
    refused = true, message = e.what();
  }
  CHECK(refused, label << ": refused");
  CHECK(message == IO::broadcastFromRoot(comm, message), label << ": the same message on every rank");
  if (comm.getRank() == 0 && refused) std::cout << "  " << label << ": " << message << std::endl;
  return message;
}

void createsAndLocks(const std::string& base, const RCP<const Comm>& comm) {
  const std::string path = base + "/a/b/c";
  const long rootPid = IO::broadcastFromRoot(*comm, static_cast<long>(::getpid()));
  IO::OutputDirectory dir(path + "/", comm);
  CHECK(dir.path() == path, "path without the trailing slash: " << dir.path());
  struct stat st;
  CHECK(::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode), "directory and parents created");
  const std::string tmp = dir.temporary("solution.h5");
  CHECK(tmp == path + "/.solution.h5." + std::to_string(rootPid) + ".tmp", "temporary name " << tmp);
  CHECK(IO::isTemporaryName(IO::fileNameOf(tmp)), "temporary recognised as one");
  if (comm->getRank() == 0) {
    const auto names = listDirectory(path);
    CHECK(names == std::vector<std::string>{".tribos.lock"}, "only the lock file, no probe left: " << names.size());
    CHECK(readFile(path + "/.tribos.lock") == std::to_string(rootPid) + " " + hostName() + "\n", "lock file names the run");
  }

  // flock locks belong to an open file description: a second open in this
  // process conflicts like another process.
  const std::string holder = "in use by another run (process " + std::to_string(rootPid) + " on host " + hostName() + ")";
  std::string m = refusal("second instance", *comm, [&] { IO::OutputDirectory again(path, comm); });
  CHECK(contains(m, holder) && contains(m, path), "names the directory and the holder: " << m);
  m = refusal("second instance, other spelling", *comm, [&] { IO::OutputDirectory again(base + "/a/b/./c", comm); });
  CHECK(contains(m, "in use"), "same directory by another name: " << m);

  // Another process (rank 0 forks; the child uses no MPI).
  if (comm->getRank() == 0) {
    const pid_t child = ::fork();
    if (child == 0) {
      int status = 2;
      try {
        IO::OutputDirectory other(path, rcp(new Teuchos::SerialComm<int>()));
        status = 3;
      } catch (const CollectiveError& e) {
        status = contains(e.what(), holder) ? 0 : 1;
      }
      ::_exit(status);
    }
    int status = -1;
    ::waitpid(child, &status, 0);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "another process is refused naming this one (child status "
                                                              << (WIFEXITED(status) ? WEXITSTATUS(status) : -1) << ")");
  }
}

// A run killed while it holds the lock: the next run takes the directory.
void killedHolder(const std::string& base, const RCP<const Comm>& comm) {
  const std::string path = base + "/killed";
  pid_t child = -1;
  if (comm->getRank() == 0) {
    int ready[2];
    CHECK(::pipe(ready) == 0, "pipe");
    child = ::fork();
    if (child == 0) {
      ::close(ready[0]);
      try {
        IO::OutputDirectory held(path, rcp(new Teuchos::SerialComm<int>()));
        CHECK(::write(ready[1], "y", 1) == 1, "signal");
        for (;;) ::pause();
      } catch (...) {
      }
      ::_exit(1);
    }
    ::close(ready[1]);
    char c = 0;
    CHECK(::read(ready[0], &c, 1) == 1 && c == 'y', "the child holds the lock");
    ::close(ready[0]);
  }
  const long childPid = IO::broadcastFromRoot(*comm, static_cast<long>(child));
  const std::string m = refusal("held by a live process", *comm, [&] { IO::OutputDirectory dir(path, comm); });
  CHECK(contains(m, "process " + std::to_string(childPid) + " on host"), "names the child: " << m);
  if (comm->getRank() == 0) {
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
  }
  comm->barrier();
  bool taken = true;
  try {
    IO::OutputDirectory dir(path, comm);
  } catch (const std::exception& e) {
    taken = false;
    if (comm->getRank() == 0) std::cerr << e.what() << std::endl;
  }
  CHECK(taken, "the lock of a killed run is gone with it");
  IO::OutputDirectory first(path, comm);
}

void releasedAtDestruction(const std::string& base, const RCP<const Comm>& comm) {
  { IO::OutputDirectory dir(base + "/released", comm); }
  bool taken = true;
  try {
    IO::OutputDirectory dir(base + "/released", comm);
  } catch (const std::exception&) {
    taken = false;
  }
  CHECK(taken, "a destroyed OutputDirectory releases the lock");
}

void refusedPaths(const std::string& base, const RCP<const Comm>& comm) {
  if (comm->getRank() == 0) writePlainFile(base + "/plain", "x");
  comm->barrier();
  std::string m = refusal("regular file at the path", *comm, [&] { IO::OutputDirectory dir(base + "/plain", comm); });
  CHECK(contains(m, "regular file") && contains(m, base + "/plain"), "says a regular file is in the way: " << m);
  m = refusal("regular file as a parent", *comm, [&] { IO::OutputDirectory dir(base + "/plain/sub", comm); });
  CHECK(contains(m, "regular file"), "says a regular file is in the way: " << m);
  m = refusal("empty path", *comm, [&] { IO::OutputDirectory dir("", comm); });

  // A read-only file system (as root, permissions do not stop anything).
  const std::string ro = base + "/readonly";
  std::string error;
  if (comm->getRank() == 0) {
    ::mkdir(ro.c_str(), 0755);
    if (::mount("tribos_test", ro.c_str(), "tmpfs", MS_RDONLY, "size=16k") != 0) error = std::strerror(errno);
  }
  error = IO::rootError(*comm, error);
  if (error.empty()) {
    m = refusal("read-only file system", *comm, [&] { IO::OutputDirectory dir(ro + "/out", comm); });
    CHECK(contains(m, "Read-only file system"), "gives the cause: " << m);
    comm->barrier();
    if (comm->getRank() == 0) ::umount2(ro.c_str(), MNT_DETACH);
  } else if (comm->getRank() == 0) {
    std::cout << "  read-only file system: skipped, cannot mount a tmpfs (" << error << ")" << std::endl;
  }
  if (::geteuid() != 0) {
    const std::string closed = base + "/closed";
    if (comm->getRank() == 0) ::mkdir(closed.c_str(), 0500);
    comm->barrier();
    m = refusal("permission denied", *comm, [&] { IO::OutputDirectory dir(closed + "/out", comm); });
    CHECK(contains(m, "Permission denied"), "gives the cause: " << m);
  }
}

void staleTemporaries(const std::string& base, const RCP<const Comm>& comm) {
  const std::string path = base + "/stale";
  { IO::OutputDirectory dir(path, comm); }
  const std::vector<std::string> stale = {".solution.h5.12345.tmp", ".summary.json.1.tmp", ".probe.99.tmp"};
  const std::vector<std::string> kept = {"solution.h5", "notes.tmp", ".hidden", ".x.tmp", "a.b.123.tmp", ".y.12a.tmp"};
  if (comm->getRank() == 0)
    for (const auto& names : {stale, kept})
      for (const std::string& f : names) writePlainFile(path + "/" + f, "earlier run");
  comm->barrier();
  IO::OutputDirectory dir(path, comm);
  if (comm->getRank() != 0) return;
  for (const std::string& f : stale) CHECK(!exists(path + "/" + f), "stale temporary " << f << " removed");
  for (const std::string& f : kept) CHECK(exists(path + "/" + f), "file " << f << " kept");
}

void writableFiles(const std::string& base, const RCP<const Comm>& comm) {
  if (comm->getRank() == 0) ::mkdir((base + "/files").c_str(), 0755);
  comm->barrier();
  IO::requireWritableFile(base + "/files/summary.json", "--summary", comm);
  if (comm->getRank() == 0) CHECK(listDirectory(base + "/files").empty(), "the probe leaves nothing");
  std::string m = refusal("missing directory", *comm, [&] {
    IO::requireWritableFile(base + "/nowhere/summary.json", "--summary", comm);
  });
  CHECK(m.rfind("--summary " + base + "/nowhere/summary.json", 0) == 0 && contains(m, "does not exist"),
        "names the option, the file and the cause: " << m);
  m = refusal("a directory", *comm, [&] { IO::requireWritableFile(base + "/files", "--summary", comm); });
  CHECK(contains(m, "is a directory"), "gives the cause: " << m);
  if (comm->getRank() == 0) writePlainFile(base + "/plainfile", "x");
  comm->barrier();
  m = refusal("a file as its directory", *comm, [&] {
    IO::requireWritableFile(base + "/plainfile/summary.json", "--summary", comm);
  });
  CHECK(contains(m, "not a directory"), "gives the cause: " << m);
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const std::string base = scratchDirectory(*comm, "output_directory");
  createsAndLocks(base, comm);
  killedHolder(base, comm);
  releasedAtDestruction(base, comm);
  refusedPaths(base, comm);
  staleTemporaries(base, comm);
  writableFiles(base, comm);
  comm->barrier();
  if (comm->getRank() == 0) removeTree(base);
  return verdict(*comm, "io_test_output_directory");
}
