#include "Tribos_SemismoothStarNewton.hpp"

#include "Tribos_Progress.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_Time.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>

#include "Tribos_Error.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_FetiOperators.hpp"
#include "Tribos_QP_Projection.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

bool inContact(NodeState s) { return s == NodeState::ContactStick || s == NodeState::ContactSlip; }
bool sticks(NodeState s) { return s == NodeState::NoContactStick || s == NodeState::ContactStick; }

}  // namespace

const NewtonSolverRegistry& newtonSolvers() {
  using Kind = NewtonSolverKind;
  static const NewtonSolverRegistry registry = [] {
    NewtonSolverRegistry r("semismooth* Newton solver");
    r.add("Sparse Direct", [] { return rcp(new Kind{Kind::Reduced, Kind::Factorization}); },
          "factor the Newton matrix in the full primal space each step, the method of the paper",
          {"Dense Schur"});
    r.add("Reduced CG", [] { return rcp(new Kind{Kind::Reduced, Kind::ConjugateGradients}); },
          "conjugate gradients on (S_FF + G_FF) dx_F = b_F, S applied by K_rr solves, Jacobi-preconditioned with "
          "diag(K_cc + G): no factorization per step",
          {"Dense Schur"});
    r.add("CG+MueLu", [] { return rcp(new Kind{Kind::FullSpace, Kind::ConjugateGradients}); },
          "no factorization at all: a full-space iterate u with (K u - f)_r = 0 gives S x - l = (K u - f)_c, Newton "
          "steps are full-space solves by Belos CG preconditioned with MueLu (inexact Newton) that also restore "
          "interior equilibrium; needs the node coordinates");
    return r;
  }();
  return registry;
}

std::string chosenNewtonSolver(const Teuchos::ParameterList& params, long long primalDofs, bool haveCoordinates) {
  const std::string name = params.get<std::string>("Newton Solver");
  if (name != kAutoNewtonSolver) return newtonSolvers().canonical(name);
  const bool direct = primalDofs <= kAutoSparseDirectMaxDofs || params.get<bool>("Dense Schur") || !haveCoordinates;
  return direct ? "Sparse Direct" : "CG+MueLu";
}

