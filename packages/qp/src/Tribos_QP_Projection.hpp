// Tribos_QP_Projection.hpp: the Euclidean projection onto a ball, the one
// formula behind every friction set of Tribos:
//   the Tresca disk ||x_T - c|| <= r of the QP solvers (ConstraintSet),
//   the friction-law residual r_T - P_g(r_T - c u_T) of a computed solution,
//   the prox of r ||.|| in the semismooth* approximation step
//   (prox(w) = w - P_r(w), Moreau).
//   P(v) = c + (v - c) min(1, r / ||v - c||)
// Inside the ball v is returned untouched (not recomputed from c), so a
// feasible point stays bit for bit where it is.
#pragma once

#include <cmath>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

// t in [0, 1] with P(v) = c + t (v - c), for n = ||v - c|| (r >= 0 expected;
// a negative r or n = 0 > r maps to the centre).
inline SC ballFactor(SC n, SC r) {
  if (!(n > r)) return 1;
  return n > 0 ? r / n : SC(0);
}

// Projection of (v1, v2) onto the disk ||(v1, v2) - (c1, c2)|| <= r.
inline void projectDisk(SC& v1, SC& v2, SC r, SC c1 = 0, SC c2 = 0) {
  const SC n = std::hypot(v1 - c1, v2 - c2);
  if (!(n > r)) return;
  const SC t = ballFactor(n, r);
  v1 = c1 + (v1 - c1) * t;
  v2 = c2 + (v2 - c2) * t;
}

// Projection of v[0..dim) onto the ball ||v|| <= r centred at 0 (a
// tangential force given by its 3D components in the tangent plane).
inline void projectBall(SC* v, int dim, SC r) {
  SC n2 = 0;
  for (int d = 0; d < dim; ++d) n2 += v[d] * v[d];
  const SC n = std::sqrt(n2);
  if (!(n > r)) return;
  const SC t = ballFactor(n, r);
  for (int d = 0; d < dim; ++d) v[d] *= t;
}

}  // namespace QP
}  // namespace Tribos
