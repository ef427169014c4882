// Validation of FCLIB problems in memory and of what a solve may promise:
// - validate() refuses each corruption of a valid local and global problem
//   (one per case, data-driven) with a message naming the dataset, and so do
//   solve() (before any work) and the writers (leaving no file behind);
// - zero contacts and W = 0 are solved exactly, without a friction solver;
// - 'converged' requires finite values and the result check (judgeResult);
// - a stored solution of the wrong size is refused by readSolution and
//   ignored with a note by readSolutionLeniently;
// - output path checks and atomic text writes.
// Corrupted files read through the driver: fclib_test_driver.py.
#include <Teuchos_UnitTestHarness.hpp>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>

#include "Tribos_FCLIB.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_FCLIB_Solve.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;
using namespace Tribos::FCLIB;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

RCP<const Comm> serialComm() { return Teuchos::rcp(new Teuchos::SerialComm<int>()); }

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// Runs f, which must throw std::runtime_error with 'fragment' in its message.
void expectError(const std::string& label, const std::function<void()>& f, const std::string& fragment, Teuchos::FancyOStream& out, bool& success) {
  try {
    f();
    TEST_ASSERT(false);  // no error, expected one naming the fragment
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    TEST_INEQUALITY(what.find(fragment), std::string::npos);  // the message names the fragment
  }
}

template <typename Problem>
struct Corruption {
  std::string label;
  std::function<void(Problem&)> apply;
  std::string fragment;  // expected in the message
};

std::vector<Corruption<LocalProblem>> localCorruptions() {
  return {
      {"negative mu", [](LocalProblem& P) { P.mu[3] = -0.3; }, "/fclib_local/vectors/mu[3] = -0.3 is negative"},
      {"nan mu", [](LocalProblem& P) { P.mu[0] = kNaN; }, "/fclib_local/vectors/mu[0] is not finite (nan)"},
      {"inf q", [](LocalProblem& P) { P.q[17] = kInf; }, "/fclib_local/vectors/q[17] is not finite (inf)"},
      {"nan q", [](LocalProblem& P) { P.q[5] = kNaN; }, "/fclib_local/vectors/q[5] is not finite (nan)"},
      {"nan in W", [](LocalProblem& P) { P.W.val[7] = kNaN; }, "/fclib_local/W has a non-finite entry (nan)"},
      {"short q", [](LocalProblem& P) { P.q.pop_back(); }, "/fclib_local/vectors/q has 143 entries, expected 144"},
      {"extra contact", [](LocalProblem& P) { P.mu.push_back(0.5); },
       "/fclib_local/W is 144 x 144, expected 147 x 147 = 3 x 49 contacts"},
      {"spacedim", [](LocalProblem& P) { P.spacedim = 4; }, "/fclib_local/spacedim = 4, expected 2 or 3"},
      {"column out of range", [](LocalProblem& P) { P.W.col[2] = 144; },
       "/fclib_local/W is not a valid compressed-row matrix: column index 144 outside [0, 144)"},
      {"decreasing pointers", [](LocalProblem& P) { std::swap(P.W.rowptr[1], P.W.rowptr[2]); },
       "/fclib_local/W is not a valid compressed-row matrix: row pointers decrease"},
      {"columns out of order", [](LocalProblem& P) { std::swap(P.W.col[0], P.W.col[1]); },
       "/fclib_local/W is not a valid compressed-row matrix: row 0 has column"},
      {"duplicate column", [](LocalProblem& P) { P.W.col[1] = P.W.col[0]; },
       "/fclib_local/W is not a valid compressed-row matrix: row 0 has column"},
      {"V without R and s", [](LocalProblem& P) { P.V = P.W; }, "/fclib_local/{V, R, vectors/s}: a mixed problem needs all three"},
  };
}

