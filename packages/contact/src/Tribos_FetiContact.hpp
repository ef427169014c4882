// Tribos_FetiContact.hpp: a FETI contact problem as a ContactDual for the
// friction algorithms, and the checks of its primal-dual solution.
//
// With lambda = lambda~ + x, G lambda~ = e and lambda~ supported on equality
// rows, the dual problem becomes
//   min 1/2 x'PFPx - x'P(h - F lambda~)  s.t.  G^ x = 0, x_N >= 0, ||x_T,k|| <= g_k
// (G^ = L^-1 G orthonormal, so SMALBE's penalty rho/2 ||G^x||^2 = rho/2 x'Qx).
#pragma once

#include <string>
#include <vector>

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_ContactDual.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_FetiDual.hpp"

namespace Tribos {
namespace Contact {

struct FrictionSpec {
  std::string law = "Frictionless";  // Frictionless | Tresca | Coulomb
  double coefficient = 0.0;          // Coulomb F
  double slipBoundTraction = 0.0;    // Tresca: traction bound, times nodal area gives g_k
};

// A solved FETI contact problem: multipliers, primal displacement, the outer
// algorithm's status and the applications of F the solve took.
struct FetiContactSolution {
  RCP<Vector> x;       // the unknown of the ContactDual (lambda = lambda~ + x)
  RCP<Vector> lambda, u;
  Friction::FrictionStatus status;
  long long n_A = 0;
};

class FetiContactProblem {
 public:
  FetiContactProblem(RCP<const Feti::FetiDual> dual, const FrictionSpec& friction);
  const Friction::ContactDual& contactDual() const { return cd_; }
  const Feti::FetiDual& fetiDual() const { return *dual_; }
  // lambda = lambda~ + x
  RCP<Vector> multipliers(const Vector& x) const;
  // Solves by the outer algorithm named (FrictionSolverFactory) from x = 0,
  // with the sublists "Algorithm 1", "MSA", "Algorithm 2" of solverParams.
  FetiContactSolution solve(const std::string& outerAlgorithm, const Teuchos::ParameterList& solverParams,
                            RCP<Teuchos::FancyOStream> out = Teuchos::null) const;
  // The factor s of the scaled dual problem (s PFP, s P(h - F lambda~)), s = 1/||PFP||.
  SC scale() const { return scale_; }

 private:
  SC scale_ = 1.0;
  RCP<const Feti::FetiDual> dual_;
  Friction::ContactDual cd_;
};

// Relative residuals of a primal-dual solution (u, lambda) computed from the
// primal quantities, independently of any solver's stopping test.
struct KKTResiduals {
  double equilibrium = 0;      // ||K u - f + B'lambda|| / ||f||
  double equality = 0;         // ||B_E u - c_E|| / ||u||  (gluing and Dirichlet rows)
  double nonpenetration = 0;   // max (N u - d)^+ / max |u|
  double complementarity = 0;  // max |min(lambda_N, c (d - N u))| / max |lambda|,  c = max |lambda| / max |u|
  double frictionLaw = 0;      // max ||lambda_T - P_B(g)(lambda_T + c T u)|| / max |lambda|
};

struct ContactCounts {
  long long nodes = 0, active = 0, stick = 0, slip = 0;
};

// Node-wise results of the local contact nodes (rank-local).
struct ContactNodeResults {
  std::vector<int> nodes;
  std::vector<double> normalForce, tangentialForce /*3 per node*/, slip /*3 per node*/, gap;
  std::vector<int> status;  // 0 no contact, 1 stick, 2 slip
};

// g: the slip bound of the solution (local, one per contact node), empty for frictionless.
KKTResiduals checkKKT(const Feti::FetiProblem& problem, const Vector& u, const Vector& lambda,
                      const std::vector<double>& g);
ContactNodeResults contactResults(const Feti::FetiProblem& problem, const Vector& u, const Vector& lambda,
                                  const std::vector<double>& g, ContactCounts& counts);

}  // namespace Contact
}  // namespace Tribos
