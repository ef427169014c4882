// SemismoothTestUtils.hpp: a minimal check-and-count harness and the prism
// problem of input/prism_tresca.xml at a given level.
#pragma once

#include <Tpetra_Core.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#include "Tribos_SemismoothInput.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace sstest {

inline int& failures() {
  static int n = 0;
  return n;
}
inline int& passes() {
  static int n = 0;
  return n;
}

#define SS_CHECK(cond, msg)                                                         \
  do {                                                                              \
    if (cond) {                                                                     \
      ++sstest::passes();                                                           \
    } else {                                                                        \
      ++sstest::failures();                                                         \
      std::cout << "FAILED " << __FILE__ << ":" << __LINE__ << ": " << msg << "\n"; \
    }                                                                               \
  } while (0)

inline std::string prismInput() {
  const char* src = std::getenv("TRIBOS_SOURCE_DIR");
  return std::string(src ? src : TRIBOS_SOURCE_DIR_DEFAULT) + "/input/prism_tresca.xml";
}

inline Tribos::Semismooth::MeshContactProblem prism(int level) {
  return Tribos::Semismooth::readMeshContactProblem(prismInput(), level);
}

inline int finish() {
  std::cout << passes() << " passed, " << failures() << " failed\n";
  return failures() == 0 ? 0 : 1;
}

}  // namespace sstest