std::vector<Corruption<GlobalProblem>> globalCorruptions() {
  return {
      {"negative mu", [](GlobalProblem& P) { P.mu[8] = -1.0; }, "/fclib_global/vectors/mu[8] = -1 is negative"},
      {"nan f", [](GlobalProblem& P) { P.f[4] = kNaN; }, "/fclib_global/vectors/f[4] is not finite (nan)"},
      {"inf w", [](GlobalProblem& P) { P.w[2] = -kInf; }, "/fclib_global/vectors/w[2] is not finite (inf)"},
      {"inf in M", [](GlobalProblem& P) { P.M.val[0] = kInf; }, "/fclib_global/M has a non-finite entry (inf)"},
      {"nan in H", [](GlobalProblem& P) { P.H.val[1] = kNaN; }, "/fclib_global/H has a non-finite entry (nan)"},
      {"short f", [](GlobalProblem& P) { P.f.pop_back(); }, "/fclib_global/M is 162 x 162, expected 161 x 161"},
      {"extra contact", [](GlobalProblem& P) { P.mu.push_back(0.3); },
       "/fclib_global/H is 162 x 27, expected 162 x 30"},
      {"short w", [](GlobalProblem& P) { P.w.resize(26); }, "/fclib_global/vectors/w has 26 entries, expected 27"},
      {"b without G", [](GlobalProblem& P) { P.b = std::vector<double>{1.0}; }, "/fclib_global/{G, vectors/b}: G and b come together"},
  };
}

// Each corruption is refused by validate, by solve (before any work: the
// message is validate's) and by the writer, which leaves nothing behind.
template <typename Problem, typename Writer>
void checkCorruptions(const Problem& valid, const std::vector<Corruption<Problem>>& cases, Writer write, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::scratchPath("validate", "refused.hdf5");
  std::remove(path.c_str());
  for (const auto& c : cases) {
    Problem P = valid;
    c.apply(P);
    expectError(c.label + " (validate)", [&] { validate(P, "test"); }, "test: " + c.fragment, out, success);
    expectError(c.label + " (solve)", [&] { solve(P, SolveOptions(), serialComm()); }, "FCLIB solve: " + c.fragment, out, success);
    expectError(c.label + " (write)", [&] { write(path, P, Info{}, nullptr, {}, Storage::CompressedRows); },
                c.fragment, out, success);
    TEST_ASSERT(!exists(path));
    TEST_ASSERT(!exists(Tribos::temporaryPathFor(path)));  // a refused write left a file
  }
  std::cout << cases.size() << " corruptions refused" << std::endl;
}

// No contacts: r and u are empty, and a global problem still has v = M^-1 f.
void checkZeroContacts(const GlobalProblem& global, Teuchos::FancyOStream& out, bool& success) {
  LocalProblem L;
  L.W = fromTriplets(0, 0, {}, {}, {}, "empty W");
  const SolveReport lr = solve(L, SolveOptions(), serialComm());
  TEST_ASSERT(lr.converged);
  TEST_ASSERT(lr.r.empty());
  TEST_ASSERT(lr.u.empty());
  TEST_EQUALITY(lr.err.absolute, 0.0);  // zero contacts (local)
  GlobalProblem G = global;
  G.mu.clear();
  G.w.clear();
  G.H = fromTriplets(G.M.rows, 0, {}, {}, {}, "empty H");
  const SolveReport gr = solve(G, SolveOptions(), serialComm());
  std::vector<double> Mv;
  G.M.multiply(gr.v, Mv);
  double residual = 0, norm = 0;
  for (std::size_t i = 0; i < Mv.size(); ++i) residual += std::pow(Mv[i] - G.f[i], 2), norm += G.f[i] * G.f[i];
  const double rel = std::sqrt(residual / norm);
  std::cout << "zero contacts (global): ||M v - f|| / ||f|| = " << rel << std::endl;
  TEST_ASSERT(gr.converged);
  TEST_ASSERT(gr.r.empty());
  TEST_ASSERT(gr.u.empty());  // zero contacts (global)
  TEST_EQUALITY(gr.v.size(), G.f.size());
  TEST_COMPARE(rel, <, 1e-10);  // zero contacts (global): v = M^-1 f
}

