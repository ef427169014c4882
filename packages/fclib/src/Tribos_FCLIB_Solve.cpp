#include "Tribos_FCLIB_Solve.hpp"

#include <Teuchos_LAPACK.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "Tribos_ContactKKT.hpp"
#include "Tribos_DualTransform.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_ArrayScan.hpp"
#include "Tribos_NonsmoothGaussSeidel.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_SemismoothNewton.hpp"

#include <klu.h>

namespace Tribos {
namespace FCLIB {

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// ---------------------------------------------------------------- MassSolver

namespace {

// The reason a library gives for a failure, without what is only of use to
// its developers: Teuchos' exceptions (Amesos2's) carry the library's source
// path, line and "Throw number" before the text; the last line is the text.
std::string libraryReason(const std::string& what) {
  std::string line;
  std::istringstream lines(what);
  for (std::string l; std::getline(lines, l);)
    if (l.find_first_not_of(" \t") != std::string::npos) line = l;
  const bool internal = line.find(".hpp") != std::string::npos || line.find(".cpp") != std::string::npos ||
                        line.find("Throw") != std::string::npos;
  return internal ? "" : line.substr(line.find_first_not_of(" \t"));
}

}  // namespace

namespace {

// Whether M equals its transpose to 1e-12 of its largest entry.
bool isSymmetric(const LocalCsr& M) { return asymmetry(M) <= 1e-12 * maxAbs(M); }

}  // namespace

MassSolver::MassSolver(const LocalCsr& M, const std::string& name, const std::string& source) : name_(name) {
  if (M.rows != M.cols) throw Error("MassSolver: M is not square");
  if (M.rows == 0) return;  // no degrees of freedom: nothing to factor, v is empty
  const auto t0 = std::chrono::steady_clock::now();
  const std::string what = "M (/fclib_global/M, " + std::to_string(M.rows) + " x " + std::to_string(M.cols) + ", " +
                           std::to_string(M.nnz()) + " entries)";
  // Auto: CHOLMOD, supernodal Cholesky, for the symmetric M of mechanics
  // (4 times faster than KLU2's LU on a stiffness matrix of 30048 dofs:
  // docs/fclib.md), KLU2 when M is not symmetric or not positive definite.
  if (name == kAutoMassSolver) name_ = isSymmetric(M) ? "CHOLMOD" : "KLU2";
  Progress::stage("factorization of " + what + " by " + name_);
  auto factor = [&] {
    solver_ = createLocalSolver(name_);
    solver_->factor(M);
  };
  try {
    try {
      factor();
    } catch (const std::exception&) {
      if (name != kAutoMassSolver || name_ == "KLU2") throw;
      name_ = "KLU2";  // symmetric but not positive definite
      Progress::stage("factorization of " + what + " by " + name_);
      factor();
    }
  } catch (const std::exception& e) {
    const std::string reason = libraryReason(e.what());
    throw Error(source + ": " + what + " is singular (or not positive definite): its " + name_ +
                " factorization failed" + (reason.empty() ? "" : " (" + reason + ")") +
                (name_ == "KLU2" ? "; the mass matrix must be nonsingular"
                                 : "; " + name_ + " needs M symmetric positive definite, KLU2 (--mass-solver KLU2) "
                                                  "takes any nonsingular M"));
  }
  factorSeconds_ = seconds(t0);
}

void MassSolver::solve(const std::vector<double>& b, std::vector<double>& x) const {
  x.assign(b.size(), 0.0);
  if (solver_) solver_->solve(b.data(), x.data(), 1);
  ++solves_;
}

SolveM MassSolver::function() const {
  return [this](const std::vector<double>& b, std::vector<double>& x) { solve(b, x); };
}

// ---------------------------------------------------------------- DelassusOperator

DelassusOperator::DelassusOperator(const LocalCsr& W, const RCP<const Map>& map) : W_(&W), map_(map) {}

DelassusOperator::DelassusOperator(const LocalCsr& H, std::shared_ptr<const MassSolver> M,
                                   const RCP<const Map>& map)
    : H_(&H), M_(std::move(M)), map_(map) {}

void DelassusOperator::applyW(const std::vector<double>& x, std::vector<double>& y) const {
  if (W_) {
    W_->multiply(x, y);
    return;
  }
  H_->multiply(x, z_);   // generalized forces
  M_->solve(z_, y_);     // velocities
  H_->multiplyTranspose(y_, y);
}

void DelassusOperator::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, SC alpha, SC beta) const {
  // W is symmetric (up to the asymmetry of M), so the transpose mode is ignored.
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    {
      auto xv = X.getVector(j)->getData();
      x_.assign(xv.begin(), xv.end());
    }
    std::vector<double> Wx;
    applyW(x_, Wx);
    auto y = Y.getVectorNonConst(j);
    auto yv = y->getDataNonConst();
    for (size_t i = 0; i < Wx.size(); ++i)
      yv[i] = (beta == 0.0 ? 0.0 : beta * yv[i]) + alpha * Wx[i];
  }
}

