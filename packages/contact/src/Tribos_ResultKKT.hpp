// Tribos_ResultKKT.hpp: the KKT residuals of a contact result as the user
// gets it: the single-valued nodal displacement u and the nodal contact
// forces that are written to the result file. Every solution path (FETI,
// semismooth*, the monolithic solve) reports these figures, computed here and only here, so
// that `converged` means the same thing whichever solver produced u.
//
// The bodies (assembled stiffness K, load f, Dirichlet conditions u_D = ubar)
// meet in contact node by node: slave node s with the contact normal n, the
// initial gap d and the master nodes i with weights N_i (none against a
// rigid plane), relative displacement w = u_s - sum N_i u_i:
//   equilibrium      K u - f - phi = 0             at every dof without a Dirichlet condition
//   Dirichlet        u_D = ubar
//   non-penetration  w.n <= d                      at every contact node
//   complementarity  lambda_N >= 0, lambda_N (d - w.n) = 0
//   friction         phi_T = P_g(phi_T - c s)      (|phi_T| <= g, phi_T opposes the slip s when |phi_T| = g)
// where phi_s = -lambda_N n + phi_T is the force on the slave node, -N_i
// phi_s its reaction on master node i, s = v - (v.n) n the relative slip
// with v = w - w_prev the relative motion since the previous load step
// (w_prev = 0 for a single step: friction acts on the slip increment), g
// the slip bound (Tresca: given; Coulomb: F lambda_N; frictionless: 0) and
// P_g the projection on the disk of radius g. Tangential components that
// Dirichlet conditions fix at the slave node and its master nodes are left
// out of the friction law (the reaction there is not a friction force).
//
// Normalisation (every figure is dimensionless and exists for any load):
//   equilibrium      ||(K u - f - phi)_free||_2 / max(||f||_2, ||K u||_2, ||phi||_2)
//   Dirichlet        max |u_D - ubar| / U
//   non-penetration  max (w.n - d)^+ / U
//   complementarity  max |min(lambda_N / P, (d - w.n) / U)|
//   friction         max ||phi_T - P_g(phi_T - (P/U) s)|| / P
// with U = max |u| and P the largest nodal force of the problem,
// max(|f|_inf, |K u|_inf, |phi|_inf), so a displacement-driven run (f = 0)
// and a run with no active contact (phi = 0) get finite, meaningful figures.
#pragma once

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_ContactConstraint.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Contact {

// One contact node of the result (rank-local; every contact node is held by
// exactly one rank).
struct ContactNodeForce {
  int node = -1;                        // the slave mesh node
  double normalForce = 0.0;             // lambda_N; the slave node is pushed with -lambda_N n
  std::array<double, 3> tangentialForce{0, 0, 0};  // phi_T, friction force on the slave node
  double slipBound = 0.0;               // Tresca g (force); ignored for the other laws
  double frictionCoefficient = 0.0;     // Coulomb F; ignored for the other laws
  std::array<double, 3> normal{0, 0, -1};  // n, unit, pointing from the slave node into its partner
  double gap = 0.0;                     // d
  std::vector<std::pair<int, double>> master;  // master nodes and weights N_i; empty: a rigid plane
  std::vector<std::pair<int, double>> slave;   // the slave side u~_s = sum S_b u_b; empty: u_s (ContactConstraint)
  // Every node of the row with its coefficient (Feti::rowTerms).
  std::vector<std::pair<int, double>> terms() const { return Feti::rowTerms(node, slave, master); }
  // w at the previous load step: friction acts on the slip since then,
  // the tangential part of w - previousRelative (zero for a single step).
  std::array<double, 3> previousRelative{0, 0, 0};
  // A glued pair's node: w = 0 (its violation max|w|/U counts as
  // non-penetration), no complementarity, no friction law.
  bool bonded = false;
};

struct ResultKKT {
  double equilibrium = 0, dirichlet = 0, nonpenetration = 0, complementarity = 0, frictionLaw = 0;
  double displacementScale = 0, forceScale = 0;  // U and P above
  // The largest of the five figures and its name.
  double worst(std::string* which = nullptr) const;
};

// u, Ku, f: nodal vectors of one layout, whose ranks hold (at least) the
// slave and master nodes of their contact nodes; each figure is summed or
// maximized over the owned nodes of all ranks. dirichlet: global dof
// (3 node + c) -> prescribed value (read at the owned nodes and the contact
// nodes). Collective over the layout's communicator. states (optional):
// set to the state of each contact of `contact` (bonded ones included, as
// 1) under the law the check applies: 0 no contact (a normal force at most
// 1e-8 of the largest over the ranks), 1 stick, 2 slip (ContactKKT::slips).
ResultKKT resultKKT(const Fem::NodalVector& u, const Fem::NodalVector& Ku, const Fem::NodalVector& f,
                    const std::map<long long, double>& dirichlet, FrictionLaw law,
                    const std::vector<ContactNodeForce>& contact, std::vector<int>* states = nullptr);

// The contact force phi of the rank-local contact nodes and their reactions
// on the master nodes, summed over the ranks, at the nodes of layout (which
// must hold every slave and master node of contact). Collective.
Fem::NodalVector contactForces(const RCP<const Fem::NodalLayout>& layout, const std::vector<ContactNodeForce>& contact);

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

}  // namespace Contact
}  // namespace Tribos
