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
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cerrno>
#include <cstring>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultWriter.hpp"

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
std::string refusal(const std::string& label, const Comm& comm, Teuchos::FancyOStream& out, bool& success, F&& f) {
  std::string message;
  bool refused = false;
  try {
    f();
  } catch (const CollectiveError& e) {
    refused = true, message = e.what();
  }
  out << label << ": " << (refused ? message : "not refused") << "\n";
  TEST_ASSERT(refused);
  TEST_EQUALITY(message, broadcastFromRoot(comm, message));  // the same message on every rank
  return message;
}

// The lock holder's description in a refusal.
std::string holderOf(long pid) {
  return "in use by another run (process " + std::to_string(pid) + " on host " + hostName() + ")";
}

// Mounts a tmpfs with the given flags and options at path (rank 0); "" or why not.
std::string mountTmpfs(const std::string& path, unsigned long flags, const std::string& options, const Comm& comm) {
  std::string error;
  if (comm.getRank() == 0) {
    ::mkdir(path.c_str(), 0755);
    if (::mount("tribos_test", path.c_str(), "tmpfs", flags, options.c_str()) != 0) error = std::strerror(errno);
  }
  return rootError(comm, error);
}

}  // namespace

TEUCHOS_UNIT_TEST(OutputDirectory, CreatesParentsAndLocks) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string path = scratch.path() + "/a/b/c";
  const long rootPid = broadcastFromRoot(*comm, static_cast<long>(::getpid()));
  IO::OutputDirectory dir(path + "/", comm);
  TEST_EQUALITY(dir.path(), path);  // without the trailing slash
  struct stat st = {};
  TEST_EQUALITY(::stat(path.c_str(), &st), 0);  // directory and parents created
  TEST_ASSERT(S_ISDIR(st.st_mode));
  const std::string tmp = dir.temporary("solution.h5");
  TEST_EQUALITY(tmp, path + "/.solution.h5." + std::to_string(rootPid) + ".tmp");
  TEST_ASSERT(isTemporaryName(fileNameOf(tmp)));
  if (comm->getRank() == 0) {
    const auto names = listDirectory(path);
    out << "files: " << names.size() << "\n";
    TEST_ASSERT(names == std::vector<std::string>{".tribos.lock"});  // only the lock file, no probe left
    TEST_EQUALITY(readFile(path + "/.tribos.lock"), std::to_string(rootPid) + " " + hostName() + "\n");
  }
}

// flock locks belong to an open file description: a second open in this
// process conflicts like another process.
TEUCHOS_UNIT_TEST(OutputDirectory, SecondInstanceRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path(), path = base + "/a/b/c";
  const long rootPid = broadcastFromRoot(*comm, static_cast<long>(::getpid()));
  IO::OutputDirectory dir(path, comm);
  std::string m = refusal("second instance", *comm, out, success, [&] { IO::OutputDirectory again(path, comm); });
  TEST_ASSERT(contains(m, holderOf(rootPid)));  // names the holder
  TEST_ASSERT(contains(m, path));               // and the directory
  m = refusal("second instance, other spelling", *comm, out, success,
              [&] { IO::OutputDirectory again(base + "/a/b/./c", comm); });
  TEST_ASSERT(contains(m, "in use"));  // same directory by another name
}

// Another process (rank 0 forks; the child uses no MPI).
TEUCHOS_UNIT_TEST(OutputDirectory, AnotherProcessRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string path = scratch.path() + "/a/b/c";
  const long rootPid = broadcastFromRoot(*comm, static_cast<long>(::getpid()));
  IO::OutputDirectory dir(path, comm);
  if (comm->getRank() != 0) return;
  const pid_t child = ::fork();
  if (child == 0) {
    int status = 2;
    try {
      IO::OutputDirectory other(path, rcp(new Teuchos::SerialComm<int>()));
      status = 3;
    } catch (const CollectiveError& e) {
      status = contains(e.what(), holderOf(rootPid)) ? 0 : 1;
    }
    ::_exit(status);
  }
  int status = -1;
  ::waitpid(child, &status, 0);
  // refused naming this process
  out << "child status " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1) << "\n";
  TEST_ASSERT(WIFEXITED(status));
  TEST_EQUALITY(WEXITSTATUS(status), 0);
}