std::vector<double> DelassusOperator::dense() const {
  const int n = static_cast<int>(map_->getGlobalNumElements());
  std::vector<double> D(static_cast<size_t>(n) * n), e(n, 0.0), col;
  if (H_) {
    if (!denseW_.empty()) return denseW_;
    // All columns with one multi-right-hand-side solve: H e_j is column j of H.
    const int ndof = H_->rows;
    std::vector<double> HE(static_cast<size_t>(ndof) * n, 0.0), MHE(HE.size());
    for (int i = 0; i < ndof; ++i)
      for (int k = H_->rowptr[i]; k < H_->rowptr[i + 1]; ++k) HE[static_cast<size_t>(H_->col[k]) * ndof + i] = H_->val[k];
    M_->solve(HE.data(), MHE.data(), n);
    for (int j = 0; j < n; ++j) {
      std::vector<double> v(MHE.begin() + static_cast<size_t>(j) * ndof, MHE.begin() + static_cast<size_t>(j + 1) * ndof);
      H_->multiplyTranspose(v, col);
      std::copy(col.begin(), col.end(), D.begin() + static_cast<size_t>(j) * n);
    }
    denseW_ = D;
    return D;
  }
  for (int j = 0; j < n; ++j) {
    e[j] = 1.0;
    applyW(e, col);
    e[j] = 0.0;
    std::copy(col.begin(), col.end(), D.begin() + static_cast<size_t>(j) * n);
  }
  return D;
}

LocalCsr DelassusOperator::explicitMatrix() const {
  if (W_) return *W_;  // n x n, as validate() checked
  LocalCsr A;
  A.rows = A.cols = static_cast<int>(map_->getGlobalNumElements());
  const std::vector<double> D = dense();
  const int n = A.rows;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double a = D[static_cast<size_t>(j) * n + i];
      if (a != 0.0 || i == j) A.col.push_back(j), A.val.push_back(a);
    }
    A.rowptr.push_back(static_cast<int>(A.col.size()));
  }
  return A;
}

// ---------------------------------------------------------------- solve

Teuchos::ParameterList defaultSolverParameters() {
  Teuchos::ParameterList p("Solver");
  auto& a1 = p.sublist("Algorithm 1");
  // Without an equality constraint Algorithm 1 runs its inner solver alone;
  // one MPGP over the product set runs to the tolerance, where block
  // Gauss-Seidel with one sweep per call can exhaust its call budget first.
  a1.set("Inner Minimization", "MPGP");
  a1.sublist("SMALBE").set("Relative Tolerance", 1e-12);
  a1.sublist("SMALBE").set("Maximum Iterations", 20000);
  a1.sublist("MPRGP").set("Maximum Iterations", 20000);
  a1.sublist("MPGP").set("Maximum Iterations", 20000);
  auto& msa = p.sublist("MSA");
  msa.set("Tolerance", 1e-13);
  msa.set("Maximum Iterations", 500);
  auto& a2 = p.sublist("Algorithm 2");
  a2.set("Relative Tolerance", 1e-12);
  a2.set("Slip Bound Tolerance", 1e-11);
  a2.set("Maximum Iterations", 100000);
  a2.sublist("MPRGP").set("Maximum Iterations", 20000);
  a2.sublist("MPGP").set("Maximum Iterations", 20000);
  return p;
}