RCP<const Teuchos::ParameterList> SemismoothStarNewton::getValidParameters() {
  using Teuchos::tuple;
  auto pl = rcp(new Teuchos::ParameterList("SemismoothStarNewton"));
  pl->set("Tolerance", 1e-8, "stop when ||S x^ - l + y^|| <= Tolerance ||l|| after an approximation step",
          rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1.0)));
  pl->set("Maximum Iterations", 50, "maximum number of Newton steps",
          rcp(new Teuchos::EnhancedNumberValidator<int>(0, 100000)));
  pl->set("Dense Schur", false, "form S densely (3m K_rr solves) and solve the Newton systems densely; small meshes only");
  Teuchos::Array<std::string> solvers;
  for (const std::string& s : localSolverNames()) solvers.push_back(s);
  pl->set("Local Solver", "CHOLMOD", "sparse direct solver for K_rr and the Newton matrices",
          rcp(new Teuchos::StringValidator(solvers)));
  pl->set("Step Scaling", "Scalar",
          "a of the approximation step: Scalar a = 1/max diag K_cc, or Nodal a_i = 1/max diag of node i's block of K_cc "
          "(K_cc >= S, so both are below 1/diag S)",
          rcp(new Teuchos::StringValidator(tuple<std::string>("Scalar", "Nodal"))));
  pl->set("Step Size Factor", 10.0,
          "multiplies a; larger a lets the multiplier y rather than x decide stick/slip and contact, which avoids "
          "cycling of the stick/slip sets (1 cycles on the prism at level 2; 10 gives 6-7 iterations)", rcp(new Teuchos::EnhancedNumberValidator<double>(1e-12, 1e12)));
  pl->set("Newton Solver", kAutoNewtonSolver,
          "Auto (Sparse Direct up to " + std::to_string(kAutoSparseDirectMaxDofs) +
              " primal dofs, with Dense Schur or without node coordinates; CG+MueLu beyond); " +
              newtonSolvers().documentation(),
          newtonSolvers().validator({kAutoNewtonSolver}));
  pl->set("CG Tolerance", 1e-12, "Reduced CG: relative residual", rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1.0)));
  pl->set("CG Maximum Iterations", 2000, "Reduced CG and CG+MueLu: iteration limit of one CG solve",
          rcp(new Teuchos::EnhancedNumberValidator<int>(1, 1000000)));
  pl->set("MueLu Smoother", "Chebyshev", "CG+MueLu: smoother on all levels but the coarsest (factored)",
          rcp(new Teuchos::StringValidator(tuple<std::string>("Chebyshev", "Symmetric Gauss-Seidel"))));
  pl->set("MueLu Algorithm", "unsmoothed",
          "CG+MueLu: MueLu \"multigrid algorithm\" of the hierarchy of K_rr and the Newton matrices, set up again "
          "every step: unsmoothed (plain aggregation: sparser coarse operators, a third of the re-setup time, a few "
          "more CG steps; prism L8 on 2 ranks: 21.7 s of solve) or sa (smoothed aggregation)",
          rcp(new Teuchos::StringValidator(tuple<std::string>("sa", "unsmoothed"))));
  pl->set("MueLu Reuse", "RP",
          "CG+MueLu: MueLu \"reuse: type\" for the matrices of successive steps: RP keeps the prolongators "
          "(built once, on K's graph) and recomputes the coarse operators and smoothers, tP keeps the tentative "
          "prolongators, none rebuilds the hierarchy each step, full keeps the first hierarchy (K_rr's; slow, for "
          "experiments)",
          rcp(new Teuchos::StringValidator(tuple<std::string>("RP", "tP", "none", "full"))));
  pl->set("Equilibrium Tolerance", 1e-3,
          "CG+MueLu: relative CG tolerance of the initial K_rr solve for l (the Newton steps restore interior "
          "equilibrium themselves; a residual estimated below Tolerance is confirmed by a K_rr solve to the absolute "
          "tolerance 0.01 Tolerance ||l|| before stopping)",
          rcp(new Teuchos::EnhancedNumberValidator<double>(1e-14, 0.5)));
  pl->set("Forcing Term Maximum", 0.01,
          "CG+MueLu: the Newton solve stops at ||residual|| <= eta ||S x^ - l + y^||, eta = min(this, "
          "||S x^ - l + y^||/||l||) (inexact Newton, superlinear; the residual estimated), but not below "
          "0.1 Tolerance ||l||",
          rcp(new Teuchos::EnhancedNumberValidator<double>(1e-14, 0.9)));
  return pl;
}

void SemismoothStarNewton::checkParameters(const Teuchos::ParameterList& params) {
  Teuchos::ParameterList p(params);
  p.validateParametersAndSetDefaults(*getValidParameters());
  // Auto takes Sparse Direct with Dense Schur, whatever the size.
  const std::string solver = chosenNewtonSolver(p, 0, false);
  TRIBOS_REQUIRE(!p.get<bool>("Dense Schur") || newtonSolvers().accepts(solver, "Dense Schur"),
                 "\"Dense Schur\" = true needs S, which \"Newton Solver\" = " << solver << " does not form ("
                 << joinNames(newtonSolvers().accepting("Dense Schur")) << " do)");
}

