// Tribos_QP_Status.hpp: what a QP solve reports back to its caller.
#pragma once

#include <ostream>
#include <string>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

struct QPStatus {
  bool converged = false;
  std::string reason;           // why the iteration stopped, in words
  int iterations = 0;           // all steps (CG + expansion + proportioning), or inner totals
  int cg_steps = 0;
  int expansion_steps = 0;
  int proportioning_steps = 0;
  long n_A = 0;                 // Hessian applications, power iterations included
  SC norm_gP = 0;               // ||g^P|| at the returned x
  SC norm_Gx = 0;               // ||G x|| (SMALBE only)
  int outer_iterations = 0;     // SMALBE only
};

std::ostream& operator<<(std::ostream& os, const QPStatus& s);

}  // namespace QP
}  // namespace Tribos
