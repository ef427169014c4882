// tribos_fclib: read an FCLIB problem, solve it with a Tribos friction
// algorithm, compare with the stored solution when there is one, and report.
//   tribos_fclib FILE.hdf5 [--xml solver.xml] [--algorithm NAME] [--tolerance TOL]
//                [--max-iterations N] [--summary FILE.json]
//                [--mass-solver Auto|KLU2|CHOLMOD|Tacho] [--write-solution OUT.hdf5] [--verbose] [--quiet]
// Exit status: 0 converged; 1 bad input or error (usage, unreadable or invalid
// problem, unusable output path: nothing solved, nothing written); 2 not
// converged (the result check failed, e.g. ||F_nat||/||q|| above --tolerance;
// the summary and the solution file are still written, and stop_reason says why);
// 3 run failure: what was printed on stdout (the summary) could not be written.
// Every exit other than 0 says why in one line on stderr.
// The solve runs on rank 0 with a communicator of one rank (Amesos2 is not
// usable on multi-rank communicators in this Trilinos build); other ranks wait.
// A run longer than 2 s shows its stage and iterations on stderr (--quiet: not).
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <optional>
#include <string>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_FCLIB.hpp"
#include "Tribos_FCLIB_Accuracy.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_FCLIB_Solve.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_ParameterReader.hpp"
#include "Tribos_Summary.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_ProcessStartup.hpp"