namespace {

using ContactDualPtr = std::shared_ptr<Friction::ContactDual>;

// The Newton systems of "Semismooth Newton" by SuiteSparse's KLU: the
// symbolic analysis once (the pattern of J does not change), a numeric
// factorization per step. J is given by rows; KLU reads the arrays as the
// columns of J', so klu_tsolve solves with J.
class KluNewtonSolver : public Friction::NewtonLinearSolver {
 public:
  KluNewtonSolver() { klu_defaults(&common_); }
  ~KluNewtonSolver() override { release(true); }
  KluNewtonSolver(const KluNewtonSolver&) = delete;
  KluNewtonSolver& operator=(const KluNewtonSolver&) = delete;
  bool factor(const LocalCsr& J) override {
    if (!symbolic_ || J.rows != n_ || J.rowptr != pattern_) {
      release(true);
      n_ = J.rows;
      pattern_ = J.rowptr;
      rowptr_ = J.rowptr;
      col_ = J.col;
      symbolic_ = klu_analyze(n_, rowptr_.data(), col_.data(), &common_);
      if (!symbolic_) return false;
    }
    release(false);
    val_ = J.val;
    numeric_ = klu_factor(rowptr_.data(), col_.data(), val_.data(), symbolic_, &common_);
    if (!numeric_ || common_.status != KLU_OK) return false;
    klu_rcond(symbolic_, numeric_, &common_);
    return common_.rcond > 1e-15;
  }
  void solve(const double* b, double* x) const override {
    std::copy(b, b + n_, x);
    klu_tsolve(symbolic_, numeric_, n_, 1, x, &common_);
  }
  std::string name() const override { return "KLU"; }

 private:
  void release(bool all) {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (all && symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }
  mutable klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  int n_ = -1;
  std::vector<int> pattern_, rowptr_, col_;
  std::vector<double> val_;
};

// Counts applications of the wrapped operator (the Hessian work n_A).
class CountingOperator : public Operator {
 public:
  explicit CountingOperator(const DelassusOperator& A) : A_(A) {}
  RCP<const Map> getDomainMap() const override { return A_.getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_.getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    count_ += static_cast<long long>(X.getNumVectors());
    A_.apply(X, Y, mode, alpha, beta);
  }
  long long count() const { return count_; }

