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
// the list's "Friction" sublist states. The list (validParameters(), and
// getValidParameters() of the object):
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
// range, an unknown law, an outer algorithm that does not solve the FETI
// dual (NSGS) or a value an outer algorithm refuses are refused by
// setParameters; an outer algorithm that does not solve the law of the
// problem's contact pairs, Tresca and Coulomb pairs in one problem, or a
// dense Semismooth Newton on a dual larger than its Dense Limit by
// setProblem (or by setParameters once a problem is set): a Tribos::Error
// naming the parameter, the reason and the valid choices, before any work.
// It is a Teuchos::ParameterListAcceptor, so that code written for any
// Trilinos solver can set, read and document its parameters; the valid list
// writes as a Teuchos XML file and reads back with its validators
// (Tribos_ValidatorXml.hpp).
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_ParameterListAcceptor.hpp>

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

class ContactSolver : public Teuchos::ParameterListAcceptor {
 public:
  ContactSolver() = default;
  ContactSolver(const RCP<const Feti::FetiProblem>& problem, const RCP<Teuchos::ParameterList>& params);

  // Validates params against validParameters() and fills in the defaults
  // (in the caller's list, as Belos does); throws Tribos::Error naming the
  // parameter (the solver keeps the parameters it had). Null: every
  // default. With a problem set, also what setProblem checks (collective
  // then, as setProblem).
  void setParameters(const RCP<Teuchos::ParameterList>& params);
  RCP<const Teuchos::ParameterList> getCurrentParameters() const { return params_; }
  // The list with defaults and documentation (FETI, the solve, Friction);
  // the object's getValidParameters() returns it.
  static RCP<const Teuchos::ParameterList> validParameters();

  // Teuchos::ParameterListAcceptor: setParameterList is setParameters;
  // unsetParameterList returns the list and leaves the solver without one
  // (solve() then takes every default).
  void setParameterList(const RCP<Teuchos::ParameterList>& params) override { setParameters(params); }
  RCP<Teuchos::ParameterList> getNonconstParameterList() override { return params_; }
  RCP<Teuchos::ParameterList> unsetParameterList() override;
  RCP<const Teuchos::ParameterList> getParameterList() const override { return params_; }
  RCP<const Teuchos::ParameterList> getValidParameters() const override { return validParameters(); }

  // Refuses (Tribos::Error, the solver keeps the problem it had) a problem
  // with contact that the parameters set cannot solve: an outer algorithm
  // that does not solve the law of its contact pairs, pairs of Tresca and of
  // Coulomb friction, a Semismooth Newton with Linear Solver = Dense LU on a
  // dual of more rows than its Dense Limit. Collective over the problem's
  // communicator (the pairs of every rank).
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
// (ContactSolver::validParameters()'s "Friction"): without "Pair <k>"
// sublists one entry, the list's own law, coefficient and slip bound, for
// every pair; with them one entry per pair up to the largest k, the
// sublist's values where it names them and the list's own elsewhere.
// Validates the list and fills in its defaults; throws Tribos::Error naming
// the entry for anything that is not valid there.
PairFriction readPairFriction(Teuchos::ParameterList& friction);
// Refuses (Tribos::Error naming the algorithm and the valid ones) an outer
// algorithm ("Outer Algorithm", Auto passes) that does not solve the law
// the contact pairs make together (runLaw).
void requireOuterAlgorithmSolves(const std::string& outerAlgorithm, FrictionLaw law);


}  // namespace Contact
}  // namespace Tribos
