// tribos: the XML-driven solver.
//   mpirun -np N tribos input/FILE.xml [--output DIR] [--summary FILE.json]
//                      [--set "Sublist/Key=value" ...] [--verify] [--export-fclib FILE.hdf5]
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Core.hpp>

#include <mpi.h>

#include <iostream>
#include <string>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Run.hpp"

namespace {

const char* kUsage =
    "usage: tribos INPUT.xml [--output DIR] [--summary FILE.json] [--set \"Sublist/Key=value\" ...] [--verify] [--verbose]\n"
    "             [--export-fclib FILE.hdf5]\n";

struct Args {
  std::string input, summary;
  std::vector<std::string> overrides;
  Tribos::RunOptions options;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&](const char* flag) {
      TRIBOS_REQUIRE(i + 1 < argc, flag << " needs a value\n" << kUsage);
      return std::string(argv[++i]);
    };
    if (s == "--output") a.options.outputDir = next("--output");
    else if (s == "--summary") a.summary = next("--summary");
    else if (s == "--set") a.overrides.push_back(next("--set"));
    else if (s == "--verify") a.options.verify = true;
    else if (s == "--verbose") a.options.verbose = true;
    else if (s == "--export-fclib") a.options.exportFclib = next("--export-fclib");
    else if (s == "--help" || s == "-h") throw Tribos::Error(kUsage);
    else if (!s.empty() && s[0] == '-') throw Tribos::Error("unknown option " + s + "\n" + kUsage);
    else {
      TRIBOS_REQUIRE(a.input.empty(), "more than one input file given (" << a.input << ", " << s << ")\n" << kUsage);
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(!a.input.empty(), "no input file given\n" << kUsage);
  a.options.inputName = a.input;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  Args args;
  Teuchos::RCP<Teuchos::ParameterList> params;
  // Input errors happen identically on every rank: report once and exit.
  try {
    args = parse(argc, argv);
    params = Tribos::Input::read(args.input, args.overrides);
    Tribos::checkRunnable(*params, comm->getSize());
  } catch (const std::exception& e) {
    if (root) std::cerr << "tribos: error: " << e.what() << std::endl;
    return 1;
  }
  try {
    const auto result = Tribos::run(*params, args.options, comm);
    const auto& summary = result.summary;
    // Teuchos timers of the phases (factorization, F applications, QP solvers, output).
    if (args.options.verbose) Teuchos::TimeMonitor::summarize(comm.ptr(), std::cout);
    if (root) {
      const std::string json = summary.toJson() + "\n";
      if (!args.summary.empty()) Tribos::IO::writeFileAtomically(args.summary, json);
      std::cout << json;
    }
    if (!result.converged) {
      if (root) std::cerr << "tribos: not converged: see stop_reason in the summary; the result is written" << std::endl;
      return 2;
    }
  } catch (const Tribos::CollectiveError& e) {
    // Every rank took the same decision: report once, no abort.
    if (root) std::cerr << "tribos: error: " << e.what() << std::endl;
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "tribos: error" << (comm->getSize() > 1 ? " on rank " + std::to_string(comm->getRank()) : "") << ": "
              << e.what() << std::endl;
    if (comm->getSize() > 1) MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
  return 0;
}
