// Reads every shipped FCLIB sample and checks dimensions and structural facts.
// No MPI_Init: the serial HDF5 calls of the MPI-flavoured library work without
// it (the default file-access property list uses the sec2 driver).
#include <Teuchos_UnitTestHarness.hpp>
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "Tribos_FCLIB.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos::FCLIB;
using fclib_test::Sample;

namespace {

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

bool frictionCoefficientsValid(const std::vector<double>& mu) {
  return std::all_of(mu.begin(), mu.end(), [](double x) { return x >= 0.0 && std::isfinite(x); });
}

void checkLocal(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::samplePath(s);
  const LocalProblem P = readLocal(path);
  TEST_EQUALITY(P.spacedim, 3);  // spacedim
  TEST_EQUALITY(P.numberOfContacts(), s.contacts);  // contacts
  TEST_EQUALITY(P.W.rows, 3 * s.contacts);
  TEST_EQUALITY(P.W.cols, 3 * s.contacts);
  TEST_EQUALITY(P.q.size(), 3u * s.contacts);
  TEST_ASSERT(frictionCoefficientsValid(P.mu));
  TEST_ASSERT(allFinite(P.W.val));
  TEST_ASSERT(allFinite(P.q));
  // W = H' M^{-1} H is symmetric positive semi-definite up to rounding.
  const double asym = asymmetry(P.W), scale = maxAbs(P.W);
  std::cout << std::setprecision(3) << s.name << ": local, " << P.numberOfContacts()
            << " contacts, W " << P.W.rows << " x " << P.W.cols << " nnz " << P.W.nnz()
            << ", max|W - W'| = " << asym << " (relative " << asym / scale << ")" << std::endl;
  TEST_COMPARE(asym, <=, 1e-8 * scale);  // W asymmetry
  // Diagonal of a PSD matrix is non-negative.
  for (int r = 0; r < P.W.rows; ++r)
    for (int k = P.W.rowptr[r]; k < P.W.rowptr[r + 1]; ++k)
      if (P.W.col[k] == r) TEST_COMPARE(P.W.val[k], >=, 0.0);  // W
  TEST_ASSERT(!P.V);
  TEST_ASSERT(!P.R);
  TEST_ASSERT(!P.s);
}

void checkGlobal(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::samplePath(s);
  const GlobalProblem P = readGlobal(path);
  TEST_EQUALITY(P.spacedim, 3);  // spacedim
  TEST_EQUALITY(P.numberOfContacts(), s.contacts);  // contacts
  // Orientation: H is ndof x 3nc (M v = H r + f, u = H' v + w).
  TEST_EQUALITY(P.H.rows, P.M.cols);
  TEST_EQUALITY(P.H.cols, 3 * s.contacts);  // H
  TEST_ASSERT(P.f.size() == static_cast<std::size_t>(P.M.rows));
  TEST_EQUALITY(P.w.size(), 3u * s.contacts);
  TEST_ASSERT(frictionCoefficientsValid(P.mu));
  TEST_ASSERT(allFinite(P.M.val));
  TEST_ASSERT(allFinite(P.H.val));
  TEST_ASSERT(allFinite(P.f));
  TEST_ASSERT(allFinite(P.w));
  const double asym = asymmetry(P.M), scale = maxAbs(P.M);
  std::cout << std::setprecision(3) << s.name << ": global, " << P.numberOfContacts()
            << " contacts, M " << P.M.rows << " x " << P.M.cols << " nnz " << P.M.nnz() << ", H "
            << P.H.rows << " x " << P.H.cols << " nnz " << P.H.nnz() << ", max|M - M'| = " << asym
            << " (relative " << asym / scale << ")" << std::endl;
  // The LMGC exports of M are symmetric only to about 1.5e-7 relative (their
  // values look rounded to single precision); Box_Stacks' diagonal M is exact.
  TEST_COMPARE(asym, <=, 1e-6 * scale);  // M asymmetry
  // Every contact is seen by some degree of freedom: no empty column of H.
  std::vector<int> columnCount(P.H.cols, 0);
  for (int c : P.H.col) ++columnCount[c];
  for (int c = 0; c < P.H.cols; ++c) TEST_COMPARE(columnCount[c], >, 0);  // H column
}

void checkSolutionAndGuesses(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::samplePath(s);
  const auto solution = readSolution(path);
  const auto guesses = readGuesses(path);
  std::cout << "  solution: " << (solution ? "yes" : "no") << ", guesses: " << guesses.size()
            << std::endl;
  if (solution) TEST_EQUALITY(solution->r.size(), 3u * s.contacts);
  for (const Solution& g : guesses) TEST_EQUALITY(g.r.size(), 3u * s.contacts);
}

void checkErrorMessages(Teuchos::FancyOStream& out, bool& success) {
  const std::string missing = fclib_test::sampleDir() + "/no_such_file.hdf5";
  try {
    readLocal(missing);
    TEST_ASSERT(false);  // reading a missing file did not throw
  } catch (const std::runtime_error& e) {
    TEST_INEQUALITY(std::string(e.what()).find(missing), std::string::npos);
  }
  // A global file read as local names the missing group.
  const std::string global = fclib_test::samplePath(fclib_test::samples()[2]);
  try {
    readLocal(global);
    TEST_ASSERT(false);  // reading a global file as local did not throw
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::cout << "expected error: " << what << std::endl;
    TEST_INEQUALITY(what.find("fclib_local"), std::string::npos);
    TEST_INEQUALITY(what.find(global), std::string::npos);
  }
}

void checkSample(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const ProblemKind kind = problemKind(fclib_test::samplePath(s));
  TEST_ASSERT(kind == s.kind);  // the sample's kind
  if (kind == ProblemKind::Local) checkLocal(s, out, success); else checkGlobal(s, out, success);
  checkSolutionAndGuesses(s, out, success);
  const Info info = readInfo(fclib_test::samplePath(s));
  out << "  title \"" << info.title << "\"\n";
}

}  // namespace

FCLIB_SAMPLE_CASES(Read, checkSample)

TEUCHOS_UNIT_TEST(Read, ErrorMessages) { checkErrorMessages(out, success); }
