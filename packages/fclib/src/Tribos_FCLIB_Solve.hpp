// Tribos_FCLIB_Solve.hpp: FCLIB problems solved by the friction algorithms of
// packages/friction (MSA + Algorithm 1, Algorithm 2), the same ones that
// solve the FETI contact problems.
//
// A local problem u = W r + q with Coulomb's law in De Saxce's form is, for a
// given slip bound g, the Tresca QP
//   min 1/2 r'W r + q'r   s.t.  r_N,k >= 0,  ||r_T,k|| <= g_k,
// i.e. a ContactDual with A = s W, b = -s q (s = 1/||W||, so that ||A|| = 1
// as the algorithms' defaults (rho, M) assume; the minimizer does not depend
// on s), normal row 3k, tangential rows 3k+1, 3k+2, no equality constraint,
// and friction coefficients mu_k. The Coulomb fixed point g = mu r_N then
// gives r; with the Tresca optimality conditions and g = mu r_N, (r, W r + q)
// satisfies Coulomb's law including the mu ||u_T|| term of the natural map,
// which is what err checks (Tribos_FCLIB_Accuracy.hpp).
//
// A global problem (M, H, f, w) is reduced to W = H' M^-1 H, q = H' M^-1 f + w,
// with W applied as an operator through one factorization of M (a
// LocalSolver: KLU2 by default, an LU, because some LMGC mass matrices are
// symmetric only to ~1e-7), and v = M^-1 (H r + f) recovered at the end.
// Everything here is serial: use a communicator of one rank.
//
// W is only positive semidefinite when bodies are rigid and contacts are few
// relative to their degrees of freedom. The QP solvers' convergence theory
// (MPRGP, MPGP, SMALBE) assumes a Hessian positive definite on the feasible
// set; with a singular W the Tresca subproblems are still convex, may have
// many minimizers, and projected-gradient iterations still decrease the
// residual, but no rate is guaranteed. The report carries the extreme
// eigenvalues of W (for problems small enough to form W densely) so a run
// says clearly when it is outside the guaranteed setting.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>
#include <vector>

#include "Tribos_FCLIB.hpp"
#include "Tribos_FCLIB_Accuracy.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_LocalCsr.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace FCLIB {

// A factorization of M giving the SolveM of Tribos_FCLIB_Accuracy.hpp.
constexpr const char* kAutoMassSolver = "Auto";

class MassSolver {
 public:
  // name: a LocalSolver ("KLU2", "CHOLMOD", "Tacho"; CHOLMOD and Tacho need M
  // symmetric positive definite), or "Auto": CHOLMOD when M is symmetric,
  // KLU2 when it is not or when CHOLMOD finds it not positive definite
  // (name() tells which factored it). A failed factorization throws
  // Tribos::Error "<source>: M (...) is singular (or not positive definite)
  // ...", source naming the problem (its file).
  MassSolver(const LocalCsr& M, const std::string& name, const std::string& source = "FCLIB solve");
  void solve(const std::vector<double>& b, std::vector<double>& x) const;
  // Without degrees of freedom (M is 0 x 0) nothing is factored and every
  // solve is empty.
  void solve(const double* b, double* x, int nrhs) const {
    if (solver_) solver_->solve(b, x, nrhs);
  }
  SolveM function() const;
  int size() const { return solver_ ? solver_->size() : 0; }
  long long solves() const { return solves_; }
  double factorSeconds() const { return factorSeconds_; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  RCP<LocalSolver> solver_;
  mutable long long solves_ = 0;
  double factorSeconds_ = 0;
};

// W as a Tpetra operator on a serial map of 3nc entries: W a stored sparse
// matrix (local problem) or H' M^-1 H (global problem).
class DelassusOperator : public Operator {
 public:
  DelassusOperator(const LocalCsr& W, const RCP<const Map>& map);
  DelassusOperator(const LocalCsr& H, std::shared_ptr<const MassSolver> M, const RCP<const Map>& map);
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override;
  // y = W x (unscaled) on plain arrays.
  void applyW(const std::vector<double>& x, std::vector<double>& y) const;
  // W as a dense column-major n x n array (n applications; for a global
  // problem one solve with M of n right-hand sides, made once and kept, so
  // that the spectrum and Newton's explicit W share it).
  std::vector<double> dense() const;
  // W as a CSR matrix: the stored W of a local problem, or H' M^-1 H formed
  // by dense() (its nonzero entries) for a global one.
  LocalCsr explicitMatrix() const;