namespace {

using namespace Tribos;

// The algorithms come from the friction registry: every one that solves
// Coulomb friction (the law of FCLIB problems).
std::string usage() {
  const std::string names = joinNames(FCLIB::coulombAlgorithms());
  return "usage: tribos_fclib FILE.hdf5 [--xml solver.xml] [--algorithm NAME] [--tolerance TOL] [--max-iterations N]\n"
         "                   [--summary FILE.json] [--mass-solver Auto|KLU2|CHOLMOD|Tacho] [--write-solution OUT.hdf5] [--verbose]\n"
         "                   [--quiet]\n"
         "--quiet              no progress lines on stderr (shown for runs longer than 2 s: stage, iterations)\n"
         "--algorithm NAME     a friction algorithm that solves Coulomb problems: " + names + "\n"
         "                     (default Algorithm2)\n"
         "--tolerance TOL      1e-15 <= TOL < 1: the result must reach ||F_nat|| / ||q|| <= TOL (the natural-map error\n"
         "                     relative to q; Siconos divides it by max(||q||, ||r||, ||u||)); the algorithm\n"
         "                     is asked for TOL and, when its own stopping test is met first, again from its\n"
         "                     result with a tighter tolerance.\n"
         "                     Without it the algorithm's tolerances (defaults or solver.xml) decide.\n"
         "--max-iterations N   N >= 1: the limit on the algorithm's outer iterations (MSA steps, Algorithm 2\n"
         "                     loops, Newton steps)\n"
         "solver.xml: a ParameterList holding the friction solver list (sublists \"Algorithm 1\", \"MSA\",\n"
         "\"Algorithm 2\", ...), either at its root or in a sublist \"Solver\"; \"Outer Algorithm\" there picks the\n"
         "algorithm (--algorithm wins); --tolerance and --max-iterations override its values.\n"
         "converged: true means the result solves the FCLIB problem: every value finite, natural-map error and\n"
         "KKT residuals within Result Check Factor (default 100) times the requested tolerance, and with\n"
         "--tolerance ||F_nat|| / ||q|| <= TOL.\n"
         "exit status: 0 converged; 1 bad input or error (nothing written); 2 not converged (the result check\n"
         "failed; results written, stop_reason says why); 3 run failure: stdout could not be written.\n";
}

enum ExitStatus { kConverged = 0, kError = 1, kNotConverged = 2, kRunFailure = 3 };

// `text` printed on stdout and flushed: "" when it and all printed there
// before was written, else why not (a full disk, a file-size limit): output
// lost is never exit 0.
std::string printOnStdout(const std::string& text) {
  errno = 0;  // the failing write's reason, whichever call makes it
  std::cout << text << std::flush;
  if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return "";
  return errno != 0 ? std::strerror(errno) : "a write error";
}

struct Args {
  std::string input, xml, summary, algorithm, massSolver = FCLIB::kAutoMassSolver, writeSolution;
  double tolerance = 0;     // 0: not given
  int maxIterations = 0;    // 0: not given
  bool verbose = false, quiet = false;
};

// The whole text must be a finite number (no trailing characters, no nan/inf).
double parseDouble(const std::string& flag, const std::string& text) {
  double value = 0;
  std::string why;
  TRIBOS_REQUIRE(IO::parseDouble(text, value, why), flag << ": \"" << text << "\" is not a finite number");
  return value;
}

int parseInt(const std::string& flag, const std::string& text) {
  int value = 0;
  std::string why;
  TRIBOS_REQUIRE(IO::parseInt(text, value, why),
                 flag << ": \"" << text << "\" is not an integer" << (why == "not an integer" ? "" : " of int's range"));
  TRIBOS_REQUIRE(value >= 1 && value <= 100000000, flag << ": " << value << " is out of range, expected 1 .. 100000000");
  return value;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    // A value that looks like an option is a forgotten value ("--summary
    // --verbose" would write a file named --verbose); write ./-x for such a name.
    auto next = [&](const char* flag) {
      TRIBOS_REQUIRE(i + 1 < argc && argv[i + 1][0] != '-',
                     flag << " needs a value" << (i + 1 < argc ? std::string(", got the option ") + argv[i + 1] : "")
                          << "\n" << usage());
      return std::string(argv[++i]);
    };
    if (s == "--xml") a.xml = next("--xml");
    else if (s == "--summary") a.summary = next("--summary");
    else if (s == "--algorithm") a.algorithm = next("--algorithm");
    else if (s == "--tolerance") {
      a.tolerance = parseDouble("--tolerance", next("--tolerance"));
      TRIBOS_REQUIRE(a.tolerance > 0 && a.tolerance < 1,
                     "--tolerance: " << a.tolerance << " is out of range, expected 0 < TOL < 1");
      // Below it the round-off of the solve is larger than the error asked
      // for: the tightened rounds end with a search direction whose
      // curvature is lost in round-off, not with an answer.
      TRIBOS_REQUIRE(a.tolerance >= Friction::kTightestTolerance,
                     "--tolerance: " << a.tolerance << " is below " << Friction::kTightestTolerance
                                     << ", the smallest natural-map error relative to ||q|| that a solve in double "
                                        "precision can be asked for");
    } else if (s == "--max-iterations") a.maxIterations = parseInt("--max-iterations", next("--max-iterations"));
    else if (s == "--mass-solver") a.massSolver = next("--mass-solver");
    else if (s == "--write-solution") a.writeSolution = next("--write-solution");
    else if (s == "--verbose") a.verbose = true;
    else if (s == "--quiet") a.quiet = true;
    else if (!s.empty() && s[0] == '-') throw Error("unknown option " + s + "\n" + usage());
    else {
      TRIBOS_REQUIRE(a.input.empty(), "more than one input file given\n" << usage());
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(!a.input.empty(), "no input file given\n" << usage());
  // Checked here: a local problem never factors M, so a typo would pass unseen.
  TRIBOS_REQUIRE(a.massSolver == FCLIB::kAutoMassSolver || a.massSolver == "KLU2" || a.massSolver == "CHOLMOD" ||
                     a.massSolver == "Tacho",
                 "--mass-solver: unknown \"" << a.massSolver << "\"; valid: Auto, KLU2, CHOLMOD, Tacho");
  if (!a.algorithm.empty()) {
    const auto valid = FCLIB::coulombAlgorithms();
    TRIBOS_REQUIRE(std::find(valid.begin(), valid.end(), a.algorithm) != valid.end(),
                   "--algorithm: unknown \"" << a.algorithm << "\"; valid (Coulomb friction): " << joinNames(valid));
  }
  return a;
}

// Output paths are checked before anything is read or solved, so that a
// mistyped directory fails at once, not after a long solve; and no output
// may replace the input or the other output.
void checkOutputs(const Args& a, const RCP<const Comm>& comm) {
  const std::vector<std::pair<std::string, std::string>> outputs = {{"--summary", a.summary},
                                                                    {"--write-solution", a.writeSolution}};
  for (const auto& [flag, path] : outputs) {
    if (path.empty()) continue;
    IO::requireWritableFile(path, flag, comm);
    TRIBOS_REQUIRE(!sameFile(path, a.input), flag << ": " << path << " is the input file");
  }
  TRIBOS_REQUIRE(a.summary.empty() || a.writeSolution.empty() || !sameFile(a.summary, a.writeSolution),
                 "--summary and --write-solution name the same file " << a.summary);
}

FCLIB::SolveOptions solveOptions(const Args& args) {
  FCLIB::SolveOptions options;
  options.massSolver = args.massSolver;
  options.verbose = args.verbose;
  options.source = "FCLIB file " + args.input;
  if (!args.xml.empty()) {
    auto pl = IO::readParameterFile(args.xml);  // every value parsed completely, finite
    const Teuchos::ParameterList& solver = pl->isSublist("Solver") ? pl->sublist("Solver") : *pl;
    options.solverParams = solver;
    if (solver.isParameter("Outer Algorithm")) options.algorithm = solver.get<std::string>("Outer Algorithm");
  }
  if (!args.algorithm.empty()) options.algorithm = args.algorithm;
  options.naturalMapTolerance = args.tolerance;
  options.maxIterations = args.maxIterations;
  return options;
}

// ||a - b|| / max(||a||, ||b||): 0 for two zero vectors, never a division by ~0.
double relDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, na = 0, nb = 0;
  for (size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]) * (a[i] - b[i]), na += a[i] * a[i], nb += b[i] * b[i];
  const double scale = std::sqrt(std::max(na, nb));
  return scale > 0 ? std::sqrt(d) / scale : 0.0;
}

