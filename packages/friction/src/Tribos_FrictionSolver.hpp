// Tribos_FrictionSolver.hpp: outer algorithms for contact with friction on a
// ContactDual, chosen by name in Belos' factory style:
//   "Tresca"          Algorithm 1 (SMALBE over Lambda_t(g) x Lambda_c) with the given slip bound g
//   "MSA+Algorithm1"  Coulomb by successive approximations g <- F lambda_N, each a Tresca solve
//   "Algorithm2"      Coulomb by the fused loop of Kucera's Algorithm 2
//   "Semismooth Newton"  Coulomb by Newton's method on the Alart-Curnier function
//   "NSGS"            Coulomb by nonsmooth Gauss-Seidel over the contacts (explicit W only)
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "Tribos_ContactDual.hpp"
#include "Tribos_Registry.hpp"

namespace Tribos {
namespace Friction {

// One outer step of an algorithm, as a convergence plot needs it. The
// residuals are relative to ||b|| (the scale of the stopping tests); NaN
// where the algorithm has no such quantity (slip-bound change of Tresca).
struct OuterStep {
  int iteration = 0;          // the algorithm's own count: Algorithm 2 loop, MSA step, SMALBE outer iterations
  SC projectedGradient = 0;   // ||g^P|| / ||b||
  SC normGx = 0;              // ||G lambda|| / ||b||
  SC slipBoundChange = 0;     // ||g(l+1) - g(l)|| / ||g||
  long n_A = 0;               // Hessian multiplications of the solve so far
  double seconds = 0;         // since the start of the solve
};

struct FrictionStatus {
  bool converged = false;
  std::string reason;
  int outer_iterations = 0;  // SMALBE outer iterations (summed over MSA steps) or Algorithm 2 loops
  int msa_iterations = 0;
  int inner_iterations = 0;
  long n_A = 0;              // Hessian multiplications of the whole solve
  long n_A_qpp = 0;          // ... in the bound-constrained (normal) solver
  long n_A_qpq = 0;          // ... in the circle-constrained (tangential) solver
  SC norm_gP = 0, norm_Gx = 0;
  SC slip_bound_change = 0;  // last relative change of g (Coulomb)
  std::vector<SC> history;   // per outer step: relative change of g (Coulomb) or ||g^P|| (Tresca)
  std::vector<OuterStep> steps;  // one per entry of history, with every residual, n_A and time
  std::vector<SC> slipBound; // the slip bound of the returned solution (local)
  // The matrix-free Newton method: the preconditioner of its CG solves at
  // the end of the solve (Preconditioner = Auto: Slip Curvature, or Lumped
  // once taken); empty for the other methods.
  std::string preconditioner;
};

// The augmented Lagrangian's state at the end of a solve: the multiplier mu
// of G x = 0 and the penalty rho (Algorithm 2, the matrix-free Newton
// method; Algorithm 1 gives mu only, its SMALBE keeping no rho), where the
// solve of a nearby problem (the next load step, a further result-check
// round) may start (FrictionSolver::setWarmStart).
struct WarmStart {
  RCP<const Vector> equalityMultiplier;
  SC rho = 0;
  // The Newton method's Preconditioner = Auto took FETI's lumped
  // preconditioner (its CG steps were long without it): the next solve
  // starts with it.
  bool lumped = false;
};

// The status of a solve repeated from its result (a next round): the counts
// of both, the history and steps of both in order, the state of the next.
FrictionStatus followedBy(const FrictionStatus& earlier, const FrictionStatus& next);

// The tolerance of a next solve when a solve met its own stopping test but
// its result missed the target by the factor achieved / target (> 1): the
// requested tolerance scaled by margin times that miss (half by default), at
// least tenfold, down to 1e-15 (a solver's stopping test and the result's
// residuals are in a roughly fixed ratio, so one or two such rounds meet the
// target; a smaller margin where the ratio is known to grow as the iterate
// converges).
double tightenedTolerance(double requested, double target, double achieved, double margin = 0.5);
// The floor of tightenedTolerance: a solve asked for it cannot be tightened.
constexpr double kTightestTolerance = 1e-15;
inline bool atTightestTolerance(double requested) { return requested <= kTightestTolerance * (1 + 1e-4); }

class FrictionSolver {
 public:
  virtual ~FrictionSolver() = default;
  // x: initial guess on input (projected if infeasible), solution on output.
  virtual FrictionStatus solve(const ContactDual& dual, Vector& x) = 0;
  virtual RCP<const Teuchos::ParameterList> getValidParameters() const = 0;
  // The relative tolerance the solve is asked for: what the result check of
  // a solution measures its KKT residuals against.
  virtual double requestedTolerance() const = 0;
  // Overrides of the parameter list for callers that ask every algorithm
  // the same (tribos_fclib --tolerance, --max-iterations): the relative
  // tolerance requestedTolerance() then returns, and the limit on the outer
  // iterations (the algorithm's own loop: SMALBE outer iterations, MSA steps,
  // Algorithm 2 loops, Newton steps). Not calling them changes nothing.
  virtual void setRequestedTolerance(double tolerance) = 0;
  virtual void setMaximumIterations(int iterations) = 0;
  void setOutputStream(RCP<Teuchos::FancyOStream> out) { out_ = out; }
  // Starts the equality constraint's multiplier and penalty where a solve of
  // a nearby problem ended (its finalState()), instead of mu = 0 and the
  // default rho: a load step continues from the one before. Algorithms
  // without them ignore it and leave finalState() empty.
  void setWarmStart(const WarmStart& previous) { warm_ = previous; }
  const WarmStart& finalState() const { return final_; }
  // Throws Error when this algorithm refuses a dual of that many rows (a
  // dense method's limit), so that a caller can refuse before the setup.
  virtual void checkDualRows(long long /*rows*/) const {}