// A run killed while it holds the lock: the next run takes the directory.
TEUCHOS_UNIT_TEST(OutputDirectory, KilledHolderLeavesNoLock) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string path = scratch.path() + "/killed";
  pid_t child = -1;
  if (comm->getRank() == 0) {
    int ready[2];
    TEST_EQUALITY(::pipe(ready), 0);
    child = ::fork();
    if (child == 0) {
      ::close(ready[0]);
      try {
        IO::OutputDirectory held(path, rcp(new Teuchos::SerialComm<int>()));
        TEST_EQUALITY(::write(ready[1], "y", 1), 1);  // a failure shows as the parent's read below
        for (;;) ::pause();
      } catch (...) {
      }
      ::_exit(1);
    }
    ::close(ready[1]);
    char c = 0;
    TEST_EQUALITY(::read(ready[0], &c, 1), 1);  // the child holds the lock
    TEST_EQUALITY(c, 'y');
    ::close(ready[0]);
  }
  const long childPid = broadcastFromRoot(*comm, static_cast<long>(child));
  const std::string m =
      refusal("held by a live process", *comm, out, success, [&] { IO::OutputDirectory dir(path, comm); });
  TEST_ASSERT(contains(m, "process " + std::to_string(childPid) + " on host"));  // names the child
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
    out << e.what() << "\n";
  }
  TEST_ASSERT(taken);  // the lock of a killed run is gone with it
  IO::OutputDirectory first(path, comm);
}

TEUCHOS_UNIT_TEST(OutputDirectory, ReleasedAtDestruction) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  { IO::OutputDirectory dir(base + "/released", comm); }
  bool taken = true;
  try {
    IO::OutputDirectory dir(base + "/released", comm);
  } catch (const std::exception& e) {
    taken = false;
    out << e.what() << "\n";
  }
  TEST_ASSERT(taken);
}

TEUCHOS_UNIT_TEST(OutputDirectory, RegularFileRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) writePlainFile(base + "/plain", "x");
  comm->barrier();
  std::string m = refusal("regular file at the path", *comm, out, success,
                          [&] { IO::OutputDirectory dir(base + "/plain", comm); });
  TEST_ASSERT(contains(m, "regular file"));
  TEST_ASSERT(contains(m, base + "/plain"));
  m = refusal("regular file as a parent", *comm, out, success,
              [&] { IO::OutputDirectory dir(base + "/plain/sub", comm); });
  TEST_ASSERT(contains(m, "regular file"));
}

TEUCHOS_UNIT_TEST(OutputDirectory, EmptyPathRefused) {
  const auto comm = Tpetra::getDefaultComm();
  refusal("empty path", *comm, out, success, [&] { IO::OutputDirectory dir("", comm); });
}

// As root, permissions do not stop anything: a read-only tmpfs does (skipped
// where mounting is not allowed).
TEUCHOS_UNIT_TEST(OutputDirectory, ReadOnlyFileSystemRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string ro = scratch.path() + "/readonly";
  const std::string error = mountTmpfs(ro, MS_RDONLY, "size=16k", *comm);
  if (!error.empty()) {
    out << "skipped, cannot mount a tmpfs (" << error << ")\n";
    return;
  }
  const std::string m =
      refusal("read-only file system", *comm, out, success, [&] { IO::OutputDirectory dir(ro + "/out", comm); });
  TEST_ASSERT(contains(m, "Read-only file system"));
  comm->barrier();
  if (comm->getRank() == 0) ::umount2(ro.c_str(), MNT_DETACH);
}

