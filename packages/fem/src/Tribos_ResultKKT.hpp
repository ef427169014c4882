// Tribos_ResultKKT.hpp: the KKT residuals of a contact result as the user
// gets it: the single-valued nodal displacement u and the nodal contact
// forces that are written to the result file. Every solution path (FETI,
// semismooth*, ...) reports these figures, computed here and only here, so
// that `converged` means the same thing whichever solver produced u.
//
// The body (assembled stiffness K, load f, Dirichlet conditions u_D = ubar)
// touches a rigid plane with outward face normal n and initial gap d:
//   equilibrium      K u - f - phi = 0             at every dof without a Dirichlet condition
//   Dirichlet        u_D = ubar
//   non-penetration  u.n <= d                      at every contact node
//   complementarity  lambda_N >= 0, lambda_N (d - u.n) = 0
//   friction         phi_T = P_g(phi_T - c s)      (|phi_T| <= g, phi_T opposes the slip s when |phi_T| = g)
// where phi = -lambda_N n + phi_T is the force of the plane on the body,
// s = u - (u.n) n the tangential displacement (the slip on a fixed plane),
// g the slip bound (Tresca: given; Coulomb: F lambda_N; frictionless: 0) and
// P_g the projection on the disk of radius g. Tangential components that a
// Dirichlet condition fixes are left out of the friction law (the reaction
// there is not a friction force).
//
// Normalisation (every figure is dimensionless and exists for any load):
//   equilibrium      ||(K u - f - phi)_free||_2 / max(||f||_2, ||K u||_2, ||phi||_2)
//   Dirichlet        max |u_D - ubar| / U
//   non-penetration  max (u.n - d)^+ / U
//   complementarity  max |min(lambda_N / P, (d - u.n) / U)|
//   friction         max ||phi_T - P_g(phi_T - (P/U) s)|| / P
// with U = max |u| and P the largest nodal force of the problem,
// max(|f|_inf, |K u|_inf, |phi|_inf), so a displacement-driven run (f = 0)
// and a run with no active contact (phi = 0) get finite, meaningful figures.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace Fem {

// A rigid plane: u.n <= gap at every contact node (n the outward unit normal
// of the body's contact face).
struct RigidPlane {
  std::array<double, 3> normal{0, 0, -1};
  double gap = 0.0;
};

// The friction law of the contact: Frictionless, Tresca (slipBound per
// node) or Coulomb (coefficient F, g = F lambda_N).
struct FrictionLaw {
  enum Kind { Frictionless, Tresca, Coulomb } kind = Frictionless;
  double coefficient = 0.0;
  static Kind parse(const std::string& name);  // "Frictionless" | "Tresca" | "Coulomb"
  static const char* name(Kind k);
};

// One contact node of the result (rank-local; every contact node is held by
// exactly one rank).
struct ContactNodeForce {
  int node = -1;                        // mesh node
  double normalForce = 0.0;             // lambda_N; the plane pushes the body with -lambda_N n
  std::array<double, 3> tangentialForce{0, 0, 0};  // phi_T, force of the plane on the body
  double slipBound = 0.0;               // Tresca g (force); ignored for the other laws
};

struct ResultKKT {
  double equilibrium = 0, dirichlet = 0, nonpenetration = 0, complementarity = 0, frictionLaw = 0;
  double displacementScale = 0, forceScale = 0;  // U and P above
  // The largest of the five figures and its name.
  double worst(std::string* which = nullptr) const;
};

// u, Ku, f: nodal vectors (3 per node), replicated on every rank. dirichlet:
// global dof (3 node + c) -> prescribed value. Collective over comm.
ResultKKT resultKKT(const std::vector<double>& u, const std::vector<double>& Ku, const std::vector<double>& f,
                    const std::map<long long, double>& dirichlet, const RigidPlane& plane, const FrictionLaw& law,
                    const std::vector<ContactNodeForce>& contact, const Comm& comm);

// The contact force phi (3 per node, replicated) of the rank-local contact
// nodes, summed over the ranks.
std::vector<double> contactForceVector(int numNodes, const RigidPlane& plane,
                                       const std::vector<ContactNodeForce>& contact, const Comm& comm);

// `converged` is a promise about the result the user gets: the solver
// stopped on its own test AND every KKT residual of the result is within
// factor times the requested tolerance. stopReason says why not (the
// solver's reason, or the residual that exceeds the limit), or the solver's
// reason for stopping when converged.
struct ResultVerdict {
  bool converged = false;
  double limit = 0;  // factor x tolerance
  std::string stopReason;
};
ResultVerdict resultVerdict(const ResultKKT& kkt, bool solverConverged, const std::string& solverReason,
                            double tolerance, double factor);

}  // namespace Fem
}  // namespace Tribos
