#include "Tribos_BlasKernels.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>

namespace Tribos {

namespace {

template <class F>
F openblasFunction(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}

using CoreName = char* (*)();
using Init = void (*)();

// The most capable kernel set whose instructions the processor has beyond
// Prescott's, or nullptr.
const char* laterKernels() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  return nullptr;
}

}  // namespace

std::string blasKernelName() {
  const auto coreName = openblasFunction<CoreName>("openblas_get_corename");
  return coreName ? std::string(coreName()) : std::string();
}

std::string selectBlasKernels() {
  const auto coreName = openblasFunction<CoreName>("openblas_get_corename");
  const auto quit = openblasFunction<Init>("gotoblas_dynamic_quit");
  const auto init = openblasFunction<Init>("gotoblas_dynamic_init");
  if (!coreName || !quit || !init || std::getenv("OPENBLAS_CORETYPE")) return "";
  if (strcasecmp(coreName(), "Prescott") != 0) return "";
  const char* kernels = laterKernels();
  if (!kernels) return "";
  // gotoblas_dynamic_init reads OPENBLAS_CORETYPE, and does nothing while a
  // kernel set is chosen: quit first.
  setenv("OPENBLAS_CORETYPE", kernels, 0);
  quit();
  init();
  return std::string("OpenBLAS took this processor for an unknown model (Prescott kernels); its instructions "
                     "allow ") + coreName() + ", selected";
}

}  // namespace Tribos