SemismoothStarNewton::SemismoothStarNewton(const ContactProblem& problem, const Teuchos::ParameterList& params)
    : params_(params), contact_(problem.contact), numNodes_(problem.numNodes()) {
  params_.validateParametersAndSetDefaults(*getValidParameters());
  checkParameters(params_);
  // From here on the list names the solver that runs (FullSpaceNewton reads it).
  params_.set("Newton Solver", chosenNewtonSolver(params_, 3LL * problem.numNodes(), !problem.coords.empty()));
  newtonSolver_ = *newtonSolvers().create(params_.get<std::string>("Newton Solver"));
  if (newtonSolver_.space == NewtonSolverKind::FullSpace) {
    fullSpace_ = std::make_unique<FullSpaceNewton>(problem, params_);
  } else {
    reduction_ = std::make_unique<ContactReduction>(problem, params_.get<std::string>("Local Solver"));
  }
  const RotatedSystem& sys = fullSpace_ ? fullSpace_->system() : reduction_->system();
  const int m = sys.m;
  const std::vector<double> dmax = sys.nodalMaxDiagonalKcc();
  const double factor = params_.get<double>("Step Size Factor");
  a_.assign(m, 0.0);
  const double global = *std::max_element(dmax.begin(), dmax.end());
  for (int i = 0; i < m; ++i) {
    const double dii = params_.get<std::string>("Step Scaling") == "Nodal" ? dmax[i] : global;
    TRIBOS_REQUIRE(dii > 0, "semismooth*: K_cc has a non-positive diagonal at contact node " << contact_[i].node);
    a_[i] = factor / dii;
  }
  if (params_.get<bool>("Dense Schur")) {
    Teuchos::Time timer("dense S");
    timer.start();
    denseS_ = reduction_->denseS();
    timer.stop();
    denseSeconds_ = timer.totalElapsedTime();
  }
}

SemismoothStarNewton::~SemismoothStarNewton() = default;

const ContactReduction& SemismoothStarNewton::reduction() const {
  TRIBOS_REQUIRE(reduction_, "semismooth*: \"Newton Solver\" = CG+MueLu does not reduce the problem (no S, no K_rr factor)");
  return *reduction_;
}

void SemismoothStarNewton::applyS(const std::vector<double>& x, std::vector<double>& Sx) const {
  if (denseS_.empty()) return reduction_->applyS(x, Sx);
  const int n = static_cast<int>(x.size());
  Sx.assign(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) Sx[i] += denseS_[static_cast<size_t>(j) * n + i] * x[j];
}

// w = x - a (S x - l); x^ = prox_{a psi}(w) node by node, y^ = (w - x^)/a, so
// that y^ lies in d psi(x^):
//   x^_nu = min(w_nu, d_i),  x^_tau = w_tau max(0, 1 - a g_i / ||w_tau||).
// A node is in contact when y^_nu > 0 (weak contact, w_nu = d_i, counts as
// no contact) and sticks when x^_tau = 0. tau are the free tangential
// directions only: a direction fixed by a Dirichlet condition keeps its
// value and has no friction (y^ = 0 there), the other one has the same
// bound g_i in 1D. Without friction (g_i = 0) the prox is the identity on
// tau and a node never sticks: its tangential rule is dy_tau = 0, which
// holds at x^_tau = 0 as well. A node with no free tangential direction
// cannot slide and counts as sticking.
SemismoothStarNewton::Approximation SemismoothStarNewton::approximationStep(const std::vector<double>& x,
                                                                            const std::vector<double>& Sxl) const {
  const int m = static_cast<int>(contact_.size());
  const std::vector<char>& prescribed = system().prescribed;
  Approximation ap;
  ap.x.resize(3 * m);
  ap.y.resize(3 * m);
  ap.state.resize(m);
  for (int i = 0; i < m; ++i) {
    const double a = a_[i], g = contact_[i].g, d = contact_[i].d;
    double w[3];
    for (int k = 0; k < 3; ++k) w[k] = x[3 * i + k] - a * Sxl[3 * i + k];
    const bool contact = w[2] > d;
    ap.x[3 * i + 2] = contact ? d : w[2];
    double wt2 = 0;
    int freeTangential = 0;
    for (int k = 0; k < 2; ++k)
      if (!prescribed[3 * i + k]) {
        wt2 += w[k] * w[k];
        ++freeTangential;
      }
    const double wt = std::sqrt(wt2);
    const bool stick = freeTangential == 0 || (g > 0 && wt <= a * g);
    // prox of a g ||.|| on w_tau: w_tau - P_ag(w_tau) (Moreau)
    const double shrink = stick ? 0.0 : 1.0 - QP::ballFactor(wt, a * g);
    for (int k = 0; k < 2; ++k) {
      const int j = 3 * i + k;
      ap.x[j] = prescribed[j] ? system().xPrescribed[j] : shrink * w[k];
      ap.y[j] = prescribed[j] ? 0.0 : (w[k] - ap.x[j]) / a;
    }
    ap.y[3 * i + 2] = (w[2] - ap.x[3 * i + 2]) / a;
    ap.state[i] = contact ? (stick ? NodeState::ContactStick : NodeState::ContactSlip)
                          : (stick ? NodeState::NoContactStick : NodeState::NoContactSlip);
    ap.contact += contact;
    ap.stick += stick;
  }
  ap.slip = m - ap.stick;
  return ap;
}

