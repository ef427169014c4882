// Tribos_FetiSolve.hpp: a FETI problem solved the way Tribos solves it, for
// the driver and for applications that assemble their own subdomains
// (FetiProblem's second constructor) alike:
//   no contact: projected CG on the dual problem (list "FETI"/"Projected CG");
//   contact:    the outer algorithm "Outer Algorithm" (Tresca: Algorithm 1;
//               Coulomb: Algorithm2 or MSA+Algorithm1) on the transformed
//               dual problem (FetiContactProblem);
// then the result an application writes: the nodal displacement, the
// contact forces, slip and status per contact node, the KKT residuals of
// that result node by node (Contact::resultKKT), and the verdict: converged
// means the solver stopped on its test AND the residuals are within
// "Result Check Factor" times its requested tolerance.
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "Tribos_FetiContact.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_SolveResult.hpp"

namespace Tribos {
namespace Contact {

// The shared result (Tribos_SolveResult.hpp) and what FETI adds to it.
struct FetiSolveResult : SolveResult {
  RCP<Vector> lambda;           // the multipliers of B (this rank's rows)
  RCP<Vector> primal;           // the subdomain displacements (FETI's primal vector)
  int rounds = 1;               // contact: solves until the result met the check (Result Check Rounds)
  std::string outerAlgorithm;            // empty without contact
  std::string handover;                  // why Auto's Newton solve handed over to Algorithm2 (empty: it did not)
  Friction::FrictionStatus status;       // contact: the outer algorithm's status
  double relativeResidual = 0;           // projected CG
  // The dual operator and the coarse problem, for performance reports: all
  // applications of F (the solver's n_A, the power iterations, the setup's)
  // and their wall time on this rank; the coarse dimension (6S in TFETI) and
  // the memory of its sparse Cholesky factors on this rank.
  long long F_applications = 0;
  double F_seconds = 0;
  int coarseSize = 0;
  double coarseFactorMb = 0;
};

// The outer algorithm of a contact run: `requested`, or for "Auto" (the
// default) the one that suits the run's law (runLaw), so that a user who
// names a law need not name an algorithm too: for Coulomb friction the
// matrix-free Semismooth Newton, which takes from 0.28 to 0.74 of Algorithm
// 2's applications of F from rest on the seed brick up to a million dofs, a
// fraction of them in a load step that starts near its solution, and from
// 0.2 to 0.5 of them where the contact alone holds a body (two blocks, a lap
// joint, a sphere loaded by forces; docs/semismooth.md); Algorithm1 for
// Tresca friction and frictionless contact. A Newton solve chosen by Auto
// that stops without converging, or whose result misses its check, is
// followed by Algorithm2 (solveFeti), and the result says why
// (FetiSolveResult::handover).
std::string outerAlgorithmFor(const std::string& requested, const PairFriction& friction);
constexpr const char* kAutoOuterAlgorithm = "Auto";

// The parameters solveFeti reads, with defaults and documentation:
// "Outer Algorithm", "Result Check Factor", the outer algorithms' sublists
// "Algorithm 1", "MSA", "Algorithm 2", and "FETI"/"Projected CG". Other
// entries of the list are left to their owners.
RCP<const Teuchos::ParameterList> fetiSolveParameters();

// Solves problem; friction: the law of each contact pair (one for all;
// ignored without contact). Collective. Throws Tribos::Error for parameters
// that are not valid (naming them) and CollectiveError for a body that
// neither its Dirichlet rows nor its contact hold.
FetiSolveResult solveFeti(const RCP<const Feti::FetiProblem>& problem, const PairFriction& friction,
                          const Teuchos::ParameterList& params, RCP<Teuchos::FancyOStream> out = Teuchos::null);
inline FetiSolveResult solveFeti(const RCP<const Feti::FetiProblem>& problem, const FrictionSpec& friction,
                                 const Teuchos::ParameterList& params, RCP<Teuchos::FancyOStream> out = Teuchos::null) {
  return solveFeti(problem, PairFriction{friction}, params, out);
}

// A FETI problem solved at a sequence of loads, a
// quasi-static load history (docs/load_history.md): K, its factors, B, F's
// operator and the coarse space are built once and serve every step; each
// step starts from the previous step's multipliers, and its friction acts
// on the slip since the previous step (FetiProblem::setTangentialOffset),
// contact on the gap of the reference geometry.
class FetiLoadSteps {
 public:
  // params as solveFeti takes them; validated here. Collective.
  FetiLoadSteps(const RCP<Feti::FetiProblem>& problem, const PairFriction& friction,
                const Teuchos::ParameterList& params, RCP<Teuchos::FancyOStream> out = Teuchos::null);
  // The next step at loads (FetiProblem::setLoads). The first step is the
  // static solve of solveFeti. Collective.
  FetiSolveResult solve(const Fem::LoadCase& loads);
  // The next step at the loads the problem now has (an application's,
  // FetiProblem::setRightHandSides); the first is the static solve.
  // Collective.
  FetiSolveResult solveNext();
  // A history continued from a step solved elsewhere (an earlier run's last
  // complete step, read back from its result): the next solve acts on the
  // slip since uPrevious, a nodal displacement on problem->nodalLayout().
  // Every subdomain copy of a node takes the node's value (the copies of a
  // solved step agree to the gluing tolerance), and the next step starts
  // from zero multipliers: its result is the one the uninterrupted history
  // gives, reached in other iterations. Collective.
  void resumeFrom(const Fem::NodalVector& uPrevious);
  // The problem's K has new values (FetiProblem::setStiffness): F and its
  // norm are formed again at the next step; the history goes on.
  void stiffnessChanged();
  int completedSteps() const { return steps_; }

 private:
  RCP<Feti::FetiProblem> problem_;
  PairFriction friction_;
  Teuchos::ParameterList params_;
  RCP<Teuchos::FancyOStream> out_;
  RCP<const Feti::FetiDual> operators_;  // the first step's dual: F and the coarse space
  int steps_ = 0;
  double normPFP_ = 0;
  RCP<const Vector> lambda_, primal_;  // of the previous step (lambda_ empty after resumeFrom)
  RCP<const Vector> lambdaBefore_;      // the multipliers of the step before it
  RCP<const Vector> h_, hBefore_;       // the dual right-hand sides of those two steps
  Friction::WarmStart warm_;            // ... and its outer algorithm's final state (empty after resumeFrom)
  Fem::NodalVector u_;
  // Where the next step's iterations start (predictedMultipliers in the source).
  RCP<const Vector> predictedMultipliers(const Feti::FetiDual& dual) const;
};

}  // namespace Contact
}  // namespace Tribos
