// Tribos_CholmodStatus.hpp: what a CHOLMOD call's status means, said once for
// every user of CHOLMOD. Running out of memory is not an indefinite matrix:
// it becomes std::bad_alloc, which drivers report with the stage of the run.
#pragma once

#include <cholmod.h>

#include <new>
#include <string>

#include "Tribos_Error.hpp"

namespace Tribos {

// After cholmod_analyze / cholmod_factorize / conversions: throws
// std::bad_alloc when CHOLMOD ran out of memory, Tribos::Error naming `what`
// otherwise. For factorizations also pass the factor: a pivot that is not
// positive (L->minor < n) means the matrix is not positive definite.
inline void requireCholmodOk(const cholmod_common& common, const std::string& what, const cholmod_factor* L = nullptr) {
  if (common.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  TRIBOS_REQUIRE(common.status >= CHOLMOD_OK, "CHOLMOD: " << what << " failed (status " << common.status << ")");
  TRIBOS_REQUIRE(L == nullptr || L->minor == L->n, "CHOLMOD: " << what << ": the matrix of size " << L->n
                                                               << " is not positive definite (pivot " << L->minor << ")");
}

}  // namespace Tribos
