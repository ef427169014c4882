// PrismProblem.hpp: the semismooth* prism of input/prism_tresca.xml at a
// given level, read and validated by the driver's reader (the one reader of
// the input schema).
#pragma once

#include <cstdlib>
#include <string>

#include "Tribos_Input.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace sstest {

inline std::string prismInput() {
  const char* src = std::getenv("TRIBOS_SOURCE_DIR");
  return std::string(src ? src : TRIBOS_SOURCE_DIR_DEFAULT) + "/input/prism_tresca.xml";
}

inline Tribos::Semismooth::MeshContactProblem prism(int level) {
  using namespace Tribos;
  return Input::semismoothProblem(*Input::read(prismInput(), {"Mesh/Level=" + std::to_string(level)}));
}

}  // namespace sstest