 private:
  const DelassusOperator& A_;
  mutable long long count_ = 0;
};

// The contact KKT residuals of (r, u) (Contact::ContactKKT, as for FETI
// results) with g = mu r_N, the gap u_N and the slip u_T: forces and
// velocities are compared through max|r| and a velocity scale that includes
// the free velocity q (when every contact is closed and stuck, u is
// round-off and would not be a scale).
void kktResiduals(const std::vector<double>& r, const std::vector<double>& u, const std::vector<double>& mu,
                  const std::vector<double>& q, SolveReport& rep) {
  // std::max drops a nan, so a non-finite result would look exact here.
  if (!allFinite(r) || !allFinite(u)) {
    rep.kktNormal = rep.kktComplementarity = rep.kktFriction = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  Contact::ContactKKT kkt(std::max(normInf(r), 1e-300), std::max({normInf(u), normInf(q), 1e-300}));
  for (size_t k = 0; k < mu.size(); ++k)
    kkt.add(r[3 * k], u[3 * k], &r[3 * k + 1], &u[3 * k + 1], 2, mu[k] * std::max(r[3 * k], 0.0));
  rep.kktNormal = kkt.nonpenetration();
  rep.kktComplementarity = kkt.complementarity();
  rep.kktFriction = kkt.frictionLaw();
}

// defaultSolverParameters(), made once: building a parameter list takes
// microseconds, more than NSGS takes to solve a small problem.
const Teuchos::ParameterList& cachedDefaults() {
  static const Teuchos::ParameterList defaults = defaultSolverParameters();
  return defaults;
}

// The "Solver" list: the defaults with the user's entries set over them
// (sublists recursively), so a user list overrides only what it names.
Teuchos::ParameterList solverList(const SolveOptions& options) {
  Teuchos::ParameterList params(cachedDefaults());
  params.setParameters(options.solverParams);
  return params;
}

// The factor of the result check: the list's "Result Check Factor" (as
// Tribos_Run.cpp reads it for FETI runs), else the options'.
double resultCheckFactor(const Teuchos::ParameterList& params, const SolveOptions& options) {
  const double factor = params.isParameter("Result Check Factor") ? params.get<double>("Result Check Factor")
                                                                   : options.resultCheckFactor;
  if (!(factor >= 1.0) || !std::isfinite(factor))
    throw Error("FCLIB solve: Result Check Factor = " + std::to_string(factor) + ", expected >= 1");
  return factor;
}

using SolverPtr = RCP<Friction::FrictionSolver>;

// Extreme eigenvalues of the symmetric part of W, formed densely.
void spectrum(const DelassusOperator& op, int n, SolveReport& rep) {
  Progress::stage("eigenvalues of W (dense, " + std::to_string(n) + " x " + std::to_string(n) + ")");
  std::vector<double> D = op.dense();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < i; ++j) {
      const double s = 0.5 * (D[static_cast<size_t>(i) * n + j] + D[static_cast<size_t>(j) * n + i]);
      D[static_cast<size_t>(i) * n + j] = D[static_cast<size_t>(j) * n + i] = s;
    }
  std::vector<double> eig(n), work(1);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.SYEV('N', 'U', n, D.data(), n, eig.data(), work.data(), -1, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.SYEV('N', 'U', n, D.data(), n, eig.data(), work.data(), static_cast<int>(work.size()), &info);
  if (info != 0) return;
  rep.spectrumKnown = true;
  rep.eigMin = eig.front();
  rep.eigMax = eig.back();
  rep.numericalRank =
      static_cast<int>(std::count_if(eig.begin(), eig.end(), [&](double e) { return e > 1e-12 * rep.eigMax; }));
}

// W = 0 (no contacts, or contacts no degree of freedom sees): u = q whatever
// r, so the problem has a solution exactly when r = 0 is one, i.e. when q
// itself satisfies Coulomb's law. The friction solvers need a nonzero
// Hessian; this case is settled without them.
SolveReport solveWithZeroW(const std::vector<double>& q, const std::vector<double>& mu, const SolveOptions& options) {
  SolveReport rep;
  rep.algorithm = options.algorithm;
  rep.r.assign(q.size(), 0.0);
  rep.u = q;
  rep.status.converged = true;
  rep.status.reason = mu.empty() ? "no contacts: r and u are empty" : "W = 0: u = q whatever r, r = 0 checked";
  rep.note = mu.empty() ? "the problem has no contacts (mu is empty): r and u are empty"
                        : "W = 0: u = q whatever r; the problem has a solution (r = 0) exactly when q satisfies "
                          "Coulomb's law, which err and kkt check";
  rep.err = naturalMapError(rep.r, rep.u, mu, q);
  kktResiduals(rep.r, rep.u, mu, q, rep);
  return rep;
}

ContactDualPtr contactDual(const Operator& A, const std::vector<double>& q, const std::vector<double>& mu,
                           const RCP<const Map>& map);

// The common part: W (as op), q, mu -> r, u, status, err, spectrum.
SolveReport solveReduced(DelassusOperator& op, const std::vector<double>& q, const std::vector<double>& mu,
                         const SolveOptions& options, Friction::FrictionSolver& solver, const RCP<const Map>& map,
                         double kktLimit) {
  SolveReport rep;
  rep.algorithm = options.algorithm;
  const int nc = static_cast<int>(mu.size());
  const int n = 3 * nc;
  const auto t0 = std::chrono::steady_clock::now();
  if (n <= options.denseSpectrumLimit) spectrum(op, n, rep);
  CountingOperator A(op);
  const auto cd = contactDual(A, q, mu, map);
  // s W, -s q with s = 1/||W||; the power steps are not solver work. The
  // local problem has no equality constraint: the scaling is the whole chain.
  auto scaling = rcp(new Friction::ScalingTransform(50));
  Friction::DualTransformChain transforms;
  transforms.add(scaling).forward(*cd);
  const long long n_A0 = A.count();
  rep.normW = scaling->norm();
  rep.scale = scaling->scale();
  if (options.verbose)
    std::cout << "FCLIB: " << nc << " contacts, ||W|| ~ " << rep.normW << ", eig(W) in [" << rep.eigMin << ", "
              << rep.eigMax << "], numerical rank " << rep.numericalRank << ", ||q|| " << std::sqrt(std::inner_product(q.begin(), q.end(), q.begin(), 0.0)) << "\n";
  if (options.verbose) solver.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(std::cout)));
  LocalCsr explicitW;
  if (auto* newton = dynamic_cast<Friction::SemismoothNewton*>(&solver)) {
    explicitW = op.explicitMatrix();
    newton->setHessianMatrix(&explicitW, rep.scale);
    // KLU for sparse W; LAPACK's dense LU once W has more than a tenth of
    // its entries (FETI exports: W = H'M^-1 H is dense), where a sparse
    // factorization only adds indexing to the same fill.
    const double density = static_cast<double>(explicitW.col.size()) / std::max(1.0, double(n) * n);
    newton->setLinearSolver(density > 0.1 ? Friction::denseLuSolver()
                                          : RCP<Friction::NewtonLinearSolver>(rcp(new KluNewtonSolver())));
    const double s = rep.scale;  // v = A r - b = s (W r + q) = s u
    newton->setStoppingMeasure([&q, &mu, s](const std::vector<double>& r, const std::vector<double>& v) {
      std::vector<double> u(v.size());
      for (size_t i = 0; i < v.size(); ++i) u[i] = v[i] / s;
      return naturalMapError(r, u, mu, q).relativeToQ;
    });
  }
  rep.timeSetup = seconds(t0);
  const auto t1 = std::chrono::steady_clock::now();
  Vector x(map);
  const double target = options.naturalMapTolerance;
  const int rounds = target > 0 ? options.toleranceRounds : 1;
  double requested = target > 0 ? solver.requestedTolerance() : 0;
  int iterationsLeft = options.maxIterations;
  for (int round = 1; round <= rounds; ++round) {
    Progress::stage(options.algorithm + " solve" + (round > 1 ? ", round " + std::to_string(round) : ""));
    const Friction::FrictionStatus s = solver.solve(*cd, x);
    // The counts of every round, the state of the last.
    rep.status = round == 1 ? s : Friction::followedBy(rep.status, s);
    rep.rounds = round;
    transforms.back(x);
    {
      auto xv = x.getData();
      rep.r.assign(xv.begin(), xv.end());
    }
    op.applyW(rep.r, rep.u);
    for (int i = 0; i < n; ++i) rep.u[i] += q[i];
    rep.err = naturalMapError(rep.r, rep.u, mu, q);
    if (target <= 0) break;
    rep.roundErrors.push_back(rep.err.relativeToQ);
    // Met when the natural-map error and the KKT residuals of the result
    // check (judgeResult) are: a next round is asked for when either is not.
    kktResiduals(rep.r, rep.u, mu, q, rep);
    const bool met = rep.err.relativeToQ <= target && rep.kktNormal <= kktLimit &&
                     rep.kktComplementarity <= kktLimit && rep.kktFriction <= kktLimit;
    if (!s.converged || met || round == rounds) break;
    // The algorithm met its own test but not the natural-map error: ask again
    // from this result, the tolerance scaled by how far the error is off.
    const int used = s.msa_iterations > 0 ? s.msa_iterations : s.outer_iterations;  // the loop the limit counts
    if (iterationsLeft > 0) {
      iterationsLeft -= used;
      if (iterationsLeft <= 0) {
        rep.status.converged = false;
        rep.status.reason = "--max-iterations (" + std::to_string(options.maxIterations) +
                            ") reached before the natural-map error met the tolerance";
        break;
      }
      solver.setMaximumIterations(iterationsLeft);
    }
    if (Friction::atTightestTolerance(requested)) break;
    requested = Friction::tightenedTolerance(requested, target, rep.err.relativeToQ);
    solver.setRequestedTolerance(requested);
  }
  if (target > 0 && rep.status.converged && rep.err.relativeToQ > target)
    rep.note = "the algorithm met its own stopping test " + std::to_string(rep.rounds) +
               " time(s) with tightened tolerances (down to " + std::to_string(requested) +
               ") but not the natural-map tolerance";
  rep.timeSolve = seconds(t1);
  rep.n_A = A.count() - n_A0;
  kktResiduals(rep.r, rep.u, mu, q, rep);
  if (rep.spectrumKnown && rep.numericalRank < n && rep.note.empty()) {
    std::ostringstream s;
    s << "W is singular (numerical rank " << rep.numericalRank << " of " << n
      << "): the Tresca subproblems are convex but not strictly, so MPRGP/MPGP/SMALBE rate bounds and the "
         "uniqueness of r do not apply";
    rep.note = s.str();
  }
  return rep;
}

// NSGS on W's entries: no Tpetra map, no scaling (the local solves use
// W_cc as it is), the natural-map error ||F_nat|| / ||q|| as its stopping
// measure. rep.u = W r + q of the returned r (NSGS forms it from W's entries
// after its last sweep) and rep.err its natural-map error (the measure's
// last call is on the returned r and u); the KKT residuals are the caller's.
SolveReport solveExplicit(const CsrView& W, const std::vector<double>& q, const std::vector<double>& mu,
                          const SolveOptions& options, Friction::NonsmoothGaussSeidel& nsgs) {
  SolveReport rep;
  rep.algorithm = options.algorithm;
  const auto t0 = std::chrono::steady_clock::now();
  Progress::stage(options.algorithm + " solve");
  if (options.verbose) nsgs.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(std::cout)));
  nsgs.setStoppingMeasure([&q, &mu, &rep](const std::vector<double>& r, const std::vector<double>& u) {
    rep.err = naturalMapError(r, u, mu, q);
    return rep.err.relativeToQ;
  });
  rep.r.assign(q.size(), 0.0);
  rep.status = nsgs.solve({W, q.data(), mu.data(), static_cast<int>(mu.size())}, rep.r, rep.u);
  nsgs.setStoppingMeasure(nullptr);  // it refers to q and mu of this call
  rep.n_A = rep.status.n_A;
  rep.timeSolve = seconds(t0);
  return rep;
}