// W = 0 with contacts: u = q whatever r. A separating q (q_N > 0, q_T = 0)
// is solved by r = 0; a penetrating one (q_N < 0) has no solution at all.
void checkZeroW(const LocalProblem& valid, Teuchos::FancyOStream& out, bool& success) {
  LocalProblem P = valid;
  std::fill(P.W.val.begin(), P.W.val.end(), 0.0);
  for (int k = 0; k < P.numberOfContacts(); ++k) P.q[3 * k] = 1.0, P.q[3 * k + 1] = P.q[3 * k + 2] = 0.0;
  const SolveReport ok = solve(P, SolveOptions(), serialComm());
  TEST_ASSERT(ok.converged);
  TEST_EQUALITY(ok.err.absolute, 0.0);  // W = 0, separating q
  P.q[0] = -1.0;
  const SolveReport bad = solve(P, SolveOptions(), serialComm());
  TEST_ASSERT(!bad.converged);
  TEST_INEQUALITY(bad.stopReason.find("natural-map error"), std::string::npos);  // W = 0, penetrating q must not converge
}

// judgeResult: converged only with the solver's test, finite values and
// every figure within the limit.
void checkJudgement(Teuchos::FancyOStream& out, bool& success) {
  SolveReport base;
  base.status.converged = true;
  base.r = {1.0, 0.0, 0.0};
  base.u = {0.0, 0.0, 0.0};
  base.limit = 1e-10;
  base.tolerance = 1e-12;
  SolveReport rep = base;
  judgeResult(rep);
  TEST_ASSERT(rep.converged);  // a clean report converges
  const std::vector<std::pair<std::string, std::function<void(SolveReport&)>>> spoilers = {
      {"the solver did not converge", [](SolveReport& r) { r.status.converged = false; }},
      {"non-finite", [](SolveReport& r) { r.u[1] = kNaN; }},
      {"non-finite", [](SolveReport& r) { r.v = {0.0, kInf}; }},
      {"natural-map error", [](SolveReport& r) { r.err.relativeToMax = 0.3; }},
      {"natural-map error", [](SolveReport& r) { r.err.relativeToMax = kNaN; }},
      {"friction law", [](SolveReport& r) { r.kktFriction = 0.3; }},
      {"non-penetration", [](SolveReport& r) { r.kktNormal = kNaN; }},
  };
  for (const auto& [fragment, spoil] : spoilers) {
    SolveReport r = base;
    spoil(r);
    judgeResult(r);
    TEST_ASSERT(!r.converged);
    TEST_INEQUALITY(r.stopReason.find(fragment), std::string::npos);  // not converged, the reason naming the fragment
  }
}

// A relative error against an infinite scale is nan, never 0.
void checkNonFiniteAccuracy(Teuchos::FancyOStream& out, bool& success) {
  const NaturalMapError e = naturalMapError({0, 0, 0}, {kInf, 0, 0}, {0.3}, {kInf, 0, 0});
  TEST_ASSERT(std::isnan(e.relativeToQ));
  TEST_ASSERT(std::isnan(e.relativeToMax));  // err with inf q
}

// A solve stopped early reports solver_converged false and converged false.
void checkNotConverged(const LocalProblem& P, Teuchos::FancyOStream& out, bool& success) {
  SolveOptions options;
  options.solverParams.sublist("Algorithm 2").set("Maximum Iterations", 1);
  const SolveReport rep = solve(P, options, serialComm());
  TEST_ASSERT(!rep.status.converged);
  TEST_ASSERT(!rep.converged);  // one Algorithm 2 iteration converged
  SolveOptions strict;
  strict.solverParams.set("Result Check Factor", 0.5);
  expectError("Result Check Factor < 1", [&] { solve(P, strict, serialComm()); }, "Result Check Factor", out, success);
}

void copyFile(const std::string& from, const std::string& to) {
  std::ifstream in(from, std::ios::binary);
  std::ofstream copy(to, std::ios::binary | std::ios::trunc);
  copy << in.rdbuf();
}

