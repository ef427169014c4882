// Write-then-read of every shipped sample must reproduce the data bit for bit,
// with matrices stored as compressed rows and as triplets. Also checks that a
// failed write leaves an existing file untouched.
#include <Teuchos_UnitTestHarness.hpp>
#include <cstdio>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

#include "Tribos_FCLIB.hpp"
#include "Tribos_FileSystem.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;
using namespace Tribos::FCLIB;
using fclib_test::Sample;

namespace {

bool sameOptionalMatrix(const std::optional<LocalCsr>& a, const std::optional<LocalCsr>& b) {
  return a.has_value() == b.has_value() && (!a || bitwiseEqual(*a, *b));
}

bool sameOptionalVector(const std::optional<std::vector<double>>& a,
                        const std::optional<std::vector<double>>& b) {
  return a.has_value() == b.has_value() && (!a || bitwiseEqual(*a, *b));
}

bool sameSolution(const Solution& a, const Solution& b) {
  return bitwiseEqual(a.v, b.v) && bitwiseEqual(a.u, b.u) && bitwiseEqual(a.r, b.r) &&
         bitwiseEqual(a.l, b.l);
}

bool sameInfo(const Info& a, const Info& b) {
  return a.title == b.title && a.description == b.description && a.math_info == b.math_info;
}

bool same(const LocalProblem& a, const LocalProblem& b) {
  return bitwiseEqual(a.W, b.W) && bitwiseEqual(a.q, b.q) && bitwiseEqual(a.mu, b.mu) &&
         a.spacedim == b.spacedim && sameOptionalMatrix(a.V, b.V) &&
         sameOptionalMatrix(a.R, b.R) && sameOptionalVector(a.s, b.s);
}

bool same(const GlobalProblem& a, const GlobalProblem& b) {
  return bitwiseEqual(a.M, b.M) && bitwiseEqual(a.H, b.H) && bitwiseEqual(a.f, b.f) &&
         bitwiseEqual(a.w, b.w) && bitwiseEqual(a.mu, b.mu) && a.spacedim == b.spacedim &&
         sameOptionalMatrix(a.G, b.G) && sameOptionalVector(a.b, b.b);
}

const char* storageName(Storage s) { return s == Storage::CompressedRows ? "csr" : "triplets"; }

template <typename Problem, typename Reader, typename Writer>
void roundTrip(const Sample& s, Storage storage, Reader read, Writer write, Teuchos::FancyOStream& out, bool& success) {
  const std::string in = fclib_test::samplePath(s);
  const std::string path = fclib_test::scratchPath("roundtrip", storageName(storage) + s.name);
  const Problem P = read(in);
  const Info info = readInfo(in);
  const std::optional<Solution> solution = readSolution(in);
  const std::vector<Solution> guesses = readGuesses(in);

  write(path, P, info, solution ? &*solution : nullptr, guesses, storage);

  TEST_ASSERT(problemKind(path) == s.kind);
  TEST_ASSERT(same(P, read(path)));  // problem differs after
  TEST_ASSERT(sameInfo(info, readInfo(path)));  // info
  const std::optional<Solution> solution2 = readSolution(path);
  TEST_ASSERT(solution.has_value() == solution2.has_value() && (!solution || sameSolution(*solution, *solution2)));  // solution
  const std::vector<Solution> guesses2 = readGuesses(path);
  TEST_EQUALITY(guesses.size(), guesses2.size());  // number of guesses
  for (std::size_t k = 0; k < std::min(guesses.size(), guesses2.size()); ++k)
    TEST_ASSERT(sameSolution(guesses[k], guesses2[k]));  // guess
  std::ifstream tmp(Tribos::temporaryPathFor(path));
  TEST_ASSERT(!tmp.good());  // temporary file left behind
  std::remove(path.c_str());
  std::cout << s.name << ": round trip (" << storageName(storage) << ") done" << std::endl;
}

void roundTripSample(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  for (Storage storage : {Storage::CompressedRows, Storage::Triplets}) {
    if (s.kind == ProblemKind::Local)
      roundTrip<LocalProblem>(s, storage, readLocal, writeLocal, out, success);
    else
      roundTrip<GlobalProblem>(s, storage, readGlobal, writeGlobal, out, success);
  }
}

// A write that fails (dimension error, or the temporary file cannot be
// created) must leave the file already at the target path intact.
void failedWriteKeepsOldFile(Teuchos::FancyOStream& out, bool& success) {
  const Sample s = fclib_test::samples()[0];
  const LocalProblem P = readLocal(fclib_test::samplePath(s));
  const std::string path = fclib_test::scratchPath("roundtrip", "failed_write.hdf5");
  writeLocal(path, P, Info{"good", "", ""});

  LocalProblem bad = P;
  bad.q.pop_back();
  try {
    writeLocal(path, bad, Info{"bad", "", ""});
    TEST_ASSERT(false);  // writing a q of the wrong size did not throw
  } catch (const std::runtime_error& e) {
    std::cout << "expected error: " << e.what() << std::endl;
    TEST_INEQUALITY(std::string(e.what()).find("q"), std::string::npos);
  }
  TEST_EQUALITY(readInfo(path).title, "good");  // old file damaged by a rejected write

  // Block the temporary file with a directory so that HDF5 cannot create it.
  const std::string tmp = Tribos::temporaryPathFor(path);
  ::mkdir(tmp.c_str(), 0700);
  try {
    writeLocal(path, P, Info{"replaced", "", ""});
    TEST_ASSERT(false);  // writing over a blocked temporary did not throw
  } catch (const std::runtime_error& e) {
    std::cout << "expected error: " << e.what() << std::endl;
  }
  ::rmdir(tmp.c_str());
  TEST_EQUALITY(readInfo(path).title, "good");  // old file damaged by a failed write
  TEST_ASSERT(same(P, readLocal(path)));  // old file content changed
  std::remove(path.c_str());
}

}  // namespace


FCLIB_SAMPLE_CASES(RoundTrip, roundTripSample)

TEUCHOS_UNIT_TEST(RoundTrip, FailedWriteKeepsOldFile) { failedWriteKeepsOldFile(out, success); }