// The Tresca QP of the slip bound g: A = W, b = -q, normal row 3k,
// tangential rows 3k+1, 3k+2, no equality constraint.
ContactDualPtr contactDual(const Operator& A, const std::vector<double>& q, const std::vector<double>& mu,
                           const RCP<const Map>& map) {
  const int nc = static_cast<int>(mu.size());
  auto cd = std::make_shared<Friction::ContactDual>();
  cd->A = Teuchos::rcpFromRef(A);
  auto b = rcp(new Vector(map));
  {
    auto bv = b->getDataNonConst();
    for (int i = 0; i < 3 * nc; ++i) bv[i] = -q[i];
  }
  cd->b = b;
  for (int k = 0; k < nc; ++k) {
    cd->normalRows.push_back(3 * k);
    cd->tangentRows.push_back(3 * k + 1);
    cd->tangentRows.push_back(3 * k + 2);
  }
  cd->normalLower.assign(nc, 0.0);
  cd->normalOffset.assign(nc, 0.0);
  cd->slipBound.assign(nc, 0.0);
  cd->frictionCoefficient = mu;
  cd->check();
  return cd;
}

RCP<const Map> serialMap(int n, const RCP<const Comm>& comm) {
  return rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, comm));
}

const char* kContext = "FCLIB solve";

