// tribos_fclib: read an FCLIB problem, solve it with a Tribos friction
// algorithm, compare with the stored solution when there is one, and report.
//   tribos_fclib FILE.hdf5 [--xml solver.xml] [--algorithm NAME] [--summary FILE.json]
//                [--mass-solver KLU2|CHOLMOD|Tacho] [--write-solution OUT.hdf5] [--verbose]
// The solve runs on rank 0 with a communicator of one rank (Amesos2 is not
// usable on multi-rank communicators in this Trilinos build); other ranks wait.
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_FCLIB.hpp"
#include "Tribos_FCLIB_Accuracy.hpp"
#include "Tribos_FCLIB_Solve.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Summary.hpp"

namespace {

using namespace Tribos;

const char* kUsage =
    "usage: tribos_fclib FILE.hdf5 [--xml solver.xml] [--algorithm MSA+Algorithm1|Algorithm2|Tresca]\n"
    "                   [--summary FILE.json] [--mass-solver KLU2|CHOLMOD|Tacho] [--write-solution OUT.hdf5] [--verbose]\n"
    "solver.xml: a ParameterList holding the friction solver list (sublists \"Algorithm 1\", \"MSA\",\n"
    "\"Algorithm 2\"), either at its root or in a sublist \"Solver\"; \"Outer Algorithm\" there picks the\n"
    "algorithm (default Algorithm2, --algorithm wins).\n";

struct Args {
  std::string input, xml, summary, algorithm, massSolver = "KLU2", writeSolution;
  bool verbose = false;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&](const char* flag) {
      TRIBOS_REQUIRE(i + 1 < argc, flag << " needs a value\n" << kUsage);
      return std::string(argv[++i]);
    };
    if (s == "--xml") a.xml = next("--xml");
    else if (s == "--summary") a.summary = next("--summary");
    else if (s == "--algorithm") a.algorithm = next("--algorithm");
    else if (s == "--mass-solver") a.massSolver = next("--mass-solver");
    else if (s == "--write-solution") a.writeSolution = next("--write-solution");
    else if (s == "--verbose") a.verbose = true;
    else if (s == "--help" || s == "-h") throw Error(kUsage);
    else if (!s.empty() && s[0] == '-') throw Error("unknown option " + s + "\n" + kUsage);
    else {
      TRIBOS_REQUIRE(a.input.empty(), "more than one input file given\n" << kUsage);
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(!a.input.empty(), "no input file given\n" << kUsage);
  return a;
}

double relDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]) * (a[i] - b[i]), n += b[i] * b[i];
  return std::sqrt(d) / std::max(std::sqrt(n), 1e-300);
}

IO::Summary errSummary(const FCLIB::NaturalMapError& e) {
  IO::Summary s;
  s.set("absolute", e.absolute).set("relative_to_q", e.relativeToQ).set("relative_to_max", e.relativeToMax);
  s.set("norm_q", e.normQ).set("norm_r", e.normR).set("norm_u", e.normU);
  return s;
}

IO::Summary run(const Args& args, const RCP<const Comm>& self) {
  FCLIB::SolveOptions options;
  options.massSolver = args.massSolver;
  options.verbose = args.verbose;
  if (!args.xml.empty()) {
    auto pl = Teuchos::getParametersFromXmlFile(args.xml);
    const Teuchos::ParameterList& solver = pl->isSublist("Solver") ? pl->sublist("Solver") : *pl;
    options.solverParams = solver;
    if (solver.isParameter("Outer Algorithm")) options.algorithm = solver.get<std::string>("Outer Algorithm");
  }
  if (!args.algorithm.empty()) options.algorithm = args.algorithm;

  IO::Summary summary;
  summary.set("input", args.input);
  const FCLIB::Info info = FCLIB::readInfo(args.input);
  summary.set("title", info.title);
  const auto kind = FCLIB::problemKind(args.input);
  FCLIB::SolveReport rep;
  std::optional<FCLIB::Solution> stored = FCLIB::readSolution(args.input);
  IO::Summary storedSummary;
  if (kind == FCLIB::ProblemKind::Local) {
    const auto p = FCLIB::readLocal(args.input);
    summary.set("kind", "local").set("contacts", p.numberOfContacts());
    rep = FCLIB::solve(p, options, self);
    if (stored && stored->r.size() == rep.r.size()) {
      storedSummary.set("err", errSummary(FCLIB::naturalMapError(p, stored->r)));
      storedSummary.set("rel_diff_r", relDiff(rep.r, stored->r));
    }
    if (!args.writeSolution.empty()) {
      FCLIB::Solution s{{}, rep.u, rep.r, {}};
      FCLIB::writeLocal(args.writeSolution, p, info, &s);
    }
  } else {
    const auto p = FCLIB::readGlobal(args.input);
    summary.set("kind", "global").set("contacts", p.numberOfContacts()).set("dofs", p.M.m);
    rep = FCLIB::solve(p, options, self);
    if (stored && stored->r.size() == rep.r.size()) {
      FCLIB::MassSolver M(p.M, options.massSolver);
      storedSummary.set("err", errSummary(FCLIB::naturalMapError(p, stored->r, M.function())));
      storedSummary.set("rel_diff_r", relDiff(rep.r, stored->r));
      if (stored->v.size() == rep.v.size()) storedSummary.set("rel_diff_v", relDiff(rep.v, stored->v));
    }
    if (!args.writeSolution.empty()) {
      FCLIB::Solution s{rep.v, rep.u, rep.r, {}};
      FCLIB::writeGlobal(args.writeSolution, p, info, &s);
    }
  }
  summary.set("algorithm", rep.algorithm);
  summary.set("converged", rep.status.converged).set("stop_reason", rep.status.reason);
  summary.set("outer_iterations", rep.status.outer_iterations).set("msa_iterations", rep.status.msa_iterations);
  summary.set("inner_iterations", rep.status.inner_iterations);
  summary.set("n_A", rep.n_A).set("n_A_qpp", static_cast<long long>(rep.status.n_A_qpp));
  summary.set("n_A_qpq", static_cast<long long>(rep.status.n_A_qpq));
  if (kind == FCLIB::ProblemKind::Global) summary.set("mass_solves", rep.massSolves).set("mass_solver", args.massSolver);
  summary.set("time_setup_s", rep.timeSetup).set("time_solve_s", rep.timeSolve);
  summary.set("err", errSummary(rep.err));
  IO::Summary kkt;
  kkt.set("nonpenetration", rep.kktNormal).set("complementarity", rep.kktComplementarity);
  kkt.set("friction_law", rep.kktFriction);
  summary.set("kkt", kkt);
  IO::Summary w;
  w.set("norm_estimate", rep.normW);
  if (rep.spectrumKnown) w.set("eig_min", rep.eigMin).set("eig_max", rep.eigMax).set("numerical_rank", rep.numericalRank);
  summary.set("W", w);
  if (!rep.note.empty()) summary.set("note", rep.note);
  if (stored) summary.set("stored_solution", storedSummary);
  return summary;
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();
  auto self = comm->split(rank == 0 ? 0 : 1, rank);
  int status = 0;
  if (rank == 0) {
    try {
      const Args args = parse(argc, argv);
      const auto summary = run(args, self);
      const std::string json = summary.toJson() + "\n";
      if (!args.summary.empty()) IO::writeFileAtomically(args.summary, json);
      std::cout << json;
    } catch (const std::exception& e) {
      std::cerr << "tribos_fclib: error: " << e.what() << std::endl;
      status = 1;
    }
  }
  Teuchos::broadcast(*comm, 0, &status);
  return status;
}