 protected:
  RCP<Teuchos::FancyOStream> out_;
  WarmStart warm_, final_;
};

// An algorithm of one loop whose own list holds "Relative Tolerance" and
// "Maximum Iterations" at its top (Algorithm 2, Semismooth Newton, NSGS):
// the list, validated against the algorithm's valid parameters, and the
// overrides of FrictionSolver that set those two there (refused, naming the
// algorithm, outside the range the list documents).
class SingleLoopSolver : public FrictionSolver {
 public:
  RCP<const Teuchos::ParameterList> getValidParameters() const override { return valid_; }
  double requestedTolerance() const override;             // Relative Tolerance
  void setRequestedTolerance(double tolerance) override;  // Relative Tolerance
  void setMaximumIterations(int iterations) override;     // Maximum Iterations

 protected:
  // valid: the algorithm's validParameters(); its name names the algorithm.
  SingleLoopSolver(const Teuchos::ParameterList& params, RCP<const Teuchos::ParameterList> valid);
  // Called after an override changed the list (for values read once).
  virtual void parametersChanged() {}

  Teuchos::ParameterList params_;

 private:
  RCP<const Teuchos::ParameterList> valid_;
};

// Algorithm 1: SMALBE for G x = 0 with the inner minimization by block
// Gauss-Seidel (MPRGP + MPGP, "Sweeps") or one joint MPGP. Without G the
// inner solver runs alone to the tolerance.
class Algorithm1 : public FrictionSolver {
 public:
  explicit Algorithm1(const Teuchos::ParameterList& params);
  FrictionStatus solve(const ContactDual& dual, Vector& x) override;  // g = dual.slipBound
  FrictionStatus solve(const ContactDual& dual, const std::vector<SC>& g, Vector& x);
  RCP<const Teuchos::ParameterList> getValidParameters() const override;
  static RCP<const Teuchos::ParameterList> validParameters();
  double requestedTolerance() const override;
  void setRequestedTolerance(double tolerance) override;  // SMALBE Relative Tolerance
  void setMaximumIterations(int iterations) override;     // SMALBE Maximum Outer Iterations
  // Keeps the SMALBE multiplier between solves (warm start of MSA steps).
  void setWarmStart(bool on) { warmStart_ = on; }
  void setHessianNorm(SC normA) { normA_ = normA; }

 private:
  Teuchos::ParameterList params_;
  bool warmStart_ = false;
  RCP<Vector> mu_;
  SC normA_ = -1;
};

class MSA : public FrictionSolver {
 public:
  MSA(const Teuchos::ParameterList& params, const Teuchos::ParameterList& algorithm1);
  FrictionStatus solve(const ContactDual& dual, Vector& x) override;
  RCP<const Teuchos::ParameterList> getValidParameters() const override;
  static RCP<const Teuchos::ParameterList> validParameters();
  double requestedTolerance() const override;  // the larger of Algorithm 1's and the fixed point's
  void setRequestedTolerance(double tolerance) override;  // both: MSA Tolerance and Algorithm 1's
  void setMaximumIterations(int iterations) override;     // MSA Maximum Iterations

 private:
  Teuchos::ParameterList params_;
  Algorithm1 tresca_;
};

class Algorithm2 : public SingleLoopSolver {
 public:
  explicit Algorithm2(const Teuchos::ParameterList& params);
  FrictionStatus solve(const ContactDual& dual, Vector& x) override;
  static RCP<const Teuchos::ParameterList> validParameters();
};

// The parameter list an outer algorithm reads: a sublist of the "Solver"
// list named after the algorithm ("Algorithm 1", "MSA", "Algorithm 2").
// The outer algorithms by name: "Tresca" (Algorithm 1 with a given slip
// bound; also frictionless), "MSA+Algorithm1" and "Algorithm2" (Coulomb).
// Each accepts the friction laws it solves ("Frictionless", "Tresca",
// "Coulomb"); the maker takes the list with sublists "Algorithm 1", "MSA",
// "Algorithm 2" (missing ones take defaults).
// "Semismooth Newton" (Tribos_SemismoothNewton.hpp) solves Coulomb problems
// up to its Dense Limit of dual rows (FETI's, with G x = 0, reduced to the
// contact rows; FCLIB's with their explicit W); its list is the sublist
// "Semismooth Newton". "NSGS" (Tribos_NonsmoothGaussSeidel.hpp) reads W's
// entries, so it accepts "Coulomb (explicit W)" only (FCLIB problems); its
// list is the sublist "NSGS".
using FrictionSolverRegistry = Registry<FrictionSolver, const Teuchos::ParameterList&>;
const FrictionSolverRegistry& frictionSolvers();

// The outer algorithms that solve a dual whose operator is only applied
// (FETI's): those that accept a friction law (Frictionless, Tresca or
// Coulomb), in the registry's order; not NSGS, which reads W's entries.
// Their aliases, and their documentation for a parameter choosing one.
std::vector<std::string> dualSolverNames();
std::vector<std::string> dualSolverAliases();
std::string dualSolverDocumentation();

class FrictionSolverFactory {
 public:
  RCP<FrictionSolver> create(const std::string& name, const Teuchos::ParameterList& params) const;
  // Valid sublists "Algorithm 1", "MSA", "Algorithm 2" for input validation.
  static void addValidParameters(Teuchos::ParameterList& solverList);
};

}  // namespace Friction
}  // namespace Tribos