// Whether the registered algorithm 'name' solves Coulomb problems (FETI
// duals or explicit ones).
bool solvesCoulomb(const std::string& name) {
  const auto& registry = Friction::frictionSolvers();
  return registry.accepts(name, "Coulomb") || registry.accepts(name, Friction::kExplicitCoulomb);
}

}  // namespace

// The method, its parameters and the result check, validated before any work.
Solver::Solver(const SolveOptions& options, const RCP<const Comm>& serialComm)
    : options_(options), comm_(serialComm) {
  if (comm_->getSize() != 1)
    throw Error("FCLIB solve: use a communicator of one rank (got " + std::to_string(comm_->getSize()) + ")");
  // Without user entries the defaults are the list (no copy).
  Teuchos::ParameterList merged;
  const Teuchos::ParameterList& params =
      options.solverParams.numParams() == 0 ? cachedDefaults() : (merged = solverList(options));
  const auto& registry = Friction::frictionSolvers();
  if (registry.has(options.algorithm) && !solvesCoulomb(registry.canonical(options.algorithm)))
    throw Error("FCLIB solve: algorithm \"" + options.algorithm +
                "\" does not solve Coulomb friction, the law of FCLIB problems; valid: " +
                joinNames(coulombAlgorithms()));
  if (!(options.naturalMapTolerance >= 0 && options.naturalMapTolerance < 1))
    throw Error("FCLIB solve: tolerance " + std::to_string(options.naturalMapTolerance) +
                " on ||F_nat||/||q||, expected in [0, 1) (0: the algorithm's own)");
  if (options.maxIterations < 0)
    throw Error("FCLIB solve: maximum iterations " + std::to_string(options.maxIterations) +
                ", expected >= 0 (0: the algorithm's own)");
  if (options.toleranceRounds < 1)
    throw Error("FCLIB solve: tolerance rounds " + std::to_string(options.toleranceRounds) + ", expected >= 1");
  const double factor = resultCheckFactor(params, options);
  if (!(options.symmetryTolerance >= 0 && options.symmetryTolerance < 1))
    throw Error("FCLIB solve: symmetry tolerance " + std::to_string(options.symmetryTolerance) +
                ", expected in [0, 1)");
  solver_ = registry.create(options.algorithm, params);
  // NSGS solves the contacts' Coulomb problems and Semismooth Newton the
  // Alart-Curnier equations, for any W; the others minimize a quadratic in W.
  needsSymmetricW_ = !dynamic_cast<Friction::NonsmoothGaussSeidel*>(solver_.get()) &&
                     !dynamic_cast<Friction::SemismoothNewton*>(solver_.get());
  resetLimits();
  tolerance_ = options.naturalMapTolerance > 0 ? options.naturalMapTolerance : solver_->requestedTolerance();
  limit_ = factor * tolerance_;
}