// A copy of a sample whose /solution/u has 10 entries instead of 144.
std::string fileWithShortStoredU(const std::string& sample) {
  const std::string path = fclib_test::scratchPath("validate", "short_u.hdf5");
  copyFile(sample, path);
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Ldelete(file, "/solution/u", H5P_DEFAULT);
  hsize_t n = 10;
  hid_t space = H5Screate_simple(1, &n, nullptr);
  hid_t set = H5Dcreate2(file, "/solution/u", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const std::vector<double> values(n, 1.0);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(set);
  H5Sclose(space);
  H5Fclose(file);
  return path;
}

void checkStoredSolutionOfWrongSize(const std::string& sample, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fileWithShortStoredU(sample);
  TEST_EQUALITY(readLocal(path).numberOfContacts(), 48);  // the problem itself reads
  expectError("strict readSolution", [&] { readSolution(path); },
              "/solution/u has 10 entries, expected 144", out, success);
  std::vector<std::string> notes;
  const auto s = readSolutionLeniently(path, notes);
  TEST_ASSERT(s.has_value());
  TEST_ASSERT(s->u.empty());
  TEST_EQUALITY(s->r.size(), 144u);  // lenient: u dropped, r kept
  TEST_EQUALITY(notes.size(), 1u);
  TEST_INEQUALITY(notes[0].find("/solution/u has 10 entries"), std::string::npos);
  TEST_INEQUALITY(notes[0].find("ignored"), std::string::npos);  // lenient: one note naming /solution/u
  std::remove(path.c_str());
}

}  // namespace

const std::string& localPath() {
  static const std::string path = fclib_test::samplePath(fclib_test::samples()[0]);  // local_problem_test, 48 contacts
  return path;
}

const std::string& globalPath() {
  static const std::string path = fclib_test::samplePath(fclib_test::samples()[3]);  // LMGC ...00046, 9 contacts, 162 dofs
  return path;
}

TEUCHOS_UNIT_TEST(Validate, LocalCorruptions) {
  checkCorruptions(readLocal(localPath()), localCorruptions(), writeLocal, out, success);
}
TEUCHOS_UNIT_TEST(Validate, GlobalCorruptions) {
  checkCorruptions(readGlobal(globalPath()), globalCorruptions(), writeGlobal, out, success);
}
TEUCHOS_UNIT_TEST(Validate, ZeroContacts) { checkZeroContacts(readGlobal(globalPath()), out, success); }
TEUCHOS_UNIT_TEST(Validate, ZeroW) { checkZeroW(readLocal(localPath()), out, success); }
TEUCHOS_UNIT_TEST(Validate, Judgement) { checkJudgement(out, success); }
TEUCHOS_UNIT_TEST(Validate, NonFiniteAccuracy) { checkNonFiniteAccuracy(out, success); }
TEUCHOS_UNIT_TEST(Validate, NotConverged) { checkNotConverged(readLocal(localPath()), out, success); }
TEUCHOS_UNIT_TEST(Validate, StoredSolutionOfWrongSize) { checkStoredSolutionOfWrongSize(localPath(), out, success); }

// Empty rows repeat a row boundary: a matrix whose columns ascend in every
// row is accepted whatever rows are empty (the ordering test counts each
// boundary once), and a step down inside a row after empty rows is refused.
TEUCHOS_UNIT_TEST(Validate, ColumnOrderWithEmptyRows) {
  LocalProblem P;
  P.mu = {0.3, 0.5};
  P.q = {-1, 0, 0, -1, 0, 0};
  P.W.rows = P.W.cols = 6;
  // rows 0 and 4 hold entries; rows 1-3 and 5 are empty; row 0 ends at
  // column 5 and row 4 starts at column 0 (a step down across the boundary).
  P.W.rowptr = {0, 2, 2, 2, 2, 4, 4};
  P.W.col = {3, 5, 0, 4};
  P.W.val = {1, 2, 3, 4};
  validate(P, "test");  // accepted
  P.W.col = {3, 5, 4, 0};  // row 4: column 0 after column 4
  expectError("step down inside row 4", [&] { validate(P, "test"); },
              "W is not a valid compressed-row matrix: row 4 has column 0 after column 4", out, success);
}
