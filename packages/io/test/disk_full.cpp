// A result that does not fit: under a file size limit (setrlimit after
// MPI_Init, SIGXFSZ ignored so that writes fail with EFBIG) and, where the
// machine lets us mount one, on a tmpfs too small for it (ENOSPC). Every rank
// must throw Tribos::RunFailure with the same one-line message, no temporary
// may remain, the previous result set must be intact, and nothing may hang.
// Each case writes to its own scratch directory. With --exit-status the
// program behaves like a driver instead: it prints the message once and
// exits with status 3 on every rank (disk_full_exit.sh checks that from
// outside: status, one message, no core, no hang).
#include <sys/mount.h>
#include <sys/resource.h>

#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultSet.hpp"
#include "Tribos_ProcessStartup.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

const std::vector<std::string> kSet = {"solution.h5", "solution.xmf", "summary.json"};

// The file size limit of this process, while in scope.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    rlimit lim = saved_;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &saved_); }

 private:
  rlimit saved_;
};

struct Outcome {
  bool committed = false, runFailure = false;
  std::string message;
};

// Writes a 12^3 Hex8 result (about 250 kB) as one ResultSet in dir.
Outcome writeResult(const IO::OutputDirectory& dir, const Mesh::Discretization& disc, bool reserve,
                    const RCP<const Comm>& comm) {
  Outcome out;
  IO::Field pressure{"pressure", 1, std::vector<double>(disc.ownedNodes().size(), 1.5)};
  IO::Field stress{"von_mises", 1, std::vector<double>(static_cast<size_t>(disc.part.numCells()), 2.5)};
  IO::PointSet contact{"contact", {}, {IO::Field{"gap", 1, {}}}};
  if (comm->getRank() == 0)
    for (int k = 0; k < 50; ++k) contact.coords.push_back({k * 0.01, 0, 0}), contact.fields[0].values.push_back(k);
  IO::ResultAttributes attributes{{{"stop_reason", "converged"}}, {{"converged", 1.0}}};
  try {
    IO::ResultSet files(dir, comm);
    const std::string h5 = files.add(kSet[0]), xmf = files.add(kSet[1]), summary = files.add(kSet[2]);
    IO::ResultWriter writer(disc, comm);
    writer.reserveSpace(reserve);
    writer.write(h5, kSet[0], xmf, displacementOf(disc), {pressure}, {stress}, {contact}, attributes);
    IO::writeTextFile(summary, "{\"converged\": true}\n", comm);
    files.commit();
    out.committed = true;
  } catch (const RunFailure& e) {
    out.runFailure = true, out.message = e.what();
  } catch (const std::exception& e) {
    out.message = std::string("not a RunFailure: ") + e.what();
  }
  return out;
}

void writeOldSet(const std::string& dir, const Comm& comm) {
  if (comm.getRank() == 0)
    for (const std::string& f : kSet) writePlainFile(dir + "/" + f, "old " + f);
  comm.barrier();
}

// Every rank failed with RunFailure, with rank 0's message, one line naming
// the file and a reason; no temporary left; the old set untouched.
void checkFailure(const Outcome& result, const std::string& dir, const RCP<const Comm>& comm, Teuchos::FancyOStream& out,
                  bool& success) {
  out << "message: " << (result.committed ? "committed" : result.message) << "\n";
  TEST_ASSERT(result.runFailure);
  const std::string rootMessage = broadcastFromRoot(*comm, result.message);
  TEST_EQUALITY(result.message, rootMessage);               // the same on every rank
  TEST_EQUALITY(result.message.find('\n'), std::string::npos);  // one line
  TEST_ASSERT(contains(result.message, "solution.h5"));       // names the file
  TEST_ASSERT(contains(result.message, "File too large") || contains(result.message, "No space left"));  // the reason
  if (comm->getRank() == 0) {
    const auto left = temporariesIn(dir);
    for (const std::string& f : left) out << "temporary left: " << f << "\n";
    TEST_ASSERT(left.empty());
    for (const std::string& f : kSet) TEST_EQUALITY(readFile(dir + "/" + f), "old " + f);  // the old set unchanged
  }
}

// From the first metadata block to most of the data.
// (Only with the space reserved: without, HDF5 1.10 cannot close a file
// whose metadata lies beyond the limit, and crashes in MPI_Finalize.)
void fileSizeLimitCase(rlim_t kib, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "disk_full");
  const auto disc = boxDiscretization(12, 12, 12, *comm);
  IO::OutputDirectory dir(scratch.path() + "/limit", comm);
  writeOldSet(dir.path(), *comm);
  Outcome result;
  {
    FileSizeLimit limit(kib * 1024);
    result = writeResult(dir, disc, true, comm);
  }
  checkFailure(result, dir.path(), comm, out, success);
}

// Mounts a tmpfs of `size` at path (rank 0); "" or why not.
std::string mountSmallDisk(const std::string& path, const std::string& size, const Comm& comm) {
  std::string error;
  if (comm.getRank() == 0) {
    ::mkdir(path.c_str(), 0755);
    if (::mount("tribos_test", path.c_str(), "tmpfs", 0, ("size=" + size).c_str()) != 0) error = std::strerror(errno);
  }
  return rootError(comm, error);
}