// Newton step: S dx + dy = -residual with, per node,
//   no contact: dy_nu = 0;   contact: dx_nu = 0;
//   stick: dx_tau = 0;       slide: dy_tau = (g/||x^_tau||)(I - t t') dx_tau, t = x^_tau/||x^_tau||.
// Eliminating dy leaves (S_FF + G_FF) dx_F = -residual_F on the free components F.
// Prescribed tangential directions are never free. With one free tangential
// direction (1D friction) or g = 0, I - t t' (resp. g) vanishes: G = 0.
void SemismoothStarNewton::linearization(const Approximation& ap, std::vector<char>& freeComp,
                                         std::vector<std::array<double, 4>>& G) const {
  const int m = static_cast<int>(contact_.size());
  const std::vector<char>& prescribed = system().prescribed;
  freeComp.assign(3 * m, 0);
  G.assign(m, {0, 0, 0, 0});
  for (int i = 0; i < m; ++i) {
    freeComp[3 * i + 2] = !inContact(ap.state[i]);
    if (sticks(ap.state[i])) continue;
    for (int k = 0; k < 2; ++k) freeComp[3 * i + k] = !prescribed[3 * i + k];
    if (!freeComp[3 * i] || !freeComp[3 * i + 1] || contact_[i].g == 0) continue;
    const double xt = std::hypot(ap.x[3 * i], ap.x[3 * i + 1]);
    const double t[2] = {ap.x[3 * i] / xt, ap.x[3 * i + 1] / xt}, c = contact_[i].g / xt;
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) G[i][2 * p + q] = c * ((p == q) - t[p] * t[q]);
  }
}

void SemismoothStarNewton::newtonStep(const Approximation& ap, const std::vector<double>& residual,
                                      std::vector<double>& dx, std::vector<double>& Sdx) {
  const int nc = 3 * reduction_->numContactNodes();
  std::vector<char> freeComp;
  std::vector<std::array<double, 4>> G;
  linearization(ap, freeComp, G);
  std::vector<double> rhs(nc);
  for (int j = 0; j < nc; ++j) rhs[j] = -residual[j];
  if (denseS_.empty() && newtonSolver_.step == NewtonSolverKind::ConjugateGradients)
    return reducedCG(freeComp, G, rhs, dx, Sdx);
  if (denseS_.empty()) return reduction_->newtonSolve(freeComp, G, rhs, dx, Sdx);

  std::vector<int> F;
  for (int j = 0; j < nc; ++j)
    if (freeComp[j]) F.push_back(j);
  const int nF = static_cast<int>(F.size());
  std::vector<double> A(static_cast<size_t>(nF) * nF), b(nF);
  for (int q = 0; q < nF; ++q) {
    b[q] = rhs[F[q]];
    for (int p = 0; p < nF; ++p) {
      double v = denseS_[static_cast<size_t>(F[q]) * nc + F[p]];
      const int i = F[p] / 3;
      if (F[p] / 3 == F[q] / 3 && F[p] % 3 < 2 && F[q] % 3 < 2) v += G[i][2 * (F[p] % 3) + F[q] % 3];
      A[static_cast<size_t>(q) * nF + p] = v;
    }
  }
  if (nF > 0) {
    Feti::DenseCholesky cholesky;  // LAPACK, as FETI's coarse problem
    TRIBOS_REQUIRE(cholesky.tryFactor(std::move(A), nF), "semismooth*: dense Newton matrix is not positive definite");
    cholesky.solve(b);
  }
  dx.assign(nc, 0.0);
  for (int q = 0; q < nF; ++q) dx[F[q]] = b[q];
  applyS(dx, Sdx);
}

