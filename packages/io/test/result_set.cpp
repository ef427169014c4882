// ResultSet: a new set replaces the old one; a run that fails before commit
// leaves the old set and no temporary; a commit that finds a file missing
// changes nothing; a commit that fails half way has removed the old summary
// first, so no directory ever shows a complete-looking mixed set. And
// writeFileAtomically: replaced or untouched, never a temporary left.
#include <sys/stat.h>

#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
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

void checkSet(const std::string& dir, const std::string& tag, const Comm& comm, Teuchos::FancyOStream& out,
              bool& success) {
  if (comm.getRank() != 0) return;
  for (const std::string& f : kSet) TEST_EQUALITY(readFile(dir + "/" + f), tag + " " + f);
  TEST_ASSERT(temporariesIn(dir).empty());
}

// f throws E on every rank with the same message; what() of rank 0.
template <class E, class F>
std::string expectCollective(const std::string& label, const Comm& comm, Teuchos::FancyOStream& out, bool& success,
                             F&& f) {
  std::string message;
  bool thrown = false;
  try {
    f();
  } catch (const E& e) {
    thrown = true, message = e.what();
  }
  out << label << ": " << message << "\n";
  TEST_ASSERT(thrown);
  TEST_EQUALITY(message, broadcastFromRoot(comm, message));  // the same message on every rank
  return message;
}

// A directory holding the committed set v2, as the cases below start from.
struct WithSet {
  WithSet(const RCP<const Comm>& comm, const std::string& tag) : scratch(comm, tag), dir(scratch.path() + "/out", comm) {
    writeSet(dir, "v1", comm);
    writeSet(dir, "v2", comm);
  }
  ScratchDirectory scratch;
  IO::OutputDirectory dir;
};

}  // namespace

TEUCHOS_UNIT_TEST(ResultSet, NewSetReplacesOld) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "result_set");
  IO::OutputDirectory dir(scratch.path() + "/out", comm);
  writeSet(dir, "v1", comm);
  checkSet(dir.path(), "v1", *comm, out, success);
  writeSet(dir, "v2", comm);
  checkSet(dir.path(), "v2", *comm, out, success);
  if (comm->getRank() == 0) TEST_ASSERT(exists(dir.path() + "/.tribos.lock"));  // the lock stays
}

// An exception between writing and commit (a solver failure, a write error).
TEUCHOS_UNIT_TEST(ResultSet, FailureBeforeCommitKeepsOldSet) {
  const auto comm = Tpetra::getDefaultComm();
  WithSet set(comm, "result_set");
  const IO::OutputDirectory& dir = set.dir;
  bool caught = false;
  try {
    IO::ResultSet files(dir, comm);
    IO::writeTextFile(files.add("solution.h5"), "v3 solution.h5", comm);
    IO::writeTextFile(files.add("solution.xmf"), "v3 solution.xmf", comm);
    files.add("summary.json");
    if (comm->getRank() == 0) TEST_EQUALITY(temporariesIn(dir.path()).size(), size_t(2));  // two temporaries written
    throw std::runtime_error("the run failed");
  } catch (const std::runtime_error&) {
    caught = true;
  }
  TEST_ASSERT(caught);  // the exception passed through
  checkSet(dir.path(), "v2", *comm, out, success);
}

TEUCHOS_UNIT_TEST(ResultSet, MissingFileChangesNothing) {
  const auto comm = Tpetra::getDefaultComm();
  WithSet set(comm, "result_set");
  const IO::OutputDirectory& dir = set.dir;
  const std::string m = expectCollective<RunFailure>("summary never written", *comm, out, success, [&] {
    IO::ResultSet files(dir, comm);
    IO::writeTextFile(files.add("solution.h5"), "v3 solution.h5", comm);
    IO::writeTextFile(files.add("solution.xmf"), "v3 solution.xmf", comm);
    files.add("summary.json");
    files.commit();
  });
  TEST_ASSERT(contains(m, "summary.json was not written"));
  checkSet(dir.path(), "v2", *comm, out, success);
}

// The old solution.xmf cannot be removed (a directory is in its place): the
// commit stops after removing the old summary, so the directory holds no
// complete set, and says so.
TEUCHOS_UNIT_TEST(ResultSet, FailureHalfWayRemovesOldSummaryFirst) {
  const auto comm = Tpetra::getDefaultComm();
  WithSet set(comm, "result_set");
  const IO::OutputDirectory& dir = set.dir;
  if (comm->getRank() == 0) {
    ::unlink((dir.path() + "/solution.xmf").c_str());
    ::mkdir((dir.path() + "/solution.xmf").c_str(), 0755);
    writePlainFile(dir.path() + "/solution.xmf/keep", "x");
  }
  comm->barrier();
  const std::string m = expectCollective<RunFailure>("old file cannot be removed", *comm, out, success,
                                                     [&] { writeSet(dir, "v4", comm); });
  TEST_ASSERT(contains(m, "solution.xmf"));
  if (comm->getRank() == 0) {
    TEST_ASSERT(!exists(dir.path() + "/summary.json"));                        // the old summary went first
    TEST_EQUALITY(readFile(dir.path() + "/solution.h5"), "v2 solution.h5");  // files after it untouched
    TEST_ASSERT(temporariesIn(dir.path()).empty());
    removeTree(dir.path() + "/solution.xmf");
  }
  comm->barrier();
  writeSet(dir, "v5", comm);  // after repair
  checkSet(dir.path(), "v5", *comm, out, success);
}

TEUCHOS_UNIT_TEST(ResultSet, BadNamesRefused) {
  const auto comm = Tpetra::getDefaultComm();
  WithSet set(comm, "result_set");
  IO::ResultSet files(set.dir, comm);
  expectCollective<CollectiveError>("name with a directory", *comm, out, success, [&] { files.add("sub/solution.h5"); });
  files.add("solution.h5");
  expectCollective<CollectiveError>("name added twice", *comm, out, success, [&] { files.add("solution.h5"); });
}

TEUCHOS_UNIT_TEST(WriteFileAtomically, OneRank) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "result_set");
  const std::string base = scratch.path(), path = base + "/summary.json";
  if (comm->getRank() != 0) return;
  IO::writeFileAtomically(path, "one");
  IO::writeFileAtomically(path, "two");
  TEST_EQUALITY(readFile(path), "two");  // replaced
  bool thrown = false;
  try {
    IO::writeFileAtomically(base + "/missing/summary.json", "three");
  } catch (const RunFailure& e) {
    out << e.what() << "\n";
    thrown = contains(e.what(), "No such file or directory");
  }
  TEST_ASSERT(thrown);  // a file that cannot be written: RunFailure with the cause
}

TEUCHOS_UNIT_TEST(WriteFileAtomically, Collective) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "result_set");
  const std::string base = scratch.path(), path = base + "/summary.json";
  if (comm->getRank() == 0) IO::writeFileAtomically(path, "three");
  comm->barrier();
  IO::writeFileAtomically(path, "four", comm);
  if (comm->getRank() == 0) TEST_EQUALITY(readFile(path), "four");  // replaced
  expectCollective<RunFailure>("collective write to a missing directory", *comm, out, success, [&] {
    IO::writeFileAtomically(base + "/missing/summary.json", "five", comm);
  });
  if (comm->getRank() == 0) {
    const auto names = listDirectory(base);
    // no temporary beside the file
    TEST_EQUALITY(std::count_if(names.begin(), names.end(), [](const std::string& n) { return contains(n, ".tmp"); }), 0);
  }
}
