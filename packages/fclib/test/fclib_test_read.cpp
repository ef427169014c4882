// Reads every shipped FCLIB sample and checks dimensions and structural facts.
// No MPI_Init: the serial HDF5 calls of the MPI-flavoured library work without
// it (the default file-access property list uses the sec2 driver).
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

void checkLocal(const Sample& s) {
  const std::string path = fclib_test::samplePath(s);
  const LocalProblem P = readLocal(path);
  FCLIB_CHECK(P.spacedim == 3, s.name << " spacedim " << P.spacedim);
  FCLIB_CHECK(P.numberOfContacts() == s.contacts, s.name << " contacts " << P.numberOfContacts());
  FCLIB_CHECK(P.W.m == 3 * s.contacts && P.W.n == 3 * s.contacts, s.name);
  FCLIB_CHECK(P.q.size() == 3u * s.contacts, s.name);
  FCLIB_CHECK(frictionCoefficientsValid(P.mu), s.name);
  FCLIB_CHECK(allFinite(P.W.val) && allFinite(P.q), s.name);
  // W = H' M^{-1} H is symmetric positive semi-definite up to rounding.
  const double asym = P.W.asymmetry(), scale = P.W.maxAbs();
  std::cout << std::setprecision(3) << s.name << ": local, " << P.numberOfContacts()
            << " contacts, W " << P.W.m << " x " << P.W.n << " nnz " << P.W.nnz()
            << ", max|W - W'| = " << asym << " (relative " << asym / scale << ")" << std::endl;
  FCLIB_CHECK(asym <= 1e-8 * scale, s.name << " W asymmetry " << asym);
  // Diagonal of a PSD matrix is non-negative.
  for (int r = 0; r < P.W.m; ++r)
    for (int k = P.W.rowptr[r]; k < P.W.rowptr[r + 1]; ++k)
      if (P.W.col[k] == r) FCLIB_CHECK(P.W.val[k] >= 0.0, s.name << " W(" << r << "," << r << ")");
  FCLIB_CHECK(!P.V && !P.R && !P.s, s.name);
}

void checkGlobal(const Sample& s) {
  const std::string path = fclib_test::samplePath(s);
  const GlobalProblem P = readGlobal(path);
  FCLIB_CHECK(P.spacedim == 3, s.name << " spacedim " << P.spacedim);
  FCLIB_CHECK(P.numberOfContacts() == s.contacts, s.name << " contacts " << P.numberOfContacts());
  // Orientation: H is ndof x 3nc (M v = H r + f, u = H' v + w).
  FCLIB_CHECK(P.H.m == P.M.n && P.H.n == 3 * s.contacts,
              s.name << " H " << P.H.m << " x " << P.H.n << ", M " << P.M.m);
  FCLIB_CHECK(P.f.size() == static_cast<std::size_t>(P.M.m), s.name);
  FCLIB_CHECK(P.w.size() == 3u * s.contacts, s.name);
  FCLIB_CHECK(frictionCoefficientsValid(P.mu), s.name);
  FCLIB_CHECK(allFinite(P.M.val) && allFinite(P.H.val) && allFinite(P.f) && allFinite(P.w),
              s.name);
  const double asym = P.M.asymmetry(), scale = P.M.maxAbs();
  std::cout << std::setprecision(3) << s.name << ": global, " << P.numberOfContacts()
            << " contacts, M " << P.M.m << " x " << P.M.n << " nnz " << P.M.nnz() << ", H "
            << P.H.m << " x " << P.H.n << " nnz " << P.H.nnz() << ", max|M - M'| = " << asym
            << " (relative " << asym / scale << ")" << std::endl;
  // The LMGC exports of M are symmetric only to about 1.5e-7 relative (their
  // values look rounded to single precision); Box_Stacks' diagonal M is exact.
  FCLIB_CHECK(asym <= 1e-6 * scale, s.name << " M asymmetry " << asym);
  // Every contact is seen by some degree of freedom: no empty column of H.
  std::vector<int> columnCount(P.H.n, 0);
  for (int c : P.H.col) ++columnCount[c];
  for (int c = 0; c < P.H.n; ++c) FCLIB_CHECK(columnCount[c] > 0, s.name << " H column " << c);
}

void checkSolutionAndGuesses(const Sample& s) {
  const std::string path = fclib_test::samplePath(s);
  const auto solution = readSolution(path);
  const auto guesses = readGuesses(path);
  std::cout << "  solution: " << (solution ? "yes" : "no") << ", guesses: " << guesses.size()
            << std::endl;
  if (solution) FCLIB_CHECK(solution->r.size() == 3u * s.contacts, s.name);
  for (const Solution& g : guesses) FCLIB_CHECK(g.r.size() == 3u * s.contacts, s.name);
}

void checkErrorMessages() {
  const std::string missing = fclib_test::sampleDir() + "/no_such_file.hdf5";
  try {
    readLocal(missing);
    FCLIB_CHECK(false, "reading a missing file did not throw");
  } catch (const std::runtime_error& e) {
    FCLIB_CHECK(std::string(e.what()).find(missing) != std::string::npos, e.what());
  }
  // A global file read as local names the missing group.
  const std::string global = fclib_test::samplePath(fclib_test::samples()[2]);
  try {
    readLocal(global);
    FCLIB_CHECK(false, "reading a global file as local did not throw");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::cout << "expected error: " << what << std::endl;
    FCLIB_CHECK(what.find("fclib_local") != std::string::npos && what.find(global) != std::string::npos,
                what);
  }
}

}  // namespace

int main() {
  for (const Sample& s : fclib_test::samples()) {
    try {
      const ProblemKind kind = problemKind(fclib_test::samplePath(s));
      FCLIB_CHECK(kind == s.kind, s.name << " kind");
      if (kind == ProblemKind::Local) checkLocal(s); else checkGlobal(s);
      checkSolutionAndGuesses(s);
      const Info info = readInfo(fclib_test::samplePath(s));
      std::cout << "  title \"" << info.title << "\"" << std::endl;
    } catch (const std::exception& e) {
      FCLIB_CHECK(false, s.name << ": " << e.what());
    }
  }
  checkErrorMessages();
  return fclib_test::finish("fclib_test_read");
}
