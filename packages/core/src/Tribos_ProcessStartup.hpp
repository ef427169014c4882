// Tribos_ProcessStartup.hpp: what every Tribos program does first thing in
// main, before MPI is initialized and before any BLAS call.
#pragma once

#include "Tribos_BlasKernels.hpp"
#include "Tribos_MpiStartup.hpp"

namespace Tribos {

// A one-process run without the MPI daemon (Tribos_MpiStartup.hpp) and the
// BLAS kernels the processor allows (Tribos_BlasKernels.hpp).
inline void prepareProcess() {
  prepareMpiStartup();
  selectBlasKernels();
}

}  // namespace Tribos
