#include "Tribos_ContactSolver.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_Registry.hpp"

namespace Tribos {
namespace Contact {

namespace {

constexpr const char* kFriction = "Friction";
constexpr const char* kPair = "Pair ";

// "Law", "Coefficient", "Slip Bound Traction": the friction of one pair.
RCP<const Teuchos::ParameterList> frictionParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList(kFriction);
    pl->set("Law", frictionLawName(FrictionLaw::Frictionless),
            "the friction law of the contact pairs: Frictionless, Tresca or Coulomb", frictionLawValidator());
    pl->set("Coefficient", 0.0, "Coulomb friction coefficient F (slip bound F lambda_N)",
            rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1e6)));
    pl->set("Slip Bound Traction", 0.0,
            "Tresca: the slip bound as a traction, force per area; a node's slip bound is this times its contact area",
            rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1e300)));
  }
  return pl;
}

// Everything but "Friction": the solve's entries and the FetiProblem's.
RCP<const Teuchos::ParameterList> solveAndProblemParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = rcp(new Teuchos::ParameterList(*fetiSolveParameters()));
    pl->setName("Contact Solver");
    pl->sublist("FETI").setParameters(*Feti::FetiProblem::getValidParameters());
  }
  return pl;
}

// Teuchos' validation, its message (which names the entry and the list)
// as a Tribos::Error.
void validate(Teuchos::ParameterList& list, const Teuchos::ParameterList& valid, const std::string& where) {
  try {
    list.validateParametersAndSetDefaults(valid);
  } catch (const std::exception& e) {
    throw Error("ContactSolver: " + where + ": " + e.what());
  }
}

// The friction a validated list states (the validators' ranges refuse
// values that are not finite).
FrictionSpec frictionSpec(const Teuchos::ParameterList& list) {
  FrictionSpec f;
  f.law = frictionLaw(list, "Law");
  f.coefficient = list.get<double>("Coefficient");
  f.slipBoundTraction = list.get<double>("Slip Bound Traction");
  return f;
}

