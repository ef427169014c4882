// tribos: the XML-driven solver.
//   mpirun -np N tribos input/FILE.xml [--output DIR] [--summary FILE.json]
//                      [--set "Sublist/Key=value" ...] [--verify] [--verbose] [--quiet]
//                      [--max-memory SIZE] [--export-fclib FILE.hdf5]
//   tribos --print-parameters [input/FILE.xml] [--set "Sublist/Key=value" ...]
// Exit codes (docs/exit_codes.md): 0 converged; 1 bad input or a problem
// refused before any work, nothing written; 2 not converged, the result is
// written and marked so; 3 the run failed (output not writable, disk full,
// out of memory, numerical breakdown), no result written.
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Core.hpp>

#include <mpi.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FailureReport.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_InputXml.hpp"
#include "Tribos_MemoryEstimate.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Run.hpp"
#include "Tribos_MpiStartup.hpp"

namespace {

const char* kUsage =
    "usage: tribos INPUT.xml [options]\n"
    "       tribos --print-parameters [INPUT.xml] [--set ...]\n"
    "  --output DIR            result directory (default: Output/Directory of the input)\n"
    "  --summary FILE.json     also write the run summary to FILE.json (it is always printed on stdout)\n"
    "  --set \"Sublist/Key=value\"  override one input parameter (repeatable), e.g. --set \"Mesh/Level=8\"\n"
    "  --verify                also solve monolithically and report the difference (linear problems)\n"
    "  --verbose               print solver iterations and timers on stdout\n"
    "  --quiet                 no progress lines on stderr\n"
    "  --max-memory SIZE       refuse a run estimated to need more than SIZE (e.g. 4G) on one machine\n"
    "  --export-fclib FILE     write the FETI contact problem and its solution as an FCLIB file\n"
    "  --print-parameters      print the parameters as an XML input file, every default filled and\n"
    "                          documented (of INPUT.xml and --set when given), and exit; nothing is solved\n"
    "  --help                  this text\n"
    "exit codes: 0 converged, 1 bad input (nothing written), 2 not converged (result written, marked),\n"
    "            3 run failure: output, memory or numerical breakdown (no result written)\n";

enum Exit { kConverged = 0, kBadInput = 1, kNotConverged = 2, kRunFailure = 3 };

struct Args {
  std::string input;
  std::vector<std::string> overrides;
  Tribos::RunOptions options;
  bool help = false, quiet = false, printParameters = false;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&](const char* flag) {
      TRIBOS_REQUIRE(i + 1 < argc, flag << " needs a value\n" << kUsage);
      const std::string v = argv[++i];
      TRIBOS_REQUIRE(!v.empty(), flag << " needs a non-empty value");
      return v;
    };
    if (s == "--output") a.options.outputDir = next("--output");
    else if (s == "--summary") a.options.summaryFile = next("--summary");
    else if (s == "--set") a.overrides.push_back(next("--set"));
    else if (s == "--verify") a.options.verify = true;
    else if (s == "--verbose") a.options.verbose = true;
    else if (s == "--quiet") a.quiet = true;
    else if (s == "--max-memory") a.options.maxMemory = Tribos::parseMemorySize(next("--max-memory"), "--max-memory");
    else if (s == "--export-fclib") a.options.exportFclib = next("--export-fclib");
    else if (s == "--print-parameters") a.printParameters = true;
    else if (s == "--help" || s == "-h") a.help = true;
    else if (!s.empty() && s[0] == '-') throw Tribos::Error("unknown option " + s + "\n" + kUsage);
    else {
      TRIBOS_REQUIRE(a.input.empty(), "more than one input file given (" << a.input << ", " << s << ")\n" << kUsage);
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(a.help || a.printParameters || !a.input.empty(), "no input file given\n" << kUsage);
  a.options.inputName = a.input;
  return a;
}

// A failure the ranks did not agree on beforehand (FailureReport.hpp):
// said once by rank 0 when every rank found it, the run ended by MPI_Abort
// when this rank found it alone.
int reportFailure(const Tribos::RankFailure& failure, Tribos::FailureChannel& channel, const Tribos::Comm& comm) {
  const auto shared = channel.agree(failure, Tribos::kFailureGraceSeconds);
  if (shared.everyRank) {
    for (const auto& [message, ranks] : shared.messages)
      std::cerr << "tribos: " << (shared.inputError ? "error" : "run failed") << (ranks.empty() ? "" : " on ranks " + ranks)
                << ": " << message << std::endl;
    return shared.inputError ? kBadInput : kRunFailure;
  }
  std::cerr << "tribos: run failed" << (comm.getSize() > 1 ? " on rank " + std::to_string(comm.getRank()) + " alone" : "")
            << ": " << failure.message
            << (comm.getSize() > 1 ? "; the other ranks cannot go on without it: the run is aborted (no result written)" : "")
            << std::endl;
  if (comm.getSize() > 1) MPI_Abort(MPI_COMM_WORLD, kRunFailure);
  return kRunFailure;
}

// Runs the problem; returns the exit code. Errors the ranks agreed on
// (CollectiveError) are reported once by rank 0; any other exception goes
// through reportFailure.
int runAndReport(const Args& args, const Teuchos::ParameterList& params, const Teuchos::RCP<const Tribos::Comm>& comm,
                 Tribos::FailureChannel& channel) {
  const bool root = comm->getRank() == 0;
  Tribos::RankFailure failure;
  try {
    const auto result = Tribos::run(params, args.options, comm);
    // Teuchos timers of the phases (factorization, F applications, QP solvers, output).
    if (args.options.verbose) Teuchos::TimeMonitor::summarize(comm.ptr(), std::cout);
    const std::string json = result.summary.toJson() + "\n";
    if (root) std::cout << json << std::flush;
    if (!args.options.summaryFile.empty()) {
      try {
        Tribos::IO::writeFileAtomically(args.options.summaryFile, json, comm);
      } catch (const Tribos::RunFailure& e) {
        if (root) std::cerr << "tribos: run failed: " << e.what() << " (the summary is on stdout)" << std::endl;
        return kRunFailure;
      }
    }
    if (!result.converged) {
      if (root)
        std::cerr << "tribos: not converged: " << result.stopReason
                  << (result.written ? "; the result is written, marked converged = false" : "") << std::endl;
      return kNotConverged;
    }
    return kConverged;
  } catch (const Tribos::RunFailure& e) {
    if (root) std::cerr << "tribos: run failed: " << e.what() << std::endl;
    return kRunFailure;
  } catch (const Tribos::CollectiveError& e) {
    // Every rank took the same decision before any result: report once, no abort.
    if (root) std::cerr << "tribos: error: " << e.what() << std::endl;
    return kBadInput;
  } catch (const std::bad_alloc&) {
    failure.message = "out of memory during " + Tribos::Progress::currentStage() +
                      "; the memory estimate made before the run (docs/exit_codes.md) found enough memory, so a limit "
                      "(ulimit, cgroup) or other processes may hold it";
  } catch (const Tribos::Error& e) {
    failure = {std::string(e.what()) + " (found during " + Tribos::Progress::currentStage() + ")", true};
  } catch (const std::exception& e) {
    failure.message = "during " + Tribos::Progress::currentStage() + ": " + e.what();
  } catch (...) {
    failure.message = "during " + Tribos::Progress::currentStage() + ": an exception that is not a std::exception";
  }
  return reportFailure(failure, channel, *comm);
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareMpiStartup();  // before MPI_Init
  // Line-buffered stdout, so that --verbose lines reach a pipe as they happen.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // Kokkos answers --help itself: keep it from seeing ours.
  std::vector<char*> kokkosArgs;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) != "--help" && std::string(argv[i]) != "-h") kokkosArgs.push_back(argv[i]);
  int kokkosArgc = static_cast<int>(kokkosArgs.size());
  kokkosArgs.push_back(nullptr);
  char** kokkosArgv = kokkosArgs.data();
  Tpetra::ScopeGuard guard(&kokkosArgc, &kokkosArgv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  Tribos::FailureChannel channel(MPI_COMM_WORLD);
  Args args;
  Teuchos::RCP<Teuchos::ParameterList> params;
  // Every rank reads the input itself; the ranks then agree on the outcome
  // (the lowest failing rank's message), so that a rank that could not read
  // the file never leaves the others waiting.
  std::string inputError;
  try {
    args = parse(argc, argv);
    if (args.help) {
      // the usage alone
    } else if (args.printParameters) {
      params = args.input.empty() ? Tribos::Input::defaults(args.overrides)
                                  : Tribos::Input::read(args.input, args.overrides);
    } else {
      params = Tribos::Input::read(args.input, args.overrides);
      Tribos::checkRunnable(*params, args.options, comm->getSize());
    }
  } catch (const std::exception& e) {
    inputError = e.what();
  }
  inputError = Tribos::agreeOnError(*comm, inputError);
  if (!inputError.empty()) {
    if (root) std::cerr << "tribos: error: " << inputError << std::endl;
    return kBadInput;
  }
  if (args.help) {
    if (root) std::cout << kUsage;
    return kConverged;
  }
  if (args.printParameters) {
    // The effective list the run would use, as a file it accepts again; no
    // rank check, no output directory: no work at all.
    if (root) std::cout << Tribos::Input::toXml(*params) << std::flush;
    return kConverged;
  }
  // A file-size limit (ulimit -f) makes writes fail with EFBIG, reported
  // like a full disk, instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
  Tribos::Progress::Session progress(root && !args.quiet ? &std::cerr : nullptr);
  return runAndReport(args, *params, comm, channel);
}
