#include "Tribos_ContactKKT.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_QP_Projection.hpp"

namespace Tribos {
namespace Contact {

ContactKKT::ContactKKT(double forceScale, double displacementScale)
    : invP_(1.0 / forceScale), invU_(1.0 / displacementScale), PoverU_(forceScale / displacementScale) {
  TRIBOS_REQUIRE(forceScale > 0 && displacementScale > 0, "ContactKKT: the force scale P = "
                                                               << forceScale << " and the displacement scale U = "
                                                               << displacementScale << " must be > 0");
}

void ContactKKT::add(double lambdaN, double gap, const double* phiT, const double* slip, int dim, double g) {
  TRIBOS_REQUIRE(dim >= 0 && dim <= 3, "ContactKKT::add: dim = " << dim << " outside [0, 3]");
  nonpenetration_ = std::max(nonpenetration_, std::max(-gap, 0.0) * invU_);
  complementarity_ = std::max(complementarity_, std::abs(std::min(lambdaN * invP_, gap * invU_)));
  // phi_T is the projection of phi_T - (P/U) s onto the disk of radius g.
  double proj[3];
  for (int d = 0; d < dim; ++d) proj[d] = phiT[d] - PoverU_ * slip[d];
  QP::projectBall(proj, dim, g);
  double r2 = 0;
  for (int d = 0; d < dim; ++d) r2 += (phiT[d] - proj[d]) * (phiT[d] - proj[d]);
  frictionLaw2_ = std::max(frictionLaw2_, r2);  // one square root, at the end
}

bool ContactKKT::slips(const double* phiT, const double* slip, int dim, double g) const {
  if (g <= 0) return true;
  double z2 = 0;
  for (int d = 0; d < dim; ++d) {
    const double z = phiT[d] - PoverU_ * slip[d];
    z2 += z * z;
  }
  return z2 > g * g;
}

}  // namespace Contact
}  // namespace Tribos
