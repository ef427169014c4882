// Tribos_SolveResult.hpp: the result of a solve as every method returns it
// (FETI with or without contact, the semismooth* method, the monolithic
// solve), and what the result check and the result files read: the nodal
// displacement, the contact nodes with their forces, slip and status, the
// KKT residuals of that result (Contact::resultKKT) and the verdict on it.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "Tribos_ContactConstraint.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_ResultKKT.hpp"

namespace Tribos {
namespace Contact {

struct ContactCounts {
  long long nodes = 0, active = 0, stick = 0, slip = 0;
};

// Node-wise results of the local contact nodes (rank-local), as written.
struct ContactNodeResults {
  std::vector<int> nodes;
  std::vector<Feti::ContactConstraint> constraint;  // frame, initial gap, master nodes, pair
  std::vector<double> frictionCoefficient;          // Coulomb F of the node's pair (0 for the other laws)
  // Forces on the slave node; slip: the relative tangential displacement;
  // gap: the current normal gap d - w.n.
  std::vector<double> normalForce, tangentialForce /*3 per node*/, slip /*3 per node*/, gap;
  std::vector<double> slipBound;  // g of the solution (Tresca, Coulomb F lambda_N), 0 when frictionless
  std::vector<int> status;        // 0 no contact, 1 stick, 2 slip
  // The relative displacement w at the previous load step (3 per node;
  // empty for a single step): the result check's friction law acts on the
  // slip since then.
  std::vector<double> previousRelative;
  // The nodes of glued pairs with their forces (not written: their relative
  // displacement is zero).
  std::vector<ContactNodeForce> bonded;
  // The forces as the result check takes them (contact and bonded nodes).
  std::vector<ContactNodeForce> forces() const;

  // What an engineer reads of contact node k, each computed here only:
  // the normal and the tangential traction, the node's force over its area
  // (ContactConstraint::area: int N_s dA of the slave surface, the dual
  // mortar integral D_s), 0 where the area is not positive;
  double normalTraction(size_t k) const;
  std::array<double, 3> tangentialTraction(size_t k) const;
  // the slip increment, the relative tangential displacement of the step
  // (w - w_prev projected on the tangent plane: slip less the tangential
  // part of previousRelative; the slip itself for a single step);
  std::array<double, 3> slipIncrement(size_t k) const;
  // the energy friction dissipates at the node in the step, -phi_T . s with
  // s the slip increment: the friction force opposes the slip, so the
  // product is g |s| >= 0 where the node slips and 0 where it sticks.
  double frictionDissipation(size_t k) const;
};

// The shared part of every method's result. Collective quantities (counts,
// kkt, verdict, the solver's report) are the same on every rank; u and
// contact are this rank's.
struct SolveResult {
  Fem::NodalVector u;           // nodal displacement at the nodes this rank holds
  ContactNodeResults contact;   // this rank's contact nodes (empty without contact)
  ContactCounts counts;         // over all ranks
  ResultKKT kkt;                // of u and the contact forces
  ResultVerdict verdict;        // converged, limit, stop reason (resultVerdict, once)
  double tolerance = 0;         // the solver's requested tolerance (what the verdict measures against)
  // The solver's own report.
  bool solverConverged = false;
  std::string solverReason;
  int iterations = 0;           // the method's own iterations (CG, outer, Newton)
  long long n_A = 0;            // applications of the dual operator F (0 for primal methods)
  double solveSeconds = 0;
  // The force the supports exert on the bodies at the Dirichlet dofs, zero
  // elsewhere (supportReactions), on u's layout; empty where the method
  // computes none.
  Fem::NodalVector reaction;
};

// The reaction of the supports: K u - f - phi at every Dirichlet dof (phi:
// the contact and bonded forces on the nodes, contactForces), 0 elsewhere:
// what the equilibrium K u = f + phi + r leaves to the Dirichlet conditions,
// the multiplier of their rows in Total FETI. Off the contact nodes it is
// K u - f. Ku, f on one layout, which holds the slave and master nodes of
// the rank's contact nodes; dirichlet as resultKKT takes it. Collective.
Fem::NodalVector supportReactions(const Fem::NodalVector& Ku, const Fem::NodalVector& f,
                                  const ContactNodeResults& contact, const std::map<long long, double>& dirichlet);

// counts over all ranks of the contact nodes in `nodes` (each held by one rank).
ContactCounts countContacts(const ContactNodeResults& nodes, const Comm& comm);

// The resultant of the contact forces on the slave side of a pair: the sum
// of the normal forces lambda_N and of the friction forces (a 3-vector).
struct PairForce {
  double normal = 0;
  std::array<double, 3> tangential{0, 0, 0};
};
// Per pair 0..numPairs-1 (ContactConstraint::pair), summed over all ranks.
std::vector<PairForce> pairForces(const ContactNodeResults& nodes, int numPairs, const Comm& comm);

// How the slave side of a pair moved against its partner in a step:
// the relative tangential displacement of the pair, the mean of its slave
// nodes' slip weighted by their areas (nodes of no positive area left out),
// and the energy its friction dissipated in the step (the sum of the nodes'
// frictionDissipation).
struct PairMotion {
  std::array<double, 3> relativeTangentialDisplacement{0, 0, 0};
  double area = 0;         // the sum of the weights: the pair's slave area
  double dissipation = 0;
};
// Per pair 0..numPairs-1, over all ranks. Collective.
std::vector<PairMotion> pairMotions(const ContactNodeResults& nodes, int numPairs, const Comm& comm);

}  // namespace Contact
}  // namespace Tribos
