// Tribos_Run.hpp: one run of the XML-driven solver: set up the discretization,
// solve with the algorithm the parameters choose, write results and summary.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>

#include "Tribos_RunReport.hpp"
#include "Tribos_Summary.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

struct RunOptions {
  std::string outputDir;     // overrides Output/Directory when non-empty
  bool verify = false;       // also solve monolithically and compare
  bool verbose = false;      // print solver iterations
  std::string inputName;     // for the summary
  std::string exportFclib;   // write the contact problem and its solution as an FCLIB global problem
  std::string summaryFile;   // a copy of the summary (checked before any work; written by the caller)
  double maxMemory = 0;      // bytes one machine may give the run; 0: its available memory
  std::string restartDir;    // continue the load history of the result there (outputDir is the same directory)
};

// Checks what can be checked identically on every rank before any work
// (e.g. enough subdomains for the ranks, options that apply to the
// problem); throws Tribos::Error naming it.
void checkRunnable(const Teuchos::ParameterList& params, const RunOptions& options, int numRanks);

struct RunResult {
  IO::Summary summary;     // identical on every rank: report.toSummary()
  RunReport report;        // what each step of the run found
  bool converged = false;  // the summary's "converged": the written result passed its KKT check
  std::string stopReason;  // the summary's "stop_reason"
  bool written = false;    // the result files were written
};

// Runs the problem and writes the result (also when it did not converge,
// marked so). Before any work: the memory the run needs is estimated and
// every output path is checked (Tribos::CollectiveError). The result files
// (Output/Base Name .h5, .xmf, .parameters.xml, .history.csv and .json, the
// summary last)
// replace an earlier set only when all are written. Numerical breakdown (non-finite or
// overflowing values) and failed writes throw Tribos::RunFailure.
RunResult run(const Teuchos::ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm);

}  // namespace Tribos
