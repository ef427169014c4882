// Tribos_Driver.hpp: the tribos driver's main as a function: its command
// line read, the input read and agreed on every rank, --help,
// --print-parameters, the run and its report, the exit code returned.
//
// The program drivers/tribos.cpp keeps only what belongs to a process (MPI
// and Kokkos start-up, stdout's buffering, ignoring SIGXFSZ) and calls this;
// a test program calls it many times in one process (test/bad_inputs), so
// that a refusal is checked without starting a process for it.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {

// Runs the driver on every rank of comm with the command-line arguments
// `args` (without the program name) and returns the exit code (0-3,
// docs/exit_codes.md). Prints what the program prints: the summary and
// --help/--print-parameters on rank 0's std::cout, messages and progress on
// rank 0's std::cerr. Collective over comm. A failure one rank finds alone ends the whole job by MPI_Abort (the
// other ranks cannot go on without it); every other outcome returns.
int runDriver(const std::vector<std::string>& args, const RCP<const Comm>& comm);

}  // namespace Tribos
