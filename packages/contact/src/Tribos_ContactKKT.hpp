// Tribos_ContactKKT.hpp: the contact part of the KKT conditions of a
// solution, evaluated here for every source of contact results (the FETI and
// semismooth* results through Contact::resultKKT, FCLIB's r and u):
//   non-penetration  gap >= 0
//   complementarity  lambda_N >= 0, lambda_N gap = 0
//   friction law     phi_T = P_g(phi_T - c s)
// per contact, with the normal force lambda_N, the gap left (d - u.n; for
// FCLIB the normal velocity u_N), the tangential force phi_T and the slip s
// (any number of components: 2 in a contact frame, 3 in the tangent plane),
// the slip bound g (Tresca g, Coulomb F lambda_N^+) and P_g the projection
// onto the disk of radius g (QP::projectBall). Forces and displacements are
// compared through a force scale P and a displacement scale U, so every
// figure is dimensionless:
//   nonpenetration   max (-gap)^+ / U
//   complementarity  max |min(lambda_N / P, gap / U)|
//   friction law     max ||phi_T - P_g(phi_T - (P/U) s)|| / P
#pragma once

#include <cmath>

namespace Tribos {
namespace Contact {

class ContactKKT {
 public:
  // P, U > 0: the force and displacement scales.
  ContactKKT(double forceScale, double displacementScale);
  // One contact; phiT and slip have dim components (dim <= 3).
  void add(double lambdaN, double gap, const double* phiT, const double* slip, int dim, double g);
  // Whether the friction law puts the contact on its slip branch:
  // phi_T - (P/U) s outside the disk of radius g, where P_g is not the
  // identity (g <= 0: frictionless, always slipping). A contact on the
  // stick/slip boundary (||phi_T|| = g, s = 0) sticks. Deciding by this
  // rather than by ||phi_T|| against g alone uses the slip as well: a rim
  // node with a small bound whose force falls short of it by the solver's
  // error but which moves reads as slipping, as the law it is checked by.
  bool slips(const double* phiT, const double* slip, int dim, double g) const;
  // Maxima over the contacts added (local: reduce over ranks where needed).
  double nonpenetration() const { return nonpenetration_; }
  double complementarity() const { return complementarity_; }
  double frictionLaw() const { return std::sqrt(frictionLaw2_) * invP_; }

 private:
  double invP_, invU_, PoverU_;  // 1/P, 1/U, P/U
  // Maxima of the scaled figures, and of the unscaled squared friction residual.
  double nonpenetration_ = 0, complementarity_ = 0, frictionLaw2_ = 0;
};

}  // namespace Contact
}  // namespace Tribos
