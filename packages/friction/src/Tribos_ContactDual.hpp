// Tribos_ContactDual.hpp: the dual contact problem the friction algorithms
// solve, with no knowledge of where it comes from (FETI, FCLIB, ...):
//
//   min 1/2 x'Ax - b'x   s.t.  x_N,k >= l_k                      (normal, one per contact k)
//                              ||(x_T1,k, x_T2,k) - c_k|| <= g_k  (tangential pair)
//                              G x = 0                            (optional)
//
// The normal contact force of contact k is x_N,k + normalOffset_k; the
// tangential force is x_T,k - c_k (the centre c_k = -lambda~_T,k is zero
// unless a particular solution of G lambda = e shifted the problem:
// HomogenizationTransform). A
// contact whose tangential direction is fixed by a Dirichlet condition has
// -1 for that row: one remaining direction gives the interval
// |x_T - c| <= g_k, none gives no friction constraint. Tresca
// problems give g; Coulomb problems give the friction coefficients F_k and
// g_k = F_k (normal force). The algorithms' defaults (rho, M) assume the
// problem is scaled so that ||A|| is about 1: ScalingTransform
// (Tribos_DualTransform.hpp) does that for FETI and FCLIB problems.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "Tribos_QP_AugmentedHessian.hpp"
#include "Tribos_QP_ConstraintSet.hpp"
#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Friction {

struct ContactDual {
  RCP<const Operator> A;
  RCP<const Vector> b;
  RCP<const QP::EqualityConstraint> G;  // null: no equality constraint
  std::vector<LO> normalRows;           // local index of x_N,k
  std::vector<LO> tangentRows;          // local indices of x_T1,k, x_T2,k (2 per contact; -1: direction fixed)
  std::vector<SC> tangentCenter;        // c_k (2 per contact), empty: all zero
  std::vector<SC> normalLower;          // l_k (usually 0), local
  std::vector<SC> normalOffset;         // local
  std::vector<SC> slipBound;            // Tresca g_k, local
  std::vector<SC> frictionCoefficient;  // Coulomb F_k, local
  // Whether the rows of no contact alone determine the multiplier of G x = 0
  // (FETI: the Dirichlet conditions hold every body). false: some rigid
  // motion is held only by contact rows (a body held by its contact), and
  // which of them hold it depends on the contact state.
  bool heldWithoutContact = true;
  // The right-hand side that relative tolerances refer to; null: b. A contact
  // problem gives b without the initial gaps, which a solution with no
  // active contact never feels: a large gap must not loosen the solve. The
  // transforms (Tribos_DualTransform.hpp) map it as they map b.
  RCP<const Vector> bReference;
  // A's joint application of A + rho G'G when G'G = I - P for the projector
  // P inside A (set by ProjectionTransform for FETI's orthonormal coarse
  // constraint, kept consistent by every later transform); null: none.
  RCP<const QP::ProjectorComplement> jointHessian;
  // A as a dense n x n column-major matrix on every rank (collective), when
  // its owner forms it faster than n applications (FETI's F from its dense
  // blocks); any matrix that equals A on ker G will do. Empty function or
  // empty result: none. ScalingTransform scales it; ProjectionTransform keeps
  // it (on ker G, PAP = A).
  std::function<std::vector<double>()> denseA;
  // An estimate of ||A|| from above (QP::estimateNorm's, its safety factor
  // included) and the operator it belongs to: ScalingTransform has it for the
  // A it leaves, so the solvers need not repeat its power iterations. It
  // counts only while normAOf is A: a transform that replaces A leaves it
  // stale, and hessianNorm estimates again.
  RCP<const Operator> normAOf;
  SC normAEstimate = 0;
  // Preconditioners of A by name (FETI's "Lumped", "Dirichlet": an
  // approximate inverse of A on ker G whose range lies in ker G), for the
  // methods that solve linear systems with A by conjugate gradients (the
  // Newton method of Tribos_NewtonPCG.hpp). Empty function or null result:
  // none of that name. ScalingTransform scales it; the other transforms
  // leave it (on ker G it is already what the projected problem needs).
  std::function<RCP<const Operator>(const std::string& name)> preconditioner;

  RCP<const Map> map() const { return b->getMap(); }
  // The scale of relative tolerances: ||bReference||, or ||b|| where there
  // is no reference or it vanishes while b does not (a problem driven by
  // its gaps or prescribed values alone, e.g. a time step's projection
  // from rest onto a moved support: a zero scale would ask for an exact
  // solution and the solver would never stop). Collective.
  SC normB() const {
    const SC reference = bReference.is_null() ? 0.0 : bReference->norm2();
    return reference > 0 ? reference : b->norm2();
  }
  int numLocalContacts() const { return static_cast<int>(normalRows.size()); }
  // Whether some rank holds Coulomb contacts (collective): a rank without
  // contacts has no friction coefficients whatever the law, so a decision
  // by the law must be taken from all ranks alike.
  bool coulombOnSomeRank() const;
  // ||A|| from above: the estimate above while it belongs to A, else
  // `powerSteps` power iterations (collective; n_A counts them).
  SC hessianNorm(int powerSteps, long& n_A) const;

  // Omega(g): the product set with slip bounds g (local, one per contact).
  QP::ConstraintSet constraintSet(const std::vector<SC>& g) const;
  // Normal forces of the local contacts.
  std::vector<SC> normalForce(const Vector& x) const;
  // Coulomb slip bound g_k = F_k max(normal force_k, 0).
  std::vector<SC> coulombSlipBound(const Vector& x) const;
  // Masks of the local indices of the normal + equality block (lambda_c: every
  // index that is not tangential) and of the tangential block (lambda_t).
  std::vector<char> normalBlockMask() const;
  std::vector<char> tangentBlockMask() const;
  // Checks sizes and that every index is in range; throws naming the entry.
  void check() const;
};

// ||a - b|| over all ranks for local vectors.
SC globalNorm(const std::vector<SC>& a, const Comm& comm);
SC globalDistance(const std::vector<SC>& a, const std::vector<SC>& b, const Comm& comm);

}  // namespace Friction
}  // namespace Tribos
