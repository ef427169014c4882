// Tribos_ContactSolver.hpp: the contact solve as an object in the shape of
// a Belos::SolverManager: parameters set and validated once, a problem, a
// solve that returns a status, the result read afterwards.
//
//   Contact::ContactSolver solver;
//   solver.setParameters(params);          // every choice, friction included
//   solver.setProblem(problem);            // a Feti::FetiProblem
//   if (solver.solve() != Contact::SolveStatus::Converged) ...
//   const auto& r = solver.getResult();    // u, contact forces, KKT residuals, verdict
//
// It runs Contact::solveFeti (Tribos_FetiSolve.hpp) with the friction that
// the list's "Friction" sublist states. The list (getValidParameters()):
//   "FETI"        the FetiProblem's parameters (FetiProblem::getValidParameters();
//                 the problem is built with this sublist, the solver reads its
//                 "Projected CG"),
//   "Outer Algorithm", "Result Check Factor", "Result Check Rounds" and the
//                 outer algorithms' sublists (Contact::fetiSolveParameters()),
//   "Friction"    "Law" (Frictionless | Tresca | Coulomb), "Coefficient"
//                 (Coulomb F), "Slip Bound Traction" (Tresca: a traction, times
//                 a node's contact area its slip bound): the friction of every
//                 contact pair; a sublist "Pair <k>" (k = the pair number of the
//                 contact conditions) overrides any of them for pair k.
// An entry that is not in this list, a value of the wrong type or out of
// range, an unknown law are refused by setParameters (Tribos::Error naming
// the parameter), before any work.
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_FetiContact.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Contact {

// The outcome of solve(), as Belos::ReturnType: Converged when the solver
// stopped on its own test and every KKT residual of the result is within
// the result check (getResult().verdict), Unconverged otherwise
// (getResult().verdict.stopReason says why).
enum class SolveStatus { Converged, Unconverged };

class ContactSolver {
 public:
  ContactSolver() = default;
  ContactSolver(const RCP<const Feti::FetiProblem>& problem, const RCP<Teuchos::ParameterList>& params);

  // Validates params against getValidParameters() and fills in the
  // defaults (in the caller's list, as Belos does); throws Tribos::Error
  // naming the parameter. Null: every default.
  void setParameters(const RCP<Teuchos::ParameterList>& params);
  RCP<const Teuchos::ParameterList> getCurrentParameters() const { return params_; }
  // The list with defaults and documentation (FETI, the solve, Friction).
  static RCP<const Teuchos::ParameterList> getValidParameters();

  void setProblem(const RCP<const Feti::FetiProblem>& problem);
  const RCP<const Feti::FetiProblem>& getProblem() const { return problem_; }
  // Where the outer algorithm reports its iterations (none by default).
  void setOutputStream(const RCP<Teuchos::FancyOStream>& out) { out_ = out; }

  // Solves the problem with the parameters set (defaults when none were).
  // Collective over the problem's communicator. Throws Tribos::Error when
  // no problem is set, CollectiveError for a problem the solve refuses
  // (e.g. a body that neither its Dirichlet rows nor its contact hold).
  SolveStatus solve();

  // The result of the last solve() (throws Tribos::Error before one).
  const FetiSolveResult& getResult() const;
  // Projected CG iterations without contact, outer iterations with contact.
  int getNumIters() const { return getResult().iterations; }
  // The friction of the contact pairs as "Friction" states it
  // (readPairFriction; solve() extends it to the problem's pairs).
  const PairFriction& getFriction() const { return friction_; }

 private:
  RCP<const Feti::FetiProblem> problem_;
  RCP<Teuchos::ParameterList> params_;
  PairFriction friction_{FrictionSpec()};  // readPairFriction of "Friction"
  FrictionSpec base_;                      // "Friction"'s own entries: pairs no "Pair <k>" names
  bool perPair_ = false;                   // "Friction" has "Pair <k>" sublists
  RCP<Teuchos::FancyOStream> out_;
  bool solved_ = false;
  FetiSolveResult result_;
};

// The friction of the contact pairs that a "Friction" list states
// (ContactSolver::getValidParameters()'s "Friction"): without "Pair <k>"
// sublists one entry, the list's own law, coefficient and slip bound, for
// every pair; with them one entry per pair up to the largest k, the
// sublist's values where it names them and the list's own elsewhere.
// Validates the list and fills in its defaults; throws Tribos::Error naming
// the entry for anything that is not valid there.
PairFriction readPairFriction(Teuchos::ParameterList& friction);

}  // namespace Contact
}  // namespace Tribos