IO::Summary errSummary(const FCLIB::NaturalMapError& e) {
  IO::Summary s;
  s.set("absolute", e.absolute).set("relative_to_q", e.relativeToQ).set("relative_to_max", e.relativeToMax);
  s.set("norm_q", e.normQ).set("norm_r", e.normR).set("norm_u", e.normU);
  return s;
}

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// What a run produced, whatever the kind of problem.
struct Outcome {
  IO::Summary summary;                  // input, title, kind and sizes, then the solve
  std::optional<IO::Summary> stored;    // the comparison with the stored solution
  bool converged = false;
  std::string stopReason;
  std::vector<std::string> notes;
};

// The stored solution is reference data: compared with ours when it has the
// right sizes, otherwise ignored with a note (readSolutionLeniently).
template <typename ErrOf>
void compareStored(const std::optional<FCLIB::Solution>& stored, const FCLIB::SolveReport& rep, ErrOf errOf,
                   Outcome& out) {
  if (!stored) return;
  Progress::stage("comparison with the stored solution");
  IO::Summary& s = out.stored.emplace();
  if (!stored->r.empty()) {
    s.set("err", errSummary(errOf(stored->r)));
    s.set("rel_diff_r", relDiff(rep.r, stored->r));
  }
  if (!stored->v.empty() && stored->v.size() == rep.v.size()) s.set("rel_diff_v", relDiff(rep.v, stored->v));
}

// --write-solution: the result is written converged or not (exit 2 still
// reports it), but not with non-finite entries, which no FCLIB reader accepts.
template <typename Problem, typename Writer>
void writeResult(const Args& args, const Problem& p, const FCLIB::Info& info, const FCLIB::Solution& s,
                 Writer write, Outcome& out) {
  if (args.writeSolution.empty()) return;
  if (!allFinite(s.r) || !allFinite(s.u) || !allFinite(s.v)) {
    out.notes.push_back("--write-solution " + args.writeSolution + " not written: the result has non-finite entries");
    return;
  }
  Progress::stage("writing " + args.writeSolution);
  write(args.writeSolution, p, info, &s, {}, FCLIB::Storage::CompressedRows);
}

void solveLocal(const Args& args, const FCLIB::SolveOptions& options, const RCP<const Comm>& self,
                const FCLIB::Info& info, FCLIB::SolveReport& rep, Outcome& out) {
  const auto p = FCLIB::readLocal(args.input);
  const auto stored = FCLIB::readSolutionLeniently(args.input, out.notes);
  out.summary.set("kind", "local").set("contacts", p.numberOfContacts());
  rep = FCLIB::solve(p, options, self);
  compareStored(stored, rep, [&](const std::vector<double>& r) { return FCLIB::naturalMapError(p, r); }, out);
  writeResult(args, p, info, FCLIB::Solution{{}, rep.u, rep.r, {}}, FCLIB::writeLocal, out);
}

void solveGlobal(const Args& args, const FCLIB::SolveOptions& options, const RCP<const Comm>& self,
                 const FCLIB::Info& info, FCLIB::SolveReport& rep, Outcome& out) {
  const auto p = FCLIB::readGlobal(args.input);
  const auto stored = FCLIB::readSolutionLeniently(args.input, out.notes);
  out.summary.set("kind", "global").set("contacts", p.numberOfContacts()).set("dofs", p.M.rows);
  rep = FCLIB::solve(p, options, self);
  compareStored(
      stored, rep,
      [&](const std::vector<double>& r) { return FCLIB::naturalMapError(p, r, rep.mass->function()); },
      out);
  writeResult(args, p, info, FCLIB::Solution{rep.v, rep.u, rep.r, {}}, FCLIB::writeGlobal, out);
}

// Info is descriptive only: an unreadable one is noted, not fatal.
FCLIB::Info readInfo(const std::string& path, std::vector<std::string>& notes) {
  try {
    return FCLIB::readInfo(path);
  } catch (const std::exception& e) {
    notes.push_back(std::string(e.what()) + "; the info strings are ignored");
    return {};
  }
}