// Not as root (where permissions do not stop anything).
TEUCHOS_UNIT_TEST(OutputDirectory, PermissionDeniedRefused) {
  if (::geteuid() == 0) {
    out << "skipped as root\n";
    return;
  }
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string closed = scratch.path() + "/closed";
  if (comm->getRank() == 0) ::mkdir(closed.c_str(), 0500);
  comm->barrier();
  const std::string m =
      refusal("permission denied", *comm, out, success, [&] { IO::OutputDirectory dir(closed + "/out", comm); });
  TEST_ASSERT(contains(m, "Permission denied"));
}

// Temporaries of earlier killed runs are removed and nothing else is.
TEUCHOS_UNIT_TEST(OutputDirectory, StaleTemporariesRemoved) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string path = scratch.path() + "/stale";
  { IO::OutputDirectory dir(path, comm); }
  const std::vector<std::string> stale = {".solution.h5.12345.tmp", ".summary.json.1.tmp", ".probe.99.tmp"};
  const std::vector<std::string> kept = {"solution.h5", "notes.tmp", ".hidden", ".x.tmp", "a.b.123.tmp", ".y.12a.tmp"};
  if (comm->getRank() == 0)
    for (const auto& names : {stale, kept})
      for (const std::string& f : names) writePlainFile(path + "/" + f, "earlier run");
  comm->barrier();
  IO::OutputDirectory dir(path, comm);
  if (comm->getRank() != 0) return;
  for (const std::string& f : stale) {
    out << "stale temporary " << f << "\n";
    TEST_ASSERT(!exists(path + "/" + f));
  }
  for (const std::string& f : kept) {
    out << "kept " << f << "\n";
    TEST_ASSERT(exists(path + "/" + f));
  }
}

TEUCHOS_UNIT_TEST(RequireWritableFile, ProbeLeavesNothing) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) ::mkdir((base + "/files").c_str(), 0755);
  comm->barrier();
  IO::requireWritableFile(base + "/files/summary.json", "--summary", comm);
  if (comm->getRank() == 0) TEST_ASSERT(listDirectory(base + "/files").empty());
}

TEUCHOS_UNIT_TEST(RequireWritableFile, MissingDirectoryRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  const std::string m = refusal("missing directory", *comm, out, success, [&] {
    IO::requireWritableFile(base + "/nowhere/summary.json", "--summary", comm);
  });
  // names the option, the file and the cause
  TEST_EQUALITY(m.rfind("--summary " + base + "/nowhere/summary.json", 0), size_t(0));
  TEST_ASSERT(contains(m, "does not exist"));
}

TEUCHOS_UNIT_TEST(RequireWritableFile, DirectoryRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) ::mkdir((base + "/files").c_str(), 0755);
  comm->barrier();
  const std::string m =
      refusal("a directory", *comm, out, success, [&] { IO::requireWritableFile(base + "/files", "--summary", comm); });
  TEST_ASSERT(contains(m, "is a directory"));
}

TEUCHOS_UNIT_TEST(RequireWritableFile, FileAsDirectoryRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) writePlainFile(base + "/plainfile", "x");
  comm->barrier();
  const std::string m = refusal("a file as its directory", *comm, out, success, [&] {
    IO::requireWritableFile(base + "/plainfile/summary.json", "--summary", comm);
  });
  TEST_ASSERT(contains(m, "not a directory"));
}

// A lock file that is a link or not a regular file is refused, and the file
// a link points to is left as it was (the lock file is truncated and written).
TEUCHOS_UNIT_TEST(OutputDirectory, LockThroughLinkRefused) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "output_directory");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) {
    ::mkdir((base + "/out").c_str(), 0755);
    writePlainFile(base + "/victim", "keep me\n");
    const int linked = ::symlink((base + "/victim").c_str(), (base + "/out/.tribos.lock").c_str());
    ::mkdir((base + "/fifo_out").c_str(), 0755);
    const int made = ::mkfifo((base + "/fifo_out/.tribos.lock").c_str(), 0644);
    TEST_ASSERT(linked == 0 && made == 0);
  }
  comm->barrier();
  std::string m = refusal("lock through a link", *comm, out, success, [&] { IO::OutputDirectory dir(base + "/out", comm); });
  TEST_ASSERT(contains(m, "is a symbolic link"));
  if (comm->getRank() == 0) TEST_EQUALITY(readFile(base + "/victim"), "keep me\n");
  m = refusal("lock a FIFO", *comm, out, success, [&] { IO::OutputDirectory dir(base + "/fifo_out", comm); });
  TEST_ASSERT(contains(m, "not a regular file (a FIFO (named pipe))"));
}

