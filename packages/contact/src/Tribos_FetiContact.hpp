// Tribos_FetiContact.hpp: a FETI contact problem as a ContactDual for the
// friction algorithms, and the checks of its primal-dual solution.
//
// TFETI's dual problem goes through the transform chain of friction
// (Tribos_DualTransform.hpp): homogenization with FETI's particular solution
// lambda~ (lambda = lambda~ + x), the coarse projector P, the scaling s:
//   min 1/2 x's PFPx - x's P(h - F lambda~)  s.t.  G^ x = 0, x_N >= -lambda~_N,
//   ||x_T,k + lambda~_T,k|| <= g_k
// (lambda~ vanishes on the contact rows when the equality rows hold every
// rigid motion). G^ = L^-1 G (GG' = LL') is the orthonormal constraint of
// FETI's coarse space, which factors GG' for P and lambda~ anyway: SMALBE's
// penalty rho/2 ||G^x||^2 = rho/2 x'Qx, Q = I - P.
#pragma once

#include <string>
#include <functional>
#include <map>
#include <vector>

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_ContactDual.hpp"
#include "Tribos_ContactSearch.hpp"
#include "Tribos_DualTransform.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_FetiDual.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_SolveResult.hpp"

namespace Tribos {
namespace Contact {

struct FrictionSpec {
  FrictionLaw law = FrictionLaw::Frictionless;
  double coefficient = 0.0;          // Coulomb F
  double slipBoundTraction = 0.0;    // Tresca: traction bound, times nodal area gives g_k
};
// Throws Tribos::Error naming the entry: a law out of the enum, a coefficient or
// slip bound traction that is negative or not finite.
void checkFriction(const FrictionSpec& friction);

// The friction of each contact pair (Feti::ContactConstraint::pair); a list
// of one applies to every pair.
using PairFriction = std::vector<FrictionSpec>;
const FrictionSpec& frictionOfPair(const PairFriction& friction, int pair);
// The law the outer algorithm solves for all pairs at once: Coulomb when a
// pair is Coulomb (a frictionless pair has F = 0), else Tresca when a pair
// is Tresca (a frictionless pair has g = 0), else Frictionless. Tresca and
// Coulomb pairs in one run are refused (no outer algorithm solves both).
FrictionLaw runLaw(const PairFriction& friction);

// Refuses (Tribos::Error naming the bodies, the free motions and the pairs
// acting within them) a group of bodies that can move rigidly as a whole.
// A group: bodies joined by shared nodes or by the constraints of pairs
// between them; pairs within a group exert internal forces only, so the
// group's rigid motions are held by its Dirichlet dofs and its constraints
// against rigid planes alone (their normals; their tangents too where the
// pair has friction or is glued). A motion none of these touches leaves the
// displacement undetermined whatever the contact does, e.g. a body whose one
// pair joins two of its own surfaces. (Relative motions of the bodies of a
// group are found later, by the coarse space.) Then each body alone, the
// others staying (requireEveryBodyHeldAlone): a pair whose master surface
// does not face its slave is named there. dirichlet: constrained dofs
// 3 n + c of the mesh's nodes.
void requireEveryBodyHeld(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                          const std::vector<Contact::ContactPair>& pairs, const PairFriction& friction,
                          const std::vector<Feti::ContactConstraint>& constraints);

// Refuses (Tribos::Error naming the node) Dirichlet values that make a
// contact node with friction slide along a tangential axis they fix at the
// node and its master nodes (Fem::requireNoPrescribedSlip): the rows leave
// that axis out, so its friction force would hide in the reaction.
// position: a slave node's coordinates by its mesh number, for the message.
void requireNoPrescribedSlip(const std::vector<Feti::ContactConstraint>& contact, const PairFriction& friction,
                             const std::map<long long, double>& dirichlet,
                             const std::function<std::array<double, 3>(int)>& position);

// A solved FETI contact problem: multipliers, primal displacement, the outer
// algorithm's status and the applications of F the solve took.
struct FetiContactSolution {
  RCP<Vector> x;       // the unknown of the ContactDual (lambda = lambda~ + x)
  RCP<Vector> lambda, u;
  Friction::FrictionStatus status;
  long long n_A = 0;
  double requestedTolerance = 0;  // the outer algorithm's (what the result check measures against)
  Friction::WarmStart warmStart;  // the outer algorithm's final state, for the next load step
};

class ConjugateProjectionTransform;  // Tribos_FetiContact.cpp

class FetiContactProblem {
 public:
  // normPFP: ||PFP|| when known (the same problem at another load, norm());
  // 0 estimates it by power steps.
  FetiContactProblem(RCP<const Feti::FetiDual> dual, const PairFriction& friction, double normPFP = 0);
  FetiContactProblem(RCP<const Feti::FetiDual> dual, const FrictionSpec& friction)
      : FetiContactProblem(dual, PairFriction{friction}) {}
  const Friction::ContactDual& contactDual() const { return cd_; }
  const Feti::FetiDual& fetiDual() const { return *dual_; }
  // lambda = lambda~ + x (the chain's back map)
  RCP<Vector> multipliers(const Vector& x) const;
  // Solves by the outer algorithm named (FrictionSolverFactory) from x = 0,
  // with the sublists "Algorithm 1", "MSA", "Algorithm 2" of solverParams;
  // or from start (a previous solution's x) with the requested tolerance
  // tolerance instead of the list's (when > 0).
  // warm: where a solve of a nearby problem (the previous load step) left
  // the outer algorithm's state (FetiContactSolution::warmStart).
  // With F from single-precision blocks (DualOperator::rounded) the
  // right-hand side is corrected by the exact F at the start, and a
  // converged solve whose rounding defect could still matter at the
  // tolerance is repeated with it corrected at its solution, up to
  // kRoundingCorrections times (defect correction, docs/feti.md): the
  // solution is the exact problem's, at the tolerance asked for.
  FetiContactSolution solve(const std::string& outerAlgorithm, const Teuchos::ParameterList& solverParams,
                            RCP<Teuchos::FancyOStream> out = Teuchos::null, const Vector* start = nullptr,
                            double tolerance = 0, const Friction::WarmStart* warm = nullptr) const;
  // The start x of the ContactDual for multipliers lambda (a previous load
  // step's): lambda - lambda(0) projected onto Ker G, so that it meets the
  // equality constraint G x = 0 of this problem's loads.
  RCP<Vector> startFrom(const Vector& lambda) const;
  // The solverParams solve() accepts: the outer algorithms' sublists with
  // their defaults and documentation (FrictionSolverFactory::addValidParameters).
  static RCP<const Teuchos::ParameterList> getValidParameters();
  // The factor s of the scaled dual problem (s PFP, s P(h - F lambda~)), s = 1/||PFP||.
  SC scale() const { return scaling_->scale(); }
  SC norm() const { return scaling_->norm(); }

