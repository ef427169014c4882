// Tribos_FCLIB_Accuracy.hpp: the accuracy measure used to compare frictional
// contact solvers on FCLIB problems, i.e. the "natural map" error of Siconos'
// fc3d solvers.
//
// Per contact i, with local frame (N, T1, T2), friction coefficient mu_i,
// force r_i and relative velocity u_i:
//   u~_i   = u_i + [mu_i ||u_T,i||, 0, 0]        (De Saxce modified velocity)
//   phi_i  = r_i - P_K(r_i - u~_i)               K = {||r_T|| <= mu_i r_N}
// and the error is ||phi|| (2-norm of the stacked 3nc vector) divided by a
// normalizer: ||q|| (Siconos' relative error; for a global problem q is the
// reduced q = H' M^{-1} f + w), or max(||q||, ||r||, ||u||), which stays
// meaningful when q is small compared with the solution.
// phi = 0 exactly when (r, u) satisfies Coulomb's law with the De Saxce
// complementarity; the measure is 0 at an exact solution whatever its scale.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "Tribos_FCLIB.hpp"

namespace Tribos {
namespace FCLIB {

// Euclidean projection of r = (rN, rT1, rT2) onto the cone
// K_mu = {||r_T|| <= mu r_N}, in closed form:
//   inside K:                r
//   in the polar cone (mu ||r_T|| <= -r_N):   0
//   otherwise: onto the boundary ray, t = (r_N + mu ||r_T||) / (1 + mu^2),
//              result (t, mu t r_T / ||r_T||).
// mu = 0 gives the half line {r_T = 0, r_N >= 0}.
std::array<double, 3> projectOntoCoulombCone(const std::array<double, 3>& r, double mu);

struct NaturalMapError {
  double absolute = 0.0;        // ||phi||
  double relativeToQ = 0.0;     // ||phi|| / ||q|| (Siconos' fc3d error)
  double relativeToMax = 0.0;   // ||phi|| / max(||q||, ||r||, ||u||)
  double normQ = 0.0, normR = 0.0, normU = 0.0;
};

// The measure for given r and u (3nc each) and the vector q used for scaling.
// A normalizer below the smallest positive double is replaced by 1, so that a
// problem with q = 0 reports the absolute error instead of inf/nan; a
// non-finite entry anywhere makes the relative errors nan (never 0).
NaturalMapError naturalMapError(const std::vector<double>& r, const std::vector<double>& u,
                                const std::vector<double>& mu, const std::vector<double>& q);

// Local problem: u = W r + q.
NaturalMapError naturalMapError(const LocalProblem& problem, const std::vector<double>& r);

// Applies M^{-1}: solveM(b, x) sets x such that M x = b. The caller supplies it
// (factorization, iterative solver...), this package has no linear solver.
using SolveM = std::function<void(const std::vector<double>& b, std::vector<double>& x)>;

struct GlobalReduction {
  std::vector<double> v;  // M^{-1} (H r + f)
  std::vector<double> u;  // H' v + w
  std::vector<double> q;  // H' M^{-1} f + w, the reduced local q
};

// v and u for a given r, and the reduced q, through two solves with M.
GlobalReduction reduceGlobal(const GlobalProblem& problem, const std::vector<double>& r,
                             const SolveM& solveM);

// Global problem: the local measure after the reduction above (G, if present,
// is not handled and makes this throw).
NaturalMapError naturalMapError(const GlobalProblem& problem, const std::vector<double>& r,
                                const SolveM& solveM);

}  // namespace FCLIB
}  // namespace Tribos
