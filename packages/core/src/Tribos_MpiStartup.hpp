// Tribos_MpiStartup.hpp: what a program does before MPI_Init (before
// Tpetra::ScopeGuard or Teuchos::GlobalMPISession) so that a one-process run
// starts at once.
//
// A process started without a launcher (no mpirun, mpiexec or srun) is an MPI
// singleton: one rank that talks to no other process. Open MPI 4 still starts
// its runtime daemon for it and probes the network transports (libfabric,
// PSM2) inside MPI_Init: about 0.3 s on a workstation, longer than the whole
// solve of a small problem. For such a process only, and only for the
// settings the user has not made, this asks Open MPI for an isolated
// singleton (no daemon) and the point-to-point layer of the shared-memory
// and self transports. A process under a launcher, or one whose environment
// already sets these variables, is left alone; other MPI implementations
// ignore the variables. A singleton run cannot spawn processes
// (MPI_Comm_spawn), which Tribos never does.
#pragma once

#include <cstdlib>

namespace Tribos {

// True when a launcher started this process: Open MPI's mpirun, a PMI or
// PMIx launcher (MPICH's mpiexec, srun), or a Slurm job step.
inline bool launchedByMpiLauncher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_STEP_ID"})
    if (std::getenv(variable)) return true;
  return false;
}

// Call first thing in main, before MPI is initialized.
inline void prepareMpiStartup() {
  if (launchedByMpiLauncher()) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);  // 0: keep the user's value
  setenv("OMPI_MCA_pml", "ob1", 0);
}

}  // namespace Tribos
