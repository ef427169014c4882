// SemismoothTestUtils.hpp: the prism problem of input/prism_tresca.xml at a
// given level.
#pragma once

#include <Tpetra_Core.hpp>

#include <cstdlib>
#include <string>

#include "Tribos_SemismoothInput.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace sstest {

inline std::string prismInput() {
  const char* src = std::getenv("TRIBOS_SOURCE_DIR");
  return std::string(src ? src : TRIBOS_SOURCE_DIR_DEFAULT) + "/input/prism_tresca.xml";
}

inline Tribos::Semismooth::MeshContactProblem prism(int level) {
  return Tribos::Semismooth::readMeshContactProblem(prismInput(), level);
}

}  // namespace sstest