// k of a sublist "Pair <k>", or -1 when the name is not of that form.
int pairNumber(const std::string& name) {
  if (name.rfind(kPair, 0) != 0) return -1;
  const std::string digits = name.substr(std::string(kPair).size());
  if (digits.empty() || digits.size() > 6 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return -1;
  return std::stoi(digits);
}

// The choices of "Outer Algorithm" (fetiSolveParameters()'s validator).
std::vector<std::string> outerAlgorithmChoices() {
  const auto values = fetiSolveParameters()->getEntry("Outer Algorithm").validator()->validStringValues();
  return std::vector<std::string>(values->begin(), values->end());
}

// The choices of "Outer Algorithm" that solve a problem of the law `law`:
// Auto, the algorithms that accept it and their aliases.
std::vector<std::string> outerAlgorithmsSolving(const std::string& law) {
  const auto& registry = Friction::frictionSolvers();
  std::vector<std::string> out;
  for (const auto& name : outerAlgorithmChoices())
    if (name == kAutoOuterAlgorithm || registry.accepts(registry.canonical(name), law)) out.push_back(name);
  return out;
}

// An algorithm of the registry that does not solve the FETI dual (NSGS,
// which reads the entries of W: FCLIB problems). Refused with the reason
// before Teuchos' validation, whose message would only say that the value
// is not one of the choices.
void refuseAlgorithmOutsideFeti(const Teuchos::ParameterList& p) {
  if (!p.isType<std::string>("Outer Algorithm")) return;  // absent, or of a type the validation refuses
  const std::string name = p.get<std::string>("Outer Algorithm");
  const auto& registry = Friction::frictionSolvers();
  const auto choices = outerAlgorithmChoices();
  if (!registry.has(name) || std::find(choices.begin(), choices.end(), name) != choices.end()) return;
  throw Error("ContactSolver: Outer Algorithm = \"" + name + "\" does not solve the FETI dual problem, whose operator F "
              "is applied, never formed: " + registry.documentation({registry.canonical(name)}) +
              "; valid: " + joinNames(choices));
}

// What the outer algorithms refuse of their sublists beyond the ranges of
// the valid list (Algorithm 2: a Residual Balancing between 0 and 1): the
// solve would refuse it when it makes the algorithm. Every algorithm the
// list offers is made, so that the list is valid whichever one runs.
void refuseAlgorithmParameters(const Teuchos::ParameterList& p) {
  for (const auto& name : Friction::dualSolverNames()) {
    try {
      Friction::FrictionSolverFactory().create(name, p);
    } catch (const std::exception& e) {
      throw Error(std::string("ContactSolver: ") + e.what());
    }
  }
}

// Whether a "Friction" list has "Pair <k>" sublists.
bool namesPairs(const Teuchos::ParameterList& friction) {
  for (auto it = friction.begin(); it != friction.end(); ++it)
    if (friction.isSublist(friction.name(it))) return true;
  return false;
}

// The largest pair number of the problem's contact nodes (-1: none), on
// every rank. Collective.
int largestPair(const Feti::FetiProblem& problem) {
  int mine = -1, largest = -1;
  for (const auto& c : problem.contactConstraints()) mine = std::max(mine, c.pair);
  Teuchos::reduceAll(*problem.comm(), Teuchos::REDUCE_MAX, mine, Teuchos::outArg(largest));
  return largest;
}

// The friction solve() applies to the problem's pairs: with "Pair <k>"
// sublists, the pairs beyond the largest k take the list's own friction (a
// list of one entry applies to every pair). Collective when perPair.
PairFriction frictionOfProblem(const PairFriction& listed, const FrictionSpec& base, bool perPair,
                               const Feti::FetiProblem& problem) {
  PairFriction friction = listed;
  if (perPair) friction.resize(std::max<size_t>(friction.size(), largestPair(problem) + 1), base);
  return friction;
}

// What the solve would refuse of the parameters p (validated; the friction
// of "Friction" as listed, base and perPair as in ContactSolver) for a
// problem with contact: an outer algorithm that does not solve the law of
// its pairs, Tresca and Coulomb pairs in one problem (runLaw), a dual larger
// than a dense algorithm takes. The same decision on every rank (the
// friction and the dual's size are the same there). Collective.
void refuseForProblem(const Teuchos::ParameterList& p, const PairFriction& listed, const FrictionSpec& base,
                      bool perPair, const Feti::FetiProblem& problem) {
  if (!problem.hasContact()) return;  // projected CG: no outer algorithm, no friction
  const PairFriction friction = frictionOfProblem(listed, base, perPair, problem);
  FrictionLaw law;
  try {
    law = runLaw(friction);
  } catch (const Error& e) {
    throw CollectiveError(std::string("ContactSolver: Friction: ") + e.what());
  }
  const std::string requested = p.get<std::string>("Outer Algorithm");
  try {
    requireOuterAlgorithmSolves(requested, law);
  } catch (const Error& e) {
    throw CollectiveError(e.what());
  }
  try {
    Friction::FrictionSolverFactory()
        .create(outerAlgorithmFor(requested, friction), p)
        ->checkDualRows(static_cast<long long>(problem.dualMap()->getGlobalNumElements()));
  } catch (const Error& e) {
    throw CollectiveError(std::string("ContactSolver: ") + e.what());
  }
}

}  // namespace

void requireOuterAlgorithmSolves(const std::string& requested, FrictionLaw law) {
  const std::string lawName = frictionLawName(law);
  if (requested != kAutoOuterAlgorithm &&
      !Friction::frictionSolvers().accepts(Friction::frictionSolvers().canonical(requested), lawName))
    throw Error("ContactSolver: Outer Algorithm = \"" + requested + "\" does not solve " +
                (law == FrictionLaw::Frictionless ? "frictionless contact" : lawName + " friction") +
                ", the law of this problem's contact pairs (Friction/Law); valid for it: " +
                joinNames(outerAlgorithmsSolving(lawName)));
}

