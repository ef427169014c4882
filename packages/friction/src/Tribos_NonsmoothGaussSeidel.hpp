// Tribos_NonsmoothGaussSeidel.hpp: Coulomb friction on an explicit local
// problem by nonsmooth Gauss-Seidel (NSGS, Jean and Moreau): sweeps over the
// contacts, each contact's Coulomb problem solved exactly with the others'
// forces fixed (docs/semismooth.md, "NSGS").
//
// The problem is FCLIB's local one: u = W r + q, contact c in rows 3c
// (normal) and 3c+1, 3c+2 (tangential), friction coefficient mu_c, Coulomb's
// law between r_c and u_c. One step of a sweep, for contact c with
//   q~_c = q_c + sum_{d != c} W_cd r_d,   u_c = W_cc r_c + q~_c,
// solves the 3 x 3 problem in r_c:
//   take-off  q~_N >= 0                                  r_c = 0;
//   stick     r_c = -W_cc^-1 q~_c in the cone             u_c = 0;
//   slip      otherwise, Newton on the Alart-Curnier function of the contact
//             (AlartCurnier::blocks, the function of the global Newton
//             method) with rho_N = 1 / W_NN, rho_T = 2 / (W_TT1 + W_TT2) and an
//             Armijo line search, from the previous r_c.
// The first two are exact; the third converges to round-off in a few steps.
//
// Each sweep costs one pass over W: its CSR rows as given for the first
// sweeps, a copy in 3 x 3 blocks by contact from the eighth on. The relative
// change of r over a sweep is computed every sweep; when it is at most the
// tolerance (and every 64 sweeps), u = W r + q is formed and the stopping
// measure (by
// default ||Phi(r)|| / ||rho q||, the Alart-Curnier residual; FCLIB: the
// natural-map error ||F_nat|| / ||q||) decides. NSGS needs W's entries: it is
// registered for explicit problems only (kExplicitCoulomb), not for the FETI
// dual, whose operator is only applied.
//
// Convergence: NSGS is a block Gauss-Seidel method for a nonmonotone
// problem; no general theorem covers it (it converges for frictionless
// contact with W positive definite, the block coordinate descent of a convex
// QP), but it is the workhorse of multibody codes because each sweep is
// cheap and its iterations are robust on singular W.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <vector>

#include "Tribos_FrictionSolver.hpp"
#include "Tribos_LocalCsr.hpp"

namespace Tribos {
namespace Friction {

// The friction law an algorithm accepts (FrictionSolverRegistry) when it
// needs the entries of the Delassus operator: FCLIB's local problems.
inline const char* const kExplicitCoulomb = "Coulomb (explicit W)";

// u = W r + q with Coulomb's law per contact (rows 3c, 3c+1, 3c+2).
struct ExplicitCoulombProblem {
  CsrView W;             // 3 nc x 3 nc
  const double* q = nullptr;
  const double* mu = nullptr;
  int contacts = 0;
};

class NonsmoothGaussSeidel : public SingleLoopSolver {
 public:
  explicit NonsmoothGaussSeidel(const Teuchos::ParameterList& params);
  // Refused: the FETI dual is applied, not stored (use Algorithm2 or Semismooth Newton).
  FrictionStatus solve(const ContactDual& dual, Vector& x) override;
  // r: initial guess on input, solution on output; u = W r + q of the
  // returned r (formed from W at the last check). The stopping measure's
  // last call is on exactly the returned (r, u).
  FrictionStatus solve(const ExplicitCoulombProblem& problem, std::vector<double>& r, std::vector<double>& u) const;
  static RCP<const Teuchos::ParameterList> validParameters();

  // The stopping test: measure(r, u) <= Relative Tolerance.
  using Measure = std::function<double(const std::vector<double>& r, const std::vector<double>& u)>;
  void setStoppingMeasure(Measure m) { measure_ = std::move(m); }

 private:
  // The list's values, read once per change: a lookup by name costs more
  // than a contact's step, and a solve of a small problem takes a few.
  void readSettings();
  void parametersChanged() override { readSettings(); }
  double tol_ = 0, localTol_ = 0;
  int maxSweeps_ = 0, localMaxIt_ = 0;
  Measure measure_;
};

}  // namespace Friction
}  // namespace Tribos
