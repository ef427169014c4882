// ResultSet: a new set replaces the old one; a run that fails before commit
// leaves the old set and no temporary; a commit that finds a file missing
// changes nothing; a commit that fails half way has removed the old summary
// first, so no directory ever shows a complete-looking mixed set. And
// writeFileAtomically: replaced or untouched, never a temporary left.
#include <sys/stat.h>

#include <Tpetra_Core.hpp>

#include <iostream>
#include <stdexcept>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultSet.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

const std::vector<std::string> kSet = {"solution.h5", "solution.xmf", "summary.json"};

// Writes the whole set as version `tag` and commits it.
void writeSet(const IO::OutputDirectory& dir, const std::string& tag, const RCP<const Comm>& comm) {
  IO::ResultSet files(dir, comm);
  for (const std::string& f : kSet) IO::writeTextFile(files.add(f), tag + " " + f, comm);
  files.commit();
}

void checkSet(const std::string& dir, const std::string& tag, const std::string& label, const Comm& comm) {
  if (comm.getRank() != 0) return;
  for (const std::string& f : kSet) CHECK(readFile(dir + "/" + f) == tag + " " + f, label << ": " << f << " is " << tag);
  CHECK(temporariesIn(dir).empty(), label << ": no temporaries");
}

template <class E, class F>
std::string expectCollective(const std::string& label, const Comm& comm, F&& f) {
  std::string message;
  bool thrown = false;
  try {
    f();
  } catch (const E& e) {
    thrown = true, message = e.what();
  }
  CHECK(thrown, label << ": thrown on every rank");
  CHECK(message == IO::broadcastFromRoot(comm, message), label << ": the same message on every rank");
  if (comm.getRank() == 0) std::cout << "  " << label << ": " << message << std::endl;
  return message;
}

void replaced(const IO::OutputDirectory& dir, const RCP<const Comm>& comm) {
  writeSet(dir, "v1", comm);
  checkSet(dir.path(), "v1", "first set", *comm);
  writeSet(dir, "v2", comm);
  checkSet(dir.path(), "v2", "second set", *comm);
  if (comm->getRank() == 0) CHECK(exists(dir.path() + "/.tribos.lock"), "the lock stays");
}

// An exception between writing and commit (a solver failure, a write error).
void failureBeforeCommit(const IO::OutputDirectory& dir, const RCP<const Comm>& comm) {
  bool caught = false;
  try {
    IO::ResultSet files(dir, comm);
    IO::writeTextFile(files.add("solution.h5"), "v3 solution.h5", comm);
    IO::writeTextFile(files.add("solution.xmf"), "v3 solution.xmf", comm);
    files.add("summary.json");
    if (comm->getRank() == 0) CHECK(temporariesIn(dir.path()).size() == 2, "two temporaries written");
    throw std::runtime_error("the run failed");
  } catch (const std::runtime_error&) {
    caught = true;
  }
  CHECK(caught, "exception passed through");
  checkSet(dir.path(), "v2", "failure before commit", *comm);
}

void missingFile(const IO::OutputDirectory& dir, const RCP<const Comm>& comm) {
  const std::string m = expectCollective<RunFailure>("summary never written", *comm, [&] {
    IO::ResultSet files(dir, comm);
    IO::writeTextFile(files.add("solution.h5"), "v3 solution.h5", comm);
    IO::writeTextFile(files.add("solution.xmf"), "v3 solution.xmf", comm);
    files.add("summary.json");
    files.commit();
  });
  CHECK(contains(m, "summary.json was not written"), "names the missing file: " << m);
  checkSet(dir.path(), "v2", "missing file", *comm);
}

// The old solution.xmf cannot be removed (a directory is in its place): the
// commit stops after removing the old summary, so the directory holds no
// complete set, and says so.
void failureHalfWay(const IO::OutputDirectory& dir, const RCP<const Comm>& comm) {
  if (comm->getRank() == 0) {
    ::unlink((dir.path() + "/solution.xmf").c_str());
    ::mkdir((dir.path() + "/solution.xmf").c_str(), 0755);
    writePlainFile(dir.path() + "/solution.xmf/keep", "x");
  }
  comm->barrier();
  const std::string m = expectCollective<RunFailure>("old file cannot be removed", *comm, [&] { writeSet(dir, "v4", comm); });
  CHECK(contains(m, "solution.xmf"), "names the file: " << m);
  if (comm->getRank() == 0) {
    CHECK(!exists(dir.path() + "/summary.json"), "the old summary went first");
    CHECK(readFile(dir.path() + "/solution.h5") == "v2 solution.h5", "files after it untouched");
    CHECK(temporariesIn(dir.path()).empty(), "no temporaries after a failed commit");
    removeTree(dir.path() + "/solution.xmf");
  }
  comm->barrier();
  writeSet(dir, "v5", comm);
  checkSet(dir.path(), "v5", "after repair", *comm);
}

void names(const IO::OutputDirectory& dir, const RCP<const Comm>& comm) {
  IO::ResultSet files(dir, comm);
  expectCollective<CollectiveError>("name with a directory", *comm, [&] { files.add("sub/solution.h5"); });
  files.add("solution.h5");
  expectCollective<CollectiveError>("name added twice", *comm, [&] { files.add("solution.h5"); });
}

void atomicFiles(const std::string& base, const RCP<const Comm>& comm) {
  const std::string path = base + "/summary.json";
  if (comm->getRank() == 0) {
    IO::writeFileAtomically(path, "one");
    IO::writeFileAtomically(path, "two");
    CHECK(readFile(path) == "two", "replaced");
    bool thrown = false;
    try {
      IO::writeFileAtomically(base + "/missing/summary.json", "three");
    } catch (const RunFailure& e) {
      thrown = contains(e.what(), "No such file or directory");
    }
    CHECK(thrown, "a file that cannot be written: RunFailure with the cause");
  }
  IO::writeFileAtomically(path, "four", comm);
  if (comm->getRank() == 0) CHECK(readFile(path) == "four", "collective: replaced");
  expectCollective<RunFailure>("collective write to a missing directory", *comm, [&] {
    IO::writeFileAtomically(base + "/missing/summary.json", "five", comm);
  });
  if (comm->getRank() == 0) {
    const auto names = listDirectory(base);
    CHECK(std::count_if(names.begin(), names.end(), [](const std::string& n) { return contains(n, ".tmp"); }) == 0,
          "no temporary beside the file");
  }
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const std::string base = scratchDirectory(*comm, "result_set");
  {
    IO::OutputDirectory dir(base + "/out", comm);
    replaced(dir, comm);
    failureBeforeCommit(dir, comm);
    missingFile(dir, comm);
    failureHalfWay(dir, comm);
    names(dir, comm);
  }
  atomicFiles(base, comm);
  comm->barrier();
  if (comm->getRank() == 0) removeTree(base);
  return verdict(*comm, "io_test_result_set");
}