// Small tmpfs disks: 96k holds the old set, the lock and HDF5's metadata but
// not the data, 24k not even the metadata. Without the space reserved, the
// data writes fail (only at 96k: a failure of HDF5 1.10's metadata writes
// hangs or crashes inside HDF5, which the reservation exists to prevent).
// Skipped where mounting is not allowed.
void smallDiskCase(const std::string& size, bool reserve, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "disk_full");
  const auto disc = boxDiscretization(12, 12, 12, *comm);
  const std::string mountPoint = scratch.path() + "/tmpfs" + size;
  const std::string error = mountSmallDisk(mountPoint, size, *comm);
  if (!error.empty()) {
    out << "skipped, cannot mount a tmpfs (" << error << ")\n";
    return;
  }
  {
    IO::OutputDirectory dir(mountPoint + "/out", comm);
    writeOldSet(dir.path(), *comm);
    checkFailure(writeResult(dir, disc, reserve, comm), dir.path(), comm, out, success);
  }
  comm->barrier();
  if (comm->getRank() == 0) ::umount2(mountPoint.c_str(), MNT_DETACH);
}

// Like a driver: one message on rank 0, exit status 3 on every rank.
int exitStatusCase(const RCP<const Comm>& comm) {
  ScratchDirectory scratch(comm, "disk_full");
  const auto disc = boxDiscretization(12, 12, 12, *comm);
  IO::OutputDirectory dir(scratch.path() + "/exit", comm);
  Outcome result;
  {
    FileSizeLimit limit(16 * 1024);
    result = writeResult(dir, disc, true, comm);
  }
  if (result.committed) return 0;
  if (comm->getRank() == 0) std::cerr << "io_test_disk_full: error: " << result.message << std::endl;
  const bool clean = broadcastFromRoot(*comm, static_cast<long>(temporariesIn(dir.path()).empty())) != 0;
  if (!clean && comm->getRank() == 0) std::cout << "FAILED: temporaries left in " << dir.path() << std::endl;
  return result.runFailure && clean ? 3 : 1;
}

}  // namespace

TEUCHOS_UNIT_TEST(FileSizeLimit, Limit1KiB) { fileSizeLimitCase(1, out, success); }
TEUCHOS_UNIT_TEST(FileSizeLimit, Limit4KiB) { fileSizeLimitCase(4, out, success); }
TEUCHOS_UNIT_TEST(FileSizeLimit, Limit16KiB) { fileSizeLimitCase(16, out, success); }
TEUCHOS_UNIT_TEST(FileSizeLimit, Limit64KiB) { fileSizeLimitCase(64, out, success); }
TEUCHOS_UNIT_TEST(FileSizeLimit, Limit160KiB) { fileSizeLimitCase(160, out, success); }
TEUCHOS_UNIT_TEST(FileSizeLimit, Limit240KiB) { fileSizeLimitCase(240, out, success); }

// A limit the result fits under changes nothing.
TEUCHOS_UNIT_TEST(FileSizeLimit, ResultFitsUnderLimit) {
  const auto comm = Tpetra::getDefaultComm();
  ScratchDirectory scratch(comm, "disk_full");
  const auto disc = boxDiscretization(12, 12, 12, *comm);
  IO::OutputDirectory dir(scratch.path() + "/limit", comm);
  writeOldSet(dir.path(), *comm);
  Outcome result;
  {
    FileSizeLimit limit(64 << 20);
    result = writeResult(dir, disc, true, comm);
  }
  out << "message: " << result.message << "\n";
  TEST_ASSERT(result.committed);
  if (comm->getRank() == 0) TEST_EQUALITY(readFile(dir.path() + "/summary.json"), "{\"converged\": true}\n");
}

TEUCHOS_UNIT_TEST(SmallDisk, Tmpfs96kReserved) { smallDiskCase("96k", true, out, success); }
TEUCHOS_UNIT_TEST(SmallDisk, Tmpfs96kNotReserved) { smallDiskCase("96k", false, out, success); }
TEUCHOS_UNIT_TEST(SmallDisk, Tmpfs24kReserved) { smallDiskCase("24k", true, out, success); }

int main(int argc, char* argv[]) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  Tpetra::ScopeGuard tpetra(&argc, &argv);
  // Only a test program may do this, never the library: with SIGXFSZ ignored,
  // a write beyond the file size limit fails with EFBIG instead of killing us.
  std::signal(SIGXFSZ, SIG_IGN);
  const auto comm = Tpetra::getDefaultComm();
  comm->barrier();  // MPI's own shared-memory files exist before any limit
  if (argc > 1 && std::string(argv[1]) == "--exit-status") {
    const int status = exitStatusCase(comm);
    comm->barrier();
    return status;
  }
  // A check that fails on one rank fails the test on every rank.
  Teuchos::UnitTestRepository::setGloballyReduceTestResult(true);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