PairFriction readPairFriction(Teuchos::ParameterList& friction) {
  Teuchos::ParameterList own(kFriction);
  std::map<int, Teuchos::ParameterList> pairs;
  for (auto it = friction.begin(); it != friction.end(); ++it) {
    const std::string& name = friction.name(it);
    if (!friction.isSublist(name)) {
      own.setEntry(name, friction.entry(it));
      continue;
    }
    const int k = pairNumber(name);
    TRIBOS_REQUIRE(k >= 0, "ContactSolver: Friction/" << name << " is not a parameter of Friction (Law, Coefficient, "
                                                      << "Slip Bound Traction, or a sublist \"Pair <k>\", k the "
                                                         "pair number of the contact conditions)");
    pairs[k] = friction.sublist(name);
  }
  validate(own, *frictionParameters(), kFriction);
  friction.setParameters(own);  // the defaults, in the caller's list
  const FrictionSpec base = frictionSpec(own);
  if (pairs.empty()) return {base};
  PairFriction out(pairs.rbegin()->first + 1, base);
  for (auto& [k, list] : pairs) {
    const std::string path = std::string(kFriction) + "/" + kPair + std::to_string(k);
    validate(list, *frictionParameters(), path);  // its own entries, named by its path
    Teuchos::ParameterList merged(own);
    merged.setParameters(friction.sublist(kPair + std::to_string(k)));
    out[k] = frictionSpec(merged);
  }
  return out;
}

RCP<const Teuchos::ParameterList> ContactSolver::validParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = rcp(new Teuchos::ParameterList(*solveAndProblemParameters()));
    pl->sublist(kFriction, false,
                "the friction of every contact pair; a sublist \"Pair <k>\" with any of these entries overrides "
                "them for the pair k of the contact conditions")
        .setParameters(*frictionParameters());
  }
  return pl;
}

ContactSolver::ContactSolver(const RCP<const Feti::FetiProblem>& problem, const RCP<Teuchos::ParameterList>& params) {
  setParameters(params);
  setProblem(problem);
}

void ContactSolver::setParameters(const RCP<Teuchos::ParameterList>& params) {
  const RCP<Teuchos::ParameterList> p = params.is_null() ? Teuchos::parameterList() : params;
  refuseAlgorithmOutsideFeti(*p);
  // "Friction" holds sublists of free names ("Pair <k>"), which Teuchos'
  // validation cannot take: it is read apart, the rest validated whole.
  Teuchos::ParameterList friction = p->sublist(kFriction);
  p->remove(kFriction);
  PairFriction pairs;
  FrictionSpec base;
  bool perPair = false;
  try {
    validate(*p, *solveAndProblemParameters(), "parameters");
    refuseAlgorithmParameters(*p);
    pairs = readPairFriction(friction);
    base = frictionSpec(friction);
    perPair = namesPairs(friction);
  } catch (...) {
    p->sublist(kFriction).setParameters(friction);
    throw;
  }
  p->sublist(kFriction).setParameters(friction);
  if (!problem_.is_null()) refuseForProblem(*p, pairs, base, perPair, *problem_);
  params_ = p;
  friction_ = pairs;
  base_ = base;
  perPair_ = perPair;
  solved_ = false;
}

RCP<Teuchos::ParameterList> ContactSolver::unsetParameterList() {
  const RCP<Teuchos::ParameterList> p = params_;
  params_ = Teuchos::null;
  friction_ = {FrictionSpec()};
  base_ = FrictionSpec();
  perPair_ = false;
  solved_ = false;
  return p;
}

void ContactSolver::setProblem(const RCP<const Feti::FetiProblem>& problem) {
  if (!problem.is_null() && !params_.is_null()) refuseForProblem(*params_, friction_, base_, perPair_, *problem);
  problem_ = problem;
  solved_ = false;
}

SolveStatus ContactSolver::solve() {
  TRIBOS_REQUIRE(!problem_.is_null(), "ContactSolver::solve: no problem; call setProblem() first");
  if (params_.is_null()) setParameters(Teuchos::null);
  const PairFriction friction = frictionOfProblem(friction_, base_, perPair_, *problem_);
  solved_ = false;
  result_ = solveFeti(problem_, friction, *params_, out_);
  solved_ = true;
  return result_.verdict.converged ? SolveStatus::Converged : SolveStatus::Unconverged;
}

const FetiSolveResult& ContactSolver::getResult() const {
  TRIBOS_REQUIRE(solved_, "ContactSolver::getResult: no result; call solve() first");
  return result_;
}

}  // namespace Contact
}  // namespace Tribos