// Preconditioned CG on (S_FF + G_FF) dx_F = rhs_F; S dx is accumulated from
// the products S p of the iteration.
void SemismoothStarNewton::reducedCG(const std::vector<char>& freeComp, const std::vector<std::array<double, 4>>& G,
                                     const std::vector<double>& rhs, std::vector<double>& dx, std::vector<double>& Sdx) {
  const int nc = static_cast<int>(rhs.size());
  if (diagKcc_.empty()) diagKcc_ = reduction_->diagonalKcc();
  auto applyA = [&](const std::vector<double>& v, std::vector<double>& Sv, std::vector<double>& Av) {
    applyS(v, Sv);
    Av = Sv;
    for (int j = 0; j < nc; ++j) {
      if (!freeComp[j]) {
        Av[j] = 0;
        continue;
      }
      if (j % 3 < 2) {
        const int i = j / 3, p = j % 3;
        Av[j] += G[i][2 * p] * v[3 * i] + G[i][2 * p + 1] * v[3 * i + 1];
      }
    }
  };
  std::vector<double> r(nc), z(nc), p(nc), Sp, Ap;
  dx.assign(nc, 0.0);
  Sdx.assign(nc, 0.0);
  for (int j = 0; j < nc; ++j) r[j] = freeComp[j] ? rhs[j] : 0.0;
  const double bnorm = norm2(r), tol = params_.get<double>("CG Tolerance") * bnorm;
  const int maxIt = params_.get<int>("CG Maximum Iterations");
  auto precondition = [&]() {
    for (int j = 0; j < nc; ++j) z[j] = freeComp[j] ? r[j] / (diagKcc_[j] + (j % 3 < 2 ? G[j / 3][3 * (j % 3)] : 0.0)) : 0.0;
  };
  precondition();
  p = z;
  double rz = 0;
  for (int j = 0; j < nc; ++j) rz += r[j] * z[j];
  for (int it = 0; it < maxIt && norm2(r) > tol; ++it) {
    applyA(p, Sp, Ap);
    ++cgIterations_;
    double pAp = 0;
    for (int j = 0; j < nc; ++j) pAp += p[j] * Ap[j];
    const double alpha = rz / pAp;
    for (int j = 0; j < nc; ++j) {
      dx[j] += alpha * p[j];
      Sdx[j] += alpha * Sp[j];
      r[j] -= alpha * Ap[j];
    }
    precondition();
    double rzNew = 0;
    for (int j = 0; j < nc; ++j) rzNew += r[j] * z[j];
    for (int j = 0; j < nc; ++j) p[j] = z[j] + rzNew / rz * p[j];
    rz = rzNew;
  }
  TRIBOS_REQUIRE(norm2(r) <= tol || bnorm == 0, "semismooth*: Reduced CG did not reach " << params_.get<double>("CG Tolerance")
                                                                                       << " in " << maxIt << " steps");
}

void SemismoothStarNewton::record(SemismoothResult& res, const Approximation& ap, double rel, int k,
                                  std::ostream* log) const {
  res.residuals.push_back(rel);
  res.numContact.push_back(ap.contact);
  res.numStick.push_back(ap.stick);
  res.numSlip.push_back(ap.slip);
  if (log)
    *log << "  " << std::setw(4) << k << "   " << std::scientific << std::setprecision(6) << std::setw(22) << rel
         << std::defaultfloat << std::setw(9) << ap.contact << std::setw(8) << ap.stick << std::setw(8) << ap.slip
         << std::endl;  // flushed: large levels take minutes per step
}

