// Tribos_BlasKernels.hpp: the kernels of the BLAS every dense factorization,
// triangular solve and dense block of Tribos runs on.
//
// OpenBLAS built for several processors (DYNAMIC_ARCH, as Debian ships it)
// picks its kernels by the processor's model number when it is loaded. A
// release does not know processors newer than itself: Debian bookworm's
// OpenBLAS 0.3.21 takes a Sapphire Rapids Xeon for an unknown model and falls
// back to its Prescott (SSE3) kernels, which factor the small dense subdomain
// blocks of FETI at about 0.6 of the speed of its SkylakeX (AVX-512) kernels
// on the same processor (docs/benchmarks.md). OPENBLAS_CORETYPE names the
// kernels by hand; selectBlasKernels does what it would: when OpenBLAS chose
// Prescott and the processor has the instructions of a later kernel set
// (AVX-512 F/CD/BW/DQ/VL: SkylakeX; AVX2 and FMA: Haswell), OpenBLAS is
// initialized again with that set. The choice is made by features the
// processor reports, never by guessing from its name, so a processor without
// them keeps Prescott. A user's OPENBLAS_CORETYPE is kept, and a BLAS other
// than OpenBLAS is left alone (the OpenBLAS entry points are looked up at
// run time).
#pragma once

#include <string>

namespace Tribos {

// Call at the start of a program, before any BLAS call (prepareProcess does).
// Returns what was done, for a log ("" when nothing was changed).
std::string selectBlasKernels();

// The kernel set OpenBLAS runs ("" for another BLAS).
std::string blasKernelName();

}  // namespace Tribos
