#include "Tribos_Driver.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <mpi.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FailureReport.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_InputXml.hpp"
#include "Tribos_MemoryEstimate.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Run.hpp"

namespace Tribos {

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
    "  --restart DIR           continue the load history of this input's result in DIR (a run killed or\n"
    "                          stopped) after its last complete step, on as many ranks as it ran\n"
    "  --print-parameters      print the parameters as an XML input file, every default filled and\n"
    "                          documented (of INPUT.xml and --set when given), and exit; nothing is solved\n"
    "  --help                  this text\n"
    "exit codes: 0 converged, 1 bad input (nothing written), 2 not converged (result written, marked),\n"
    "            3 run failure: output, memory or numerical breakdown (no result written)\n";

enum Exit { kConverged = 0, kBadInput = 1, kNotConverged = 2, kRunFailure = 3 };

// `text` printed on stdout by rank 0 and flushed, collective: "" when it and
// all printed there before was written, else why not on every rank (a full
// disk, a file-size limit): output lost is a failed run, never exit 0.
std::string printOnStdout(const Comm& comm, const std::string& text) {
  std::string why;
  if (comm.getRank() == 0) {
    errno = 0;  // the failing write's reason, whichever call makes it
    std::cout << text << std::flush;
    if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout))
      why = errno != 0 ? std::strerror(errno) : "a write error";
  }
  return agreeOnError(comm, why);
}

// The exit of a run whose only output is `text` on stdout (--help, --print-parameters).
int printed(const Comm& comm, const std::string& text, const char* what) {
  const std::string lost = printOnStdout(comm, text);
  if (lost.empty()) return kConverged;
  if (comm.getRank() == 0) std::cerr << "tribos: run failed: cannot write " << what << " on stdout: " << lost << std::endl;
  return kRunFailure;
}

struct Args {
  std::string input;
  std::vector<std::string> overrides;
  RunOptions options;
  bool help = false, quiet = false, printParameters = false;
};