// S applied by K_rr solves (or densely); S x for the next approximation step
// is S x^ + S dx from the Newton step. The residuals are exact up to the
// direct solver's round-off.
void SemismoothStarNewton::solveReduced(SemismoothResult& res, Approximation& ap, std::ostream* log) {
  const int nc = 3 * reduction_->numContactNodes();
  const std::vector<double>& l = reduction_->l();
  const double lnorm = norm2(l), scale = lnorm > 0 ? lnorm : 1.0;
  const double tol = params_.get<double>("Tolerance");
  const int maxIt = params_.get<int>("Maximum Iterations");
  std::vector<double> x(nc, 0.0), Sx(nc, 0.0), Sxl(nc), Sxh, r(nc), dx, Sdx;
  for (int k = 0;; ++k) {
    for (int j = 0; j < nc; ++j) Sxl[j] = Sx[j] - l[j];
    ap = approximationStep(x, Sxl);
    applyS(ap.x, Sxh);
    for (int j = 0; j < nc; ++j) r[j] = Sxh[j] - l[j] + ap.y[j];
    const double rel = norm2(r) / scale;
    record(res, ap, rel, k, log);
    Progress::iteration([&] { return "Newton " + std::to_string(k) + ": relative residual " + Progress::sci(rel); });
    if (rel <= tol) {
      res.converged = true;
      break;
    }
    if (k == maxIt) break;
    newtonStep(ap, r, dx, Sdx);
    for (int j = 0; j < nc; ++j) {
      x[j] = ap.x[j] + dx[j];
      Sx[j] = Sxh[j] + Sdx[j];
    }
    res.iterations = k + 1;
  }
}

// ||(x - x^)/a||: the natural residual of the variational inequality (the
// step of the proximal map), free of S. Since y^ = (x - x^)/a - (S x - l),
//   S x^ - l + y^ = (I/a - S)(x - x^),
// so it is the reported residual up to a factor of the size of 1 + a ||S||.
double SemismoothStarNewton::naturalResidual(const std::vector<double>& x, const Approximation& ap) const {
  double s = 0;
  for (size_t j = 0; j < x.size(); ++j) {
    const double d = (x[j] - ap.x[j]) / a_[j / 3];
    s += d * d;
  }
  return std::sqrt(s);
}

// "CG+MueLu": S x - l = (K u - f)_c from the full-space iterate. The Newton
// step starts from u with its contact part moved to x^ and restores the
// interior equilibrium in the same solve, so S x^ - l is not known at each
// step without a correction solve with K_rr (which cost as many CG steps as
// the Newton steps). The residual ||S x^ - l + y^|| of each step is
// therefore estimated as the natural residual ||(x - x^)/a|| times the
// ratio of the two measured at the last confirmation (10, the step size
// factor, before the first). An estimate at or below Tolerance, or the
// last step allowed, is confirmed: a correction at x^ to the absolute
// tolerance 0.01 Tolerance ||l|| (the map (K u - f)_r -> error of S x^ - l
// is K_cr K_rr^-1, of norm about 1) gives the residual itself, which alone
// decides convergence.
void SemismoothStarNewton::solveFullSpace(SemismoothResult& res, Approximation& ap, std::ostream* log) {
  const int nc = 3 * fullSpace_->system().m;
  const double lnorm = norm2(fullSpace_->l()), scale = lnorm > 0 ? lnorm : 1.0;
  const double tol = params_.get<double>("Tolerance"), etaMax = params_.get<double>("Forcing Term Maximum");
  const int maxIt = params_.get<int>("Maximum Iterations");
  std::vector<double> x(nc, 0.0), Sxl = fullSpace_->l(), r(nc);
  for (double& v : Sxl) v = -v;  // S 0 - l
  std::vector<char> freeComp;
  std::vector<std::array<double, 4>> G;
  double ratio = params_.get<double>("Step Size Factor");
  for (int k = 0;; ++k) {
    ap = approximationStep(x, Sxl);
    const double natural = naturalResidual(x, ap) / scale;
    double rel = ratio * natural;
    const bool confirm = rel <= tol || k == maxIt;
    if (confirm) {
      const int cg0 = fullSpace_->cgIterations();
      const std::vector<double> Sxlh = fullSpace_->equilibrate(ap.x, 0.01 * tol * scale);
      if (log) *log << "         confirmed by a K_rr solve: " << fullSpace_->cgIterations() - cg0 << " CG steps\n";
      for (int j = 0; j < nc; ++j) r[j] = Sxlh[j] + ap.y[j];
      rel = norm2(r) / scale;
      if (natural > 0) ratio = rel / natural;
    }
    record(res, ap, rel, k, log);
    if (confirm && rel <= tol) {
      res.converged = true;
      break;
    }
    if (k == maxIt) break;
    linearization(ap, freeComp, G);
    const double eta = std::min(etaMax, rel);
    const double setup0 = fullSpace_->setupSeconds(), cgTime0 = fullSpace_->cgSeconds();
    const int cg0 = fullSpace_->cgIterations();
    fullSpace_->newtonStep(ap.x, freeComp, G, ap.y, std::max(eta * rel * scale, 0.1 * tol * scale), x, Sxl);
    if (log)
      *log << "         CG steps: Newton " << fullSpace_->cgIterations() - cg0
           << " (MueLu re-setup " << std::setprecision(3) << fullSpace_->setupSeconds() - setup0 << " s, Newton CG "
           << fullSpace_->cgSeconds() - cgTime0 << " s)\n";
    res.iterations = k + 1;
  }
}

