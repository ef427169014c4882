// Tribos_Run.hpp: one run of the XML-driven solver: set up the discretization,
// solve with the algorithm the parameters choose, write results and summary.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>

#include "Tribos_Summary.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

struct RunOptions {
  std::string outputDir;     // overrides Output/Directory when non-empty
  bool verify = false;       // also solve monolithically and compare
  bool verbose = false;      // print solver iterations
  std::string inputName;     // for the summary
  std::string exportFclib;   // write the contact problem and its solution as an FCLIB global problem
};

// Checks what can be checked identically on every rank before any work
// (e.g. enough subdomains for the ranks); throws Tribos::Error naming it.
void checkRunnable(const Teuchos::ParameterList& params, int numRanks);

struct RunResult {
  IO::Summary summary;     // identical on every rank
  bool converged = false;  // the summary's "converged": the written result passed its KKT check
};

// Runs the problem, writes the result (also when it did not converge).
RunResult run(const Teuchos::ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm);

}  // namespace Tribos