// An output that exists and is not a regular file (a device, a FIFO) would
// be replaced by the rename that writes it: refused.
TEUCHOS_UNIT_TEST(RequireWritableFile, DeviceRefused) {
  const auto comm = Tpetra::getDefaultComm();
  const std::string m =
      refusal("/dev/null", *comm, out, success, [&] { IO::requireWritableFile("/dev/null", "--summary", comm); });
  TEST_ASSERT(contains(m, "--summary /dev/null: is not a regular file (a character device)"));
}

// Outputs that are an input or another output are refused naming both; two
// inputs may be one file; names that reach one file through a link or
// through a directory not made yet are seen through.
TEUCHOS_UNIT_TEST(RequireDistinctFiles, CollisionsNamed) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "distinct_files");
  const std::string base = scratch.path();
  if (comm->getRank() == 0) {
    writePlainFile(base + "/input.xml", "<x/>\n");
    const int linked = ::symlink((base + "/input.xml").c_str(), (base + "/link.xml").c_str());
    TEST_ASSERT(linked == 0);
  }
  comm->barrier();
  const IO::RunFile input{"the input file", base + "/input.xml", false};
  IO::requireDistinctFiles({input, {"Mesh/File", base + "/input.xml", false}, {"--summary", base + "/s.json", true}},
                           comm);  // two inputs alike, a distinct output: accepted
  std::string m = refusal("summary is the input", *comm, out, success, [&] {
    IO::requireDistinctFiles({input, {"--summary", base + "/link.xml", true}}, comm);
  });
  TEST_ASSERT(contains(m, "--summary " + base + "/link.xml is the input file"));
  TEST_ASSERT(contains(m, "would overwrite it"));
  m = refusal("through a directory not made yet", *comm, out, success, [&] {
    IO::requireDistinctFiles({input, {"--export-fclib", base + "/new/../input.xml", true}}, comm);
  });
  TEST_ASSERT(contains(m, "--export-fclib"));
  m = refusal("two outputs", *comm, out, success, [&] {
    IO::requireDistinctFiles({{"--summary", base + "/out/s.json", true}, {"the result file s.json", base + "/out/./s.json", true}},
                             comm);
  });
  TEST_ASSERT(contains(m, "two outputs of one run need two files"));
}

// Two names of one file (through "..") are the same file, two names in one
// directory are not; the temporary of a path is in its directory.
TEUCHOS_UNIT_TEST(FileSystem, SameFileAndTemporaryPath) {
  const auto self = rcp(new Teuchos::SerialComm<int>());  // names only: every rank its own scratch
  ScratchDirectory scratch(self, "samefile");
  const std::string base = scratch.path();
  ::mkdir((base + "/d").c_str(), 0700);
  TEST_ASSERT(sameFile(base + "/d/../d/x", base + "/d/x"));  // neither exists
  TEST_ASSERT(!sameFile(base + "/d/x", base + "/d/y"));
  IO::writeFileAtomically(base + "/d/x", "x\n");
  TEST_ASSERT(sameFile(base + "/d/../d/x", base + "/d/x"));  // both exist
  TEST_ASSERT(!sameFile(base + "/d/x", base + "/d/y"));      // one exists
  TEST_EQUALITY(directoryOf(temporaryPathFor(base + "/d/x")), base + "/d");
  TEST_ASSERT(isTemporaryName(fileNameOf(temporaryPathFor(base + "/d/x"))));
}