SemismoothResult SemismoothStarNewton::solve(std::ostream* log) {
  Teuchos::Time timer("semismooth*");
  timer.start();
  const double factorBefore = reduction_ ? reduction_->newtonFactorSeconds() : 0.0;
  const int cgBefore = fullSpace_ ? fullSpace_->cgIterations() : cgIterations_;
  const RotatedSystem& sys = fullSpace_ ? fullSpace_->system() : reduction_->system();
  const int m = sys.m;
  const double lnorm = norm2(fullSpace_ ? fullSpace_->l() : reduction_->l());

  SemismoothResult res;
  res.numNodes = numNodes_;
  res.numContactNodes = m;
  Approximation ap;
  if (log)
    *log << "semismooth* Newton: " << m << " contact nodes, " << numNodes_ << " nodes, ||l|| = " << lnorm << "\n"
         << "  iter   ||S x^ - l + y^||/||l||  contact   stick    slip\n";
  if (fullSpace_) solveFullSpace(res, ap, log);
  else solveReduced(res, ap, log);
  if (log)
    *log << (res.converged ? "  converged" : "  NOT converged") << " after " << res.iterations << " Newton steps\n";

  res.x = ap.x;
  res.y = ap.y;
  res.state = ap.state;
  // CG+MueLu: u is the equilibrated iterate at x^ (no extra solve).
  res.u = fullSpace_ ? fullSpace_->displacement() : reduction_->displacement(ap.x);
  res.contactNodes.resize(m);
  res.lambdaN.resize(m);
  res.lambdaT.resize(m);
  res.normal.resize(m);
  res.slipBound.resize(m);
  res.gap.resize(m);
  for (int i = 0; i < m; ++i) {
    res.contactNodes[i] = contact_[i].node;
    res.normal[i] = {sys.frame[i][2], sys.frame[i][5], sys.frame[i][8]};
    res.slipBound[i] = contact_[i].g;
    res.gap[i] = contact_[i].d;
    res.lambdaN[i] = ap.y[3 * i + 2];
    const auto& R = sys.frame[i];
    for (int c = 0; c < 3; ++c) res.lambdaT[i][c] = R[3 * c] * ap.y[3 * i] + R[3 * c + 1] * ap.y[3 * i + 1];
  }
  timer.stop();
  res.solverSeconds = timer.totalElapsedTime();
  if (fullSpace_) {
    res.reductionSeconds = fullSpace_->initialSeconds();
    res.preconditionerSeconds = fullSpace_->setupSeconds();
    res.cgIterations = fullSpace_->cgIterations() - cgBefore;
  } else {
    res.reductionSeconds = reduction_->reductionSeconds() + denseSeconds_;
    res.newtonFactorSeconds = reduction_->newtonFactorSeconds() - factorBefore;
    res.cgIterations = cgIterations_ - cgBefore;
  }
  return res;
}

}  // namespace Semismooth
}  // namespace Tribos