void reportSolve(const Args& args, const FCLIB::SolveReport& rep, FCLIB::ProblemKind kind, IO::Summary& summary) {
  summary.set("algorithm", rep.algorithm);
  summary.set("converged", rep.converged).set("solver_converged", rep.status.converged);
  summary.set("stop_reason", rep.stopReason);
  summary.set("outer_iterations", rep.status.outer_iterations).set("msa_iterations", rep.status.msa_iterations);
  summary.set("inner_iterations", rep.status.inner_iterations);
  summary.set("n_A", rep.n_A).set("n_A_qpp", static_cast<long long>(rep.status.n_A_qpp));
  summary.set("n_A_qpq", static_cast<long long>(rep.status.n_A_qpq));
  if (kind == FCLIB::ProblemKind::Global) summary.set("mass_solves", rep.massSolves).set("mass_solver", rep.mass->name());
  summary.set("time_setup_s", rep.timeSetup).set("time_solve_s", rep.timeSolve);
  summary.set("err", errSummary(rep.err));
  IO::Summary kkt;
  kkt.set("nonpenetration", rep.kktNormal).set("complementarity", rep.kktComplementarity);
  kkt.set("friction_law", rep.kktFriction).set("tolerance", rep.tolerance).set("limit", rep.limit);
  summary.set("kkt", kkt);
  if (rep.naturalMapTolerance > 0) {
    IO::Summary t;
    t.set("tolerance", rep.naturalMapTolerance).set("rounds", rep.rounds);
    std::ostringstream errs;  // ||F_nat||/||q|| after each solve
    errs << std::scientific << std::setprecision(3);
    for (size_t k = 0; k < rep.roundErrors.size(); ++k) errs << (k ? " " : "") << rep.roundErrors[k];
    t.set("round_errors", errs.str());
    summary.set("natural_map", t);
  }
  IO::Summary w;
  w.set("norm_estimate", rep.normW);
  if (rep.spectrumKnown) w.set("eig_min", rep.eigMin).set("eig_max", rep.eigMax).set("numerical_rank", rep.numericalRank);
  summary.set("W", w);
}

Outcome run(const Args& args, const RCP<const Comm>& self) {
  const FCLIB::SolveOptions options = solveOptions(args);
  Progress::stage("reading " + args.input);
  const auto kind = FCLIB::problemKind(args.input);
  Outcome out;
  out.summary.set("input", args.input);
  const FCLIB::Info info = readInfo(args.input, out.notes);
  out.summary.set("title", info.title);
  FCLIB::SolveReport rep;
  if (kind == FCLIB::ProblemKind::Local) solveLocal(args, options, self, info, rep, out);
  else solveGlobal(args, options, self, info, rep, out);
  reportSolve(args, rep, kind, out.summary);
  if (!rep.note.empty()) out.notes.insert(out.notes.begin(), rep.note);
  std::string note;
  for (const auto& n : out.notes) note += (note.empty() ? "" : "; ") + n;
  if (!note.empty()) out.summary.set("note", note);
  if (out.stored) out.summary.set("stored_solution", *out.stored);
  out.converged = rep.converged;
  out.stopReason = rep.stopReason;
  return out;
}

// Kokkos (under Tpetra::ScopeGuard) answers --help with its own text, so ours
// is printed before it starts.
bool helpRequested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  if (helpRequested(argc, argv)) {
    const std::string lost = printOnStdout(usage());
    if (lost.empty()) return kConverged;
    std::cerr << "tribos_fclib: run failed: cannot write the usage on stdout: " << lost << std::endl;
    return kRunFailure;
  }
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();
  auto self = comm->split(rank == 0 ? 0 : 1, rank);
  int status = kConverged;
  if (rank == 0) {
    try {
      const Args args = parse(argc, argv);
      Progress::Session progress(args.quiet ? nullptr : &std::cerr);
      checkOutputs(args, self);
      const Outcome outcome = run(args, self);
      const std::string json = outcome.summary.toJson() + "\n";
      if (!args.summary.empty()) IO::writeFileAtomically(args.summary, json);
      const std::string lost = printOnStdout(json);
      status = !lost.empty() ? kRunFailure : outcome.converged ? kConverged : kNotConverged;
      if (!outcome.converged) std::cerr << "tribos_fclib: not converged: " << outcome.stopReason << std::endl;
      if (!lost.empty())
        std::cerr << "tribos_fclib: run failed: cannot write the summary on stdout: " << lost
                  << (args.summary.empty() ? "" : " (it is in " + args.summary + ")") << std::endl;
    } catch (const std::exception& e) {
      std::cerr << "tribos_fclib: error: " << e.what() << std::endl;
      status = kError;
    } catch (...) {
      std::cerr << "tribos_fclib: error: an exception that is not a std::exception" << std::endl;
      status = kError;
    }
  }
  Teuchos::broadcast(*comm, 0, &status);
  return status;
}