// The tolerance and iteration limit the options set (the rounds of a solve
// tighten them; every solve starts from these). Set again only after a solve
// that may have changed them: a validated parameter-list update costs more
// than NSGS on a small problem.
void Solver::resetLimits() const {
  if (limitsAsGiven_) return;
  if (options_.naturalMapTolerance > 0) solver_->setRequestedTolerance(std::max(options_.naturalMapTolerance, 1e-15));
  if (options_.maxIterations > 0) solver_->setMaximumIterations(options_.maxIterations);
  limitsAsGiven_ = true;
}

std::string Solver::source() const { return options_.source.empty() ? kContext : options_.source; }

void Solver::requireSymmetric(const LocalCsr& W) const {
  if (!needsSymmetricW_ || W.rows == 0) return;
  const Asymmetry worst = largestAsymmetry(W);
  const double scale = maxAbs(W), difference = std::abs(worst.value - worst.mirror);
  if (difference <= options_.symmetryTolerance * scale) return;
  std::ostringstream os;
  os << std::setprecision(6) << source() << ": W (/fclib_local/W) is not symmetric: W(" << worst.row << ", "
     << worst.col << ") = " << worst.value << " but W(" << worst.col << ", " << worst.row << ") = " << worst.mirror
     << " (rows and columns from 0; contacts " << worst.row / 3 << " and " << worst.col / 3 << "), a difference of "
     << difference << " > " << options_.symmetryTolerance << " max|W| = " << options_.symmetryTolerance * scale
     << "; " << options_.algorithm
     << " minimizes 1/2 r'W r + q'r and needs W symmetric (NSGS and Semismooth Newton do not: --algorithm)";
  throw Error(os.str());
}

namespace {

void finish(double tolerance, double limit, const SolveOptions& options, SolveReport& rep) {
  rep.tolerance = tolerance;
  rep.limit = limit;
  rep.naturalMapTolerance = options.naturalMapTolerance;
  judgeResult(rep);
}

}  // namespace

std::vector<std::string> coulombAlgorithms() {
  std::vector<std::string> out;
  for (const auto& name : Friction::frictionSolvers().names())
    if (solvesCoulomb(name)) out.push_back(name);
  return out;
}

void judgeResult(SolveReport& rep) {
  const bool finite = allFinite(rep.r) && allFinite(rep.u) && allFinite(rep.v);
  const std::pair<const char*, double> figures[] = {
      {"natural-map error (relative to max(||q||, ||r||, ||u||))", rep.err.relativeToMax},
      {"non-penetration", rep.kktNormal},
      {"complementarity", rep.kktComplementarity},
      {"friction law", rep.kktFriction}};
  const auto* over = std::find_if(std::begin(figures), std::end(figures),
                                  [&](const auto& f) { return !(f.second <= rep.limit); });  // a nan fails too
  const bool naturalMapMissed = rep.naturalMapTolerance > 0 && !(rep.err.relativeToQ <= rep.naturalMapTolerance);
  rep.converged = rep.status.converged && finite && !naturalMapMissed && over == std::end(figures);
  if (rep.converged) {  // no text to build in the common case
    rep.stopReason = rep.status.reason.empty() ? "converged" : rep.status.reason;
    return;
  }
  std::ostringstream reason;
  if (!rep.status.converged)
    reason << (rep.status.reason.empty() ? "the solver did not converge" : rep.status.reason);
  else if (!finite)
    reason << "the result has non-finite entries";
  else if (naturalMapMissed)
    reason << "the natural-map error ||F_nat||/||q|| of the result, " << rep.err.relativeToQ
           << ", exceeds the requested tolerance " << rep.naturalMapTolerance;
  else
    reason << "the " << over->first << " of the result, " << over->second << ", exceeds " << rep.limit
           << " (Result Check Factor times the requested tolerance " << rep.tolerance << ")";
  rep.stopReason = reason.str();
}