Args parse(const std::vector<std::string>& argv) {
  Args a;
  const size_t argc = argv.size();
  for (size_t i = 0; i < argc; ++i) {
    const std::string& s = argv[i];
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
    else if (s == "--max-memory") a.options.maxMemory = parseMemorySize(next("--max-memory"), "--max-memory");
    else if (s == "--export-fclib") a.options.exportFclib = next("--export-fclib");
    else if (s == "--restart") a.options.restartDir = next("--restart");
    else if (s == "--print-parameters") a.printParameters = true;
    else if (s == "--help" || s == "-h") a.help = true;
    else if (!s.empty() && s[0] == '-') throw Error("unknown option " + s + "\n" + kUsage);
    else {
      TRIBOS_REQUIRE(a.input.empty(), "more than one input file given (" << a.input << ", " << s << ")\n" << kUsage);
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(a.help || a.printParameters || !a.input.empty(), "no input file given\n" << kUsage);
  // A restart writes where the result it continues is.
  if (!a.options.restartDir.empty()) {
    TRIBOS_REQUIRE(a.options.outputDir.empty() || a.options.outputDir == a.options.restartDir,
                   "--restart " << a.options.restartDir << " continues the result there; --output "
                                << a.options.outputDir << " names another directory");
    a.options.outputDir = a.options.restartDir;
  }
  a.options.inputName = a.input;
  return a;
}

// A failure the ranks did not agree on beforehand (FailureReport.hpp):
// said once by rank 0 when every rank found it, the run ended by MPI_Abort
// when this rank found it alone.
int reportFailure(const RankFailure& failure, FailureChannel& channel, const Comm& comm) {
  const auto shared = channel.agree(failure, kFailureGraceSeconds);
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
int runAndReport(const Args& args, const Teuchos::ParameterList& params, const RCP<const Comm>& comm,
                 FailureChannel& channel) {
  const bool root = comm->getRank() == 0;
  RankFailure failure;
  try {
    const auto result = run(params, args.options, comm);
    // Teuchos timers of the phases (factorization, F applications, QP solvers, output).
    // Union: phases that run on some ranks only (the contact search on the
    // ranks that hold the contact surfaces) are listed too.
    if (args.options.verbose)
      Teuchos::TimeMonitor::summarize(comm.ptr(), std::cout, false, true, true, Teuchos::Union);
    const std::string json = result.summary.toJson() + "\n";
    const std::string lost = printOnStdout(*comm, json);
    if (!args.options.summaryFile.empty()) {
      try {
        IO::writeFileAtomically(args.options.summaryFile, json, comm);
      } catch (const RunFailure& e) {
        if (root)
          std::cerr << "tribos: run failed: " << e.what() << (lost.empty() ? " (the summary is on stdout)" : "")
                    << std::endl;
        return kRunFailure;
      }
    }
    if (!lost.empty()) {
      if (root)
        std::cerr << "tribos: run failed: cannot write the summary on stdout: " << lost
                  << (args.options.summaryFile.empty() ? "" : " (it is in " + args.options.summaryFile + ")")
                  << (result.written ? "; the result is written" : "") << std::endl;
      return kRunFailure;
    }
    if (!result.converged) {
      if (root)
        std::cerr << "tribos: not converged: " << result.stopReason
                  << (result.written ? "; the result is written, marked converged = false" : "") << std::endl;
      return kNotConverged;
    }
    return kConverged;
  } catch (const RunFailure& e) {
    if (root) std::cerr << "tribos: run failed: " << e.what() << std::endl;
    return kRunFailure;
  } catch (const CollectiveError& e) {
    // Every rank took the same decision before any result: report once, no abort.
    if (root) std::cerr << "tribos: error: " << e.what() << std::endl;
    return kBadInput;
  } catch (const std::bad_alloc&) {
    failure.message = "out of memory during " + Progress::currentStage() +
                      "; the memory estimate made before the run (docs/exit_codes.md) found enough memory, so a limit "
                      "(ulimit, cgroup) or other processes may hold it";
  } catch (const Error& e) {
    failure = {std::string(e.what()) + " (found during " + Progress::currentStage() + ")", true};
  } catch (const std::exception& e) {
    failure.message = "during " + Progress::currentStage() + ": " + e.what();
  } catch (...) {
    failure.message = "during " + Progress::currentStage() + ": an exception that is not a std::exception";
  }
  return reportFailure(failure, channel, *comm);
}

}  // namespace

int runDriver(const std::vector<std::string>& argv, const RCP<const Comm>& comm) {
  const bool root = comm->getRank() == 0;
  // Made at start, before any rank can fail (a collective MPI_Comm_dup).
  FailureChannel channel(rawComm(*comm));
  // What a process starts with, so that a second call in one process says
  // the same: the stage an early failure names, timers counting this run only.
  Progress::stage("start-up");
  Teuchos::TimeMonitor::zeroOutTimers();
  Args args;
  RCP<Teuchos::ParameterList> params;
  // Every rank reads the input itself; the ranks then agree on the outcome
  // (the lowest failing rank's message), so that a rank that could not read
  // the file never leaves the others waiting.
  std::string inputError;
  try {
    args = parse(argv);
    if (args.help) {
      // the usage alone
    } else if (args.printParameters) {
      params = args.input.empty() ? Input::defaults(args.overrides) : Input::read(args.input, args.overrides);
    } else {
      params = Input::read(args.input, args.overrides);
      checkRunnable(*params, args.options, comm->getSize());
    }
  } catch (const std::exception& e) {
    inputError = e.what();
  }
  inputError = agreeOnError(*comm, inputError);
  if (!inputError.empty()) {
    if (root) std::cerr << "tribos: error: " << inputError << std::endl;
    return kBadInput;
  }
  if (args.help) {
    return printed(*comm, kUsage, "the usage");
  }
  if (args.printParameters) {
    // The effective list the run would use, as a file it accepts again; no
    // rank check, no output directory: no work at all.
    return printed(*comm, root ? Input::toXml(*params) : "", "the parameters");
  }
  // A file-size limit (ulimit -f) makes writes fail with EFBIG, reported
  // like a full disk, instead of killing the process. Not before: an output
  // of --help or --print-parameters cut by the limit ends the process.
  std::signal(SIGXFSZ, SIG_IGN);
  Progress::Session progress(root && !args.quiet ? &std::cerr : nullptr);
  return runAndReport(args, *params, comm, channel);
}

}  // namespace Tribos
