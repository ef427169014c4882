// tribos: the XML-driven solver.
//   mpirun -np N tribos input/FILE.xml [--output DIR] [--summary FILE.json]
//                      [--set "Sublist/Key=value" ...] [--verify] [--verbose] [--quiet]
//                      [--max-memory SIZE] [--export-fclib FILE.hdf5]
//   tribos --print-parameters [input/FILE.xml] [--set "Sublist/Key=value" ...]
// Exit codes (docs/exit_codes.md): 0 converged; 1 bad input or a problem
// refused before any work, nothing written; 2 not converged, the result is
// written and marked so; 3 the run failed (output not writable, disk full,
// out of memory, numerical breakdown), no result written.
//
// The driver itself is Tribos::runDriver (drivers/src/Tribos_Driver.hpp);
// this program adds what belongs to a process.
#include <Tpetra_Core.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "Tribos_Driver.hpp"
#include "Tribos_ProcessStartup.hpp"

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
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
  return Tribos::runDriver(std::vector<std::string>(argv + 1, argv + argc), Tpetra::getDefaultComm());
}