 private:
  const LocalCsr* W_ = nullptr;
  const LocalCsr* H_ = nullptr;
  std::shared_ptr<const MassSolver> M_;
  RCP<const Map> map_;
  mutable std::vector<double> x_, y_, z_;
  mutable std::vector<double> denseW_;  // H' M^-1 H, once formed (global problems)
};

// "Semismooth Newton" (Friction::SemismoothNewton) is given W explicitly,
// KLU for its Newton systems, and stops on ||F_nat|| / ||q|| <= its Relative
// Tolerance (the natural-map error of Tribos_FCLIB_Accuracy.hpp); so does
// "NSGS" (Friction::NonsmoothGaussSeidel), given W's entries.
struct SolveOptions {
  // A registered friction algorithm that solves Coulomb problems
  // (coulombAlgorithms(): "MSA+Algorithm1", "Algorithm2", "Semismooth
  // Newton", "NSGS"); others (the Tresca solver, whose slip bound an FCLIB
  // problem does not give) are refused before any work, naming the valid ones.
  std::string algorithm = "Algorithm2";
  // > 0: the result must reach ||F_nat|| / ||q|| <= naturalMapTolerance (the
  // natural-map error relative to q; Siconos' fc3d_compute_error divides
  // the same map by max(||q||, ||r||, ||u||)). The algorithm is
  // asked for this relative tolerance (FrictionSolver::setRequestedTolerance);
  // an algorithm whose own stopping test is a different measure is asked
  // again from its result with a tolerance scaled by naturalMapTolerance/err
  // (at most Tolerance Rounds solves) until the natural-map error is met.
  // 0: the algorithm's parameters decide alone (the tolerance of the list).
  double naturalMapTolerance = 0;
  int toleranceRounds = 8;
  // > 0: the limit on the algorithm's outer iterations
  // (FrictionSolver::setMaximumIterations), shared by the rounds above.
  int maxIterations = 0;
  // The "Solver" list of the friction factory (sublists "Algorithm 1", "MSA",
  // "Algorithm 2"); entries not given take the values of defaultSolverParameters().
  Teuchos::ParameterList solverParams;
  std::string massSolver = kAutoMassSolver;
  // W is formed densely for its spectrum when 3nc does not exceed this.
  int denseSpectrumLimit = 3000;
  bool verbose = false;
  // SolveReport::converged holds the result to this factor times the
  // requested tolerance; "Result Check Factor" at the root of solverParams
  // (Solver/Result Check Factor of a Tribos input) wins.
  double resultCheckFactor = 100.0;
  // The methods that minimize 1/2 r'W r + q'r (MSA+Algorithm1, Algorithm2)
  // need W symmetric: their gradient is inconsistent at the level of the
  // asymmetry, and their stopping tests (relative tolerances down to 1e-12)
  // may then never be met. In local_problem_test.hdf5 (max|W| = 696), W(4,
  // 0) = 1.4e-8 made 4.3e-8 (an asymmetry of 4e-11 max|W|) keeps Algorithm 2
  // going for its 100000 iterations, 1.4e-5 for minutes; made so on both
  // sides it solves in 2000. A local problem's W is refused before any
  // work, naming its largest asymmetric entry, unless |W_ij - W_ji| <=
  // symmetryTolerance max|W| for every entry; exported ones are symmetric
  // to round-off (the samples to 2e-16). A global problem's W = H'M^-1 H is
  // symmetric by construction. NSGS and Semismooth Newton take any W.
  double symmetryTolerance = 1e-12;
  // The problem in messages, e.g. "FCLIB file X.hdf5" ("FCLIB solve" if empty).
  std::string source;
};

// Tolerances tight enough for err <= 1e-8 on the samples: the friction
// defaults (1e-6, 1e-4) are tuned for FETI runs, not for a comparison of
// solvers at round-off level.
Teuchos::ParameterList defaultSolverParameters();

struct SolveReport {
  Friction::FrictionStatus status;
  std::string algorithm;
  std::vector<double> r, u, v;   // v only for a global problem
  NaturalMapError err;
  long long n_A = 0;             // applications of W in the solve (incl. the norm estimate)
  long long massSolves = 0;      // solves with M (global problem)
  // The factorization of M (global problem; name() says which solver made
  // it), kept for further solves with M (the error of a stored solution)
  // instead of factoring M again.
  std::shared_ptr<const MassSolver> mass;
  double normW = 0, scale = 1;   // ||W|| (power method) and s = 1/||W||
  // Extreme eigenvalues of the symmetric part of W (when formed); the
  // smallest relative to the largest tells whether W is singular.
  bool spectrumKnown = false;
  double eigMin = 0, eigMax = 0;
  int numericalRank = -1;        // eigenvalues above 1e-12 eigMax
  double timeSetup = 0, timeSolve = 0;
  // The contact KKT residuals of the returned r and u with g = mu r_N
  // (Contact::ContactKKT, as for FETI results), next to err.
  double kktNormal = 0, kktComplementarity = 0, kktFriction = 0;
  std::string note;              // e.g. why a guarantee does not apply
  // 'converged' is a promise about the returned result, not the solver's own
  // stopping test (that is status.converged): the solver stopped on its test,
  // every entry of r, u and v is finite, and the natural-map error relative
  // to max(||q||, ||r||, ||u||) and the three KKT residuals above are at most
  // limit = Result Check Factor x tolerance, the tolerance asked of the method
  // (Algorithm 2's Relative Tolerance; Algorithm 1's SMALBE Relative
  // Tolerance, for MSA the larger of it and the MSA Tolerance). It refers to
  // the FCLIB (Coulomb) problem whatever the method: "Tresca" solves with the
  // slip bound 0 and is converged only where that solves the Coulomb problem.
  bool converged = false;
  std::string stopReason;        // why not converged, else the solver's reason
  double tolerance = 0, limit = 0;
  // With SolveOptions::naturalMapTolerance > 0: that tolerance, which
  // err.relativeToQ must meet as well for 'converged', the solves it took
  // and err.relativeToQ after each.
  double naturalMapTolerance = 0;
  int rounds = 1;
  std::vector<double> roundErrors;
};

// The algorithms an FCLIB problem (Coulomb friction) can be solved with.
std::vector<std::string> coulombAlgorithms();

// Sets rep.converged and rep.stopReason from rep.status, rep.r, rep.u, rep.v,
// rep.err and the KKT residuals against rep.limit (see SolveReport).
void judgeResult(SolveReport& rep);

// Solves FCLIB problems with one set of options. The method and its
// parameters are checked and the algorithm made once, by the constructor, so
// that a code that solves a problem per time step pays for them once; each
// solve() starts from the options' tolerance and iteration limit.
// "NSGS" works on W's entries directly (the local problem's stored W; a
// global problem's H' M^-1 H formed from 3nc solves with M), without the
// Tpetra dual of the other methods.
class Solver {
 public:
  Solver(const SolveOptions& options, const RCP<const Comm>& serialComm);
  SolveReport solve(const LocalProblem& problem) const;
  SolveReport solve(const GlobalProblem& problem) const;

 private:
  void resetLimits() const;
  // Refuses a nonsymmetric W when the method needs W symmetric.
  void requireSymmetric(const LocalCsr& W) const;
  std::string source() const;
  SolveOptions options_;
  RCP<const Comm> comm_;
  RCP<Friction::FrictionSolver> solver_;
  bool needsSymmetricW_ = true;
  mutable bool limitsAsGiven_ = false;  // solver_ holds the options' tolerance and iteration limit
  double tolerance_ = 0, limit_ = 0;  // the requested tolerance, Result Check Factor times it
};

// Solver(options, serialComm).solve(problem).
// The problem is validated (validate() of Tribos_FCLIB.hpp) and the method
// and its parameters checked before any work. Zero contacts is a valid
// problem: r and u are empty (global: v = M^-1 f). More generally W = 0
// (no degree of freedom sees a contact) needs no friction solver: u = q
// whatever r, and r = 0 is a solution exactly when q satisfies Coulomb's law.
SolveReport solve(const LocalProblem& problem, const SolveOptions& options, const RCP<const Comm>& serialComm);
SolveReport solve(const GlobalProblem& problem, const SolveOptions& options, const RCP<const Comm>& serialComm);

}  // namespace FCLIB
}  // namespace Tribos