SolveReport Solver::solve(const LocalProblem& problem) const {
  validate(problem, kContext);
  if (problem.V || problem.R || problem.s)
    throw Error("FCLIB solve: mixed local problems (V, R, s) are not supported");
  if (problem.spacedim != 3) throw Error("FCLIB solve: only spacedim = 3 is supported");
  requireSymmetric(problem.W);
  resetLimits();
  const int n = 3 * problem.numberOfContacts();
  SolveReport rep;
  if (isZero(problem.W)) {
    rep = solveWithZeroW(problem.q, problem.mu, options_);
  } else if (auto* nsgs = dynamic_cast<Friction::NonsmoothGaussSeidel*>(solver_.get())) {
    rep = solveExplicit(problem.W.view(), problem.q, problem.mu, options_, *nsgs);
    if (n <= options_.denseSpectrumLimit) spectrum(DelassusOperator(problem.W, serialMap(n, comm_)), n, rep);
    kktResiduals(rep.r, rep.u, problem.mu, problem.q, rep);
  } else {
    const auto map = serialMap(n, comm_);
    DelassusOperator op(problem.W, map);
    limitsAsGiven_ = false;  // its rounds may tighten them
    rep = solveReduced(op, problem.q, problem.mu, options_, *solver_, map, limit_);
  }
  finish(tolerance_, limit_, options_, rep);
  return rep;
}

SolveReport Solver::solve(const GlobalProblem& problem) const {
  validate(problem, kContext);
  if (problem.G) throw Error("FCLIB solve: global problems with equality constraints G are not supported");
  if (problem.spacedim != 3) throw Error("FCLIB solve: only spacedim = 3 is supported");
  resetLimits();
  const int n = 3 * problem.numberOfContacts();
  const auto map = serialMap(n, comm_);
  const auto t0 = std::chrono::steady_clock::now();
  auto M = std::make_shared<const MassSolver>(problem.M, options_.massSolver, source());
  // q = H' M^-1 f + w: the contact velocities at r = 0.
  std::vector<double> vFree, q;
  M->solve(problem.f, vFree);
  problem.H.multiplyTranspose(vFree, q);
  for (size_t i = 0; i < q.size(); ++i) q[i] += problem.w[i];
  const double reduction = seconds(t0);
  SolveReport rep;
  if (isZero(problem.H)) {  // W = H'M^-1 H = 0
    rep = solveWithZeroW(q, problem.mu, options_);
  } else if (auto* nsgs = dynamic_cast<Friction::NonsmoothGaussSeidel*>(solver_.get())) {
    DelassusOperator op(problem.H, M, map);
    const auto t1 = std::chrono::steady_clock::now();
    Progress::stage("W = H'M^-1 H (" + std::to_string(n) + " solves with M)");
    const LocalCsr W = op.explicitMatrix();  // H' M^-1 H, from n solves with M
    const double formW = seconds(t1);
    rep = solveExplicit(W.view(), q, problem.mu, options_, *nsgs);
    rep.timeSetup += formW;
    if (n <= options_.denseSpectrumLimit) spectrum(op, n, rep);  // the W op formed above
  } else {
    DelassusOperator op(problem.H, M, map);
    limitsAsGiven_ = false;  // its rounds may tighten them
    rep = solveReduced(op, q, problem.mu, options_, *solver_, map, limit_);
  }
  rep.timeSetup += reduction;
  // v = M^-1 (H r + f), and u = H' v + w from it (the same as W r + q up to round-off).
  std::vector<double> rhs;
  problem.H.multiply(rep.r, rhs);
  for (size_t i = 0; i < rhs.size(); ++i) rhs[i] += problem.f[i];
  M->solve(rhs, rep.v);
  problem.H.multiplyTranspose(rep.v, rep.u);
  for (size_t i = 0; i < rep.u.size(); ++i) rep.u[i] += problem.w[i];
  rep.err = naturalMapError(rep.r, rep.u, problem.mu, q);
  kktResiduals(rep.r, rep.u, problem.mu, q, rep);
  rep.massSolves = M->solves();
  rep.mass = M;
  finish(tolerance_, limit_, options_, rep);
  return rep;
}

SolveReport solve(const LocalProblem& problem, const SolveOptions& options, const RCP<const Comm>& serialComm) {
  return Solver(options, serialComm).solve(problem);
}

SolveReport solve(const GlobalProblem& problem, const SolveOptions& options, const RCP<const Comm>& serialComm) {
  return Solver(options, serialComm).solve(problem);
}

}  // namespace FCLIB
}  // namespace Tribos