 private:
  // Local dual rows: equality rows plus the normal and/or tangential rows.
  // tangent: the tangential rows of the contacts with friction (g_k > 0 or F_k > 0).
  std::vector<char> rowMask(bool normal, bool tangent) const;
  // Equality rows plus the contact rows where B u = c holds at lambda.
  std::vector<char> activeRows(const Vector& lambda, const std::vector<double>& g) const;
  // Refuses a body that its contact cannot hold (throws naming the motion).
  void checkHeldByContact() const;
  // One solve of the transformed problem cd (cd_, or cd_ with b corrected):
  // x, lambda and the solver's status; no primal yet.
  FetiContactSolution solveDual(const Friction::ContactDual& cd, const std::string& outerAlgorithm,
                                const Teuchos::ParameterList& solverParams, RCP<Teuchos::FancyOStream> out,
                                const Vector* start, double tolerance, const Friction::WarmStart* warm) const;
  // s D P (F~ - F) lambda (P: the coarse or the conjugate projection, D the
  // row scaling, where present): the rounding defect at lambda as the
  // transformed problem's b sees it.
  RCP<Vector> roundingShift(const Vector& lambda) const;
  static constexpr int kRoundingCorrections = 3;
  // sol.u from sol.lambda (FetiDual::recoverPrimal), the rigid motion fixed
  // by the rows where B u = c holds; a body the solution leaves unheld makes
  // the solve a failed one, its reason naming the free motions.
  void recoverPrimal(FetiContactSolution& sol) const;

  // PFP, P(h - F lambda~) -> s PFP, s P(h - F lambda~) (||A|| = 1); the last
  // of transforms_.
  RCP<Friction::ScalingTransform> scaling_;
  Friction::DualTransformChain transforms_;
  // lambda = lambda_U + P mu for positive definite subdomains (null: none).
  RCP<ConjugateProjectionTransform> conjugate_;
  // The scale of each local contact's multipliers in a scaled dual (empty:
  // not scaled; Friction::DiagonalScalingTransform).
  std::vector<double> contactScale_, rowScale_;
  RCP<const Feti::FetiDual> dual_;
  Friction::ContactDual cd_;
};

// The local contact nodes of the result: forces from lambda, slip and gap
// from the written (nodal, single-valued) displacement. g: the slip bound of
// the solution (local, one per contact node), empty for frictionless.
// previous: the nodal displacement of the previous load step (none: a
// single step), whose relative displacements the friction law starts from.
// The states (status) are set by resultKKT, from the law it checks.
ContactNodeResults contactResults(const Feti::FetiProblem& problem, const Fem::NodalVector& uNodal,
                                  const Vector& lambda, const std::vector<double>& g, const PairFriction& friction,
                                  const Fem::NodalVector* previous = nullptr);

// The forces between glued bodies at the local bonded nodes, from lambda.
std::vector<Contact::ContactNodeForce> bondedForces(const Feti::FetiProblem& problem, const Vector& lambda);

// The KKT residuals (Contact::resultKKT) of the written result: the nodal
// displacement and the contact forces (none for a problem without contact);
// sets contact.status (no contact, stick, slip under the law checked) and
// counts over all ranks.
Contact::ResultKKT resultKKT(const Feti::FetiProblem& problem, const Fem::NodalVector& uNodal,
                             ContactNodeResults& contact, const PairFriction& friction, ContactCounts& counts);

}  // namespace Contact
}  // namespace Tribos
