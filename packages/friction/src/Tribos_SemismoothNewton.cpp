#include "Tribos_SemismoothNewton.hpp"

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "Tribos_ContactRowReduction.hpp"
#include "Tribos_NewtonPCG.hpp"
#include "Tribos_ArrayScan.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Validators.hpp"
#include "Tribos_Progress.hpp"

namespace Tribos {
namespace Friction {

using Teuchos::ParameterList;

namespace {

class DenseLu : public NewtonLinearSolver {
 public:
  bool factor(const LocalCsr& J) override {
    n_ = J.rows;
    lu_.assign(static_cast<size_t>(n_) * n_, 0.0);
    for (int i = 0; i < n_; ++i)
      for (int k = J.rowptr[i]; k < J.rowptr[i + 1]; ++k) lu_[static_cast<size_t>(J.col[k]) * n_ + i] += J.val[k];
    pivots_.assign(n_, 0);
    int info = 0;
    Teuchos::LAPACK<int, double>().GETRF(n_, n_, lu_.data(), n_, pivots_.data(), &info);
    return info == 0;
  }
  void solve(const double* b, double* x) const override {
    std::copy(b, b + n_, x);
    int info = 0;
    Teuchos::LAPACK<int, double>().GETRS('N', n_, 1, lu_.data(), n_, pivots_.data(), x, n_, &info);
  }
  std::string name() const override { return "Dense LU"; }

 private:
  int n_ = 0;
  std::vector<double> lu_;
  std::vector<int> pivots_;
};

double diagonalEntry(const LocalCsr& A, int i) {
  for (int k = A.rowptr[i]; k < A.rowptr[i + 1]; ++k)
    if (A.col[k] == i) return A.val[k];
  return 0.0;
}

}  // namespace

RCP<NewtonLinearSolver> denseLuSolver() { return rcp(new DenseLu()); }

// ---------------------------------------------------------------- AlartCurnier

AlartCurnier::AlartCurnier(const ContactDual& dual, std::vector<double> rho)
    : rho_(std::move(rho)), n_(static_cast<int>(dual.map()->getNodeNumElements())) {
  std::vector<char> used(n_, 0);
  for (int k = 0; k < dual.numLocalContacts(); ++k) {
    Contact c{};
    c.normal = dual.normalRows[k];
    used[c.normal] = 1;
    c.tangents = 0;
    for (int j = 0; j < 2; ++j) {
      const LO t = dual.tangentRows[2 * k + j];
      if (t < 0) continue;
      c.tangent[c.tangents] = t;
      c.centre[c.tangents] = dual.tangentCenter.empty() ? 0.0 : dual.tangentCenter[2 * k + j];
      ++c.tangents;
      used[t] = 1;
    }
    c.lower = dual.normalLower[k];
    c.offset = dual.normalOffset[k];
    c.friction = dual.frictionCoefficient.empty() ? 0.0 : dual.frictionCoefficient[k];
    c.bound = dual.slipBound.empty() ? 0.0 : dual.slipBound[k];
    contacts_.push_back(c);
  }
  for (int i = 0; i < n_; ++i)
    if (!used[i]) freeRows_.push_back(i);
}

AlartCurnier AlartCurnier::withSlipBoundsAt(const double* x, const double* v) const {
  AlartCurnier frozen(*this);
  for (Contact& c : frozen.contacts_) {
    c.bound = slipBound(c, x[c.normal] - rho_[c.normal] * v[c.normal]);
    c.friction = 0.0;
  }
  return frozen;
}

void AlartCurnier::blocks(const Contact& c, const double* x, const double* v, double rhoN, double rhoT,
                          Blocks& out) {
  const int m = 1 + c.tangents;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) out.Dx[p][q] = out.Dv[p][q] = 0.0;
  const double xN = x[c.normal], vN = v[c.normal];
  const double tauN = xN - rhoN * vN;
  if (tauN > c.lower) {
    out.phi[0] = xN - tauN;
    out.Dv[0][0] = rhoN;
  } else {
    out.phi[0] = xN - c.lower;
    out.Dx[0][0] = 1.0;
  }
  const double candidate = tauN + c.offset;
  const double R = slipBound(c, tauN);
  double z[2] = {0, 0}, nz = 0;
  for (int j = 0; j + 1 < m; ++j) {
    z[j] = x[c.tangent[j]] - c.centre[j] - rhoT * v[c.tangent[j]];
    nz += z[j] * z[j];
  }
  nz = std::sqrt(nz);
  if (nz <= R) {
    for (int j = 0; j + 1 < m; ++j) {
      out.phi[j + 1] = x[c.tangent[j]] - c.centre[j] - z[j];
      out.Dv[j + 1][j + 1] = rhoT;
    }
  } else {
    const double ratio = R / nz;
    for (int j = 0; j + 1 < m; ++j) {
      const double t = z[j] / nz;
      out.phi[j + 1] = x[c.tangent[j]] - c.centre[j] - R * t;
      for (int i = 0; i + 1 < m; ++i) {
        // P = (R/||z||)(I - t t') in 2D; 0 for an interval
        const double P = m == 3 ? ratio * ((i == j ? 1.0 : 0.0) - t * z[i] / nz) : 0.0;
        out.Dx[j + 1][i + 1] = (i == j ? 1.0 : 0.0) - P;
        out.Dv[j + 1][i + 1] = rhoT * P;
      }
      if (candidate > 0) {
        out.Dx[j + 1][0] -= t * c.friction;
        out.Dv[j + 1][0] += t * c.friction * rhoN;
      }
    }
  }
}

void AlartCurnier::value(const std::vector<double>& x, const std::vector<double>& v, std::vector<double>& phi) const {
  phi.assign(n_, 0.0);
  Blocks b;
  for (const Contact& c : contacts_) {
    const double rhoN = rho_[c.normal], rhoT = c.tangents > 0 ? rho_[c.tangent[0]] : 0.0;
    blocks(c, x.data(), v.data(), rhoN, rhoT, b);
    phi[c.normal] = b.phi[0];
    for (int j = 0; j < c.tangents; ++j) phi[c.tangent[j]] = b.phi[j + 1];
  }
  for (int i : freeRows_) phi[i] = rho_[i] * v[i];
}

void AlartCurnier::jacobian(const std::vector<double>& x, const std::vector<double>& v, const LocalCsr& A, double mu,
                            LocalCsr& J) const {
  // The pattern, once: per contact row the union of A's rows of the contact
  // and the contact's own columns (sorted).
  std::vector<int> mark(A.cols, -1);
  const bool buildPattern = J.rows != n_ || J.cols != A.cols;
  if (buildPattern) {
    J = LocalCsr();
    J.rows = n_;
    J.cols = A.cols;
    std::vector<std::vector<int>> rowCols(n_);
    auto addRows = [&](const std::vector<int>& rows) {
      std::vector<int> cols;
      for (int r : rows) {
        if (mark[r] < 0) mark[r] = 1, cols.push_back(r);
        for (int k = A.rowptr[r]; k < A.rowptr[r + 1]; ++k)
          if (mark[A.col[k]] < 0) mark[A.col[k]] = 1, cols.push_back(A.col[k]);
      }
      for (int c : cols) mark[c] = -1;
      std::sort(cols.begin(), cols.end());
      for (int r : rows) rowCols[r] = cols;
    };
    for (const Contact& c : contacts_) {
      std::vector<int> rows{c.normal};
      for (int j = 0; j < c.tangents; ++j) rows.push_back(c.tangent[j]);
      addRows(rows);
    }
    for (int i : freeRows_) addRows({i});
    for (int i = 0; i < n_; ++i) {
      J.col.insert(J.col.end(), rowCols[i].begin(), rowCols[i].end());
      J.rowptr.push_back(static_cast<int>(J.col.size()));
    }
    J.val.assign(J.col.size(), 0.0);
  }
  std::fill(J.val.begin(), J.val.end(), 0.0);
  // Row r of J += a * (row s of A); the position of each column of row r in
  // J.val through 'mark'.
  auto addRow = [&](int r, int s, double a) {
    if (a == 0.0) return;
    for (int k = A.rowptr[s]; k < A.rowptr[s + 1]; ++k) J.val[mark[A.col[k]]] += a * A.val[k];
  };
  auto open = [&](int r) {
    for (int k = J.rowptr[r]; k < J.rowptr[r + 1]; ++k) mark[J.col[k]] = k;
  };
  auto close = [&](int r) {
    for (int k = J.rowptr[r]; k < J.rowptr[r + 1]; ++k) mark[J.col[k]] = -1;
  };
  Blocks b;
  for (const Contact& c : contacts_) {
    const double rhoN = rho_[c.normal], rhoT = c.tangents > 0 ? rho_[c.tangent[0]] : 0.0;
    blocks(c, x.data(), v.data(), rhoN, rhoT, b);
    const int m = 1 + c.tangents;
    int rows[3] = {c.normal, c.tangents > 0 ? c.tangent[0] : -1, c.tangents > 1 ? c.tangent[1] : -1};
    for (int p = 0; p < m; ++p) {
      const int r = rows[p];
      open(r);
      for (int q = 0; q < m; ++q) {
        J.val[mark[rows[q]]] += b.Dx[p][q];
        addRow(r, rows[q], b.Dv[p][q]);
      }
      J.val[mark[r]] += mu;
      close(r);
    }
  }
  for (int i : freeRows_) {
    open(i);
    addRow(i, i, rho_[i]);
    J.val[mark[i]] += mu;
    close(i);
  }
}

// ---------------------------------------------------------------- SemismoothNewton

// ---------------------------------------------------------------- SemismoothNewton

bool newtonStepEnds(FrictionStatus& st, int it, double measure, double normGx, double tol, int maxIter,
                    std::chrono::steady_clock::time_point start) {
  st.history.push_back(measure);
  OuterStep step;
  step.iteration = it;
  step.projectedGradient = measure;
  step.normGx = normGx;
  step.slipBoundChange = std::numeric_limits<double>::quiet_NaN();
  step.n_A = st.n_A;
  step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  st.steps.push_back(step);
  Progress::iteration([&] {
    return "Semismooth Newton " + std::to_string(it) + ": measure " + Progress::sci(measure) + ", tolerance " +
           Progress::sci(tol);
  });
  if (!std::isfinite(measure)) {
    st.reason = "Semismooth Newton: the stopping measure is not finite at step " + std::to_string(it);
    return true;
  }
  if (measure <= tol) {
    st.converged = true;
    st.reason = "Semismooth Newton: stopping measure below tolerance";
    return true;
  }
  if (it == maxIter) {
    st.reason = "Maximum Iterations (" + std::to_string(maxIter) + ") of Semismooth Newton reached";
    return true;
  }
  return false;
}

RCP<const ParameterList> SemismoothNewton::validParameters() {
  static RCP<ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Semismooth Newton");
    pl->set("Relative Tolerance", 1e-8,
            "stop when the stopping measure (default ||Phi(x)|| / ||rho b||, the Alart-Curnier residual; FCLIB: "
            "||F_nat|| / ||q||) is at most this",
            range<double>(1e-15, 1.0));
    pl->set("Maximum Iterations", 200, "Newton steps", range<int>(1, 1000000));
    pl->set("Line Search", "Armijo",
            "Armijo: backtracking on psi = 1/2 ||Phi||^2 until psi(x + t d) <= (1 - 2 sigma t) psi(x); None: full steps",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Armijo", "None"))));
    pl->set("sigma", 1e-4, "Armijo constant", range<double>(1e-12, 0.5));
    pl->set("Backtracking Factor", 0.5, "t <- factor t while the Armijo test fails", range<double>(0.01, 0.99));
    pl->set("Maximum Backtracking Steps", 30,
            "trial steps per Newton step; when none passes, the last is taken (counted as a line-search failure)",
            range<int>(0, 200));
    pl->set("rho Factor", 1.0, "rho_i = factor / A_ii (normal rows; the tangential pair shares the mean)",
            range<double>(1e-6, 1e6));
    pl->set("Regularization", 1e-3,
            "Levenberg-Marquardt term mu_k = this times min(1, ||Phi(x_k)|| / ||Phi(x_0)||) on the diagonal of J "
            "(rows scaled by rho, so the diagonal of J is about 1): it bounds the step where A is singular "
            "(closed or sticking contacts whose rows of A are dependent, as in multibody problems) and vanishes "
            "at the solution; 1e-3 measured best on the FCLIB dev set (docs/semismooth.md). It is the starting "
            "weight lambda: a step the line search cuts below 1e-3 multiplies lambda by 10 (up to 100), a full "
            "step divides it by 10 (down to this value)",
            range<double>(0.0, 1.0));
    pl->set("Dense Limit", 5000,
            "without an explicit matrix, A is formed densely up to this many rows (Linear Solver = Dense LU); "
            "Auto takes Projected CG above it",
            range<int>(1, 100000));
    pl->set("Linear Solver", "Auto",
            "the Newton systems: Dense LU (A formed densely, reduced to the contact rows, at most Dense Limit rows), "
            "Projected CG (matrix-free: A applied, never formed; the step by preconditioned CG on its free "
            "directions, Tribos_NewtonPCG.hpp), or Auto: Dense LU for an explicit matrix (FCLIB) and for a dual of "
            "at most Dense Limit rows, Projected CG above",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Auto", "Dense LU", "Projected CG"))));
    pl->set("Preconditioner", "Auto",
            "Projected CG: Slip Curvature (||A|| (||A|| I + K)^-1 on the contact rows, K the curvature of the "
            "slipping contacts' disks, which grows without bound where the slip bound is small against the slip "
            "and makes the Newton systems ill-conditioned), None, the dual problem's preconditioner by name "
            "(FETI: Lumped or Dirichlet, approximate inverses of the projected dual operator P A P), or Auto: "
            "Slip Curvature, and from the step where the Newton steps' CG solves have taken more than Lumped "
            "Above CG Iterations on average (from the second step on) the dual problem's Lumped, which the next "
            "solve of a history then starts with (docs/semismooth.md, \"Preconditioning\")",
            rcp(new Teuchos::StringValidator(
                Teuchos::tuple<std::string>("Auto", "Slip Curvature", "None", "Lumped", "Dirichlet"))));
    pl->set("Lumped Above CG Iterations", 25,
            "Preconditioner = Auto: the mean CG iterations per Newton step above which FETI's lumped "
            "preconditioner replaces the slip curvature scaling",
            range<int>(0, 1000000));
    pl->set("Equality Constraint", "Auto",
            "Projected CG: how the Newton steps hold G x = 0. Augmented Lagrangian: H = A + rho G'G and mu "
            "updated after each step (Penalty, Penalty Balancing, Maximum Penalty, Multiplier Update Ratio); "
            "Face Projection: mu is an unknown of each step, whose direction is kept in ker G by projected CG "
            "with the projector onto ker(G Pi), Pi the free directions (G Pi G' factored per step; needs an "
            "equality constraint that forms it, as FETI's coarse space does). Auto: Face Projection where the "
            "contact alone holds some rigid motion (its multiplier and the contact state decide each other, and "
            "the augmented Lagrangian's lagging multiplier takes 1.05-1.4x the applications of A), the augmented "
            "Lagrangian otherwise (fewer applications of A where the rows of no contact fix the multiplier; "
            "docs/semismooth.md)",
            rcp(new Teuchos::StringValidator(
                Teuchos::tuple<std::string>("Auto", "Augmented Lagrangian", "Face Projection"))));
    pl->set("Penalty", 1.0,
            "Projected CG: the augmented Lagrangian's rho of G x = 0, as a multiple of ||A||", range<double>(1e-6, 1e6));
    pl->set("Penalty Balancing", 5.0,
            "Projected CG: rho is doubled after a Newton step whose ||G x|| exceeds this times ||Phi|| (the "
            "multiplier of G x = 0 lags the contact conditions), up to Maximum Penalty; 0 keeps rho fixed",
            range<double>(0.0, 1e6));
    pl->set("Maximum Penalty", 64.0, "Projected CG: the largest rho of Penalty Balancing, as a multiple of ||A||",
            range<double>(1e-6, 1e12));
    pl->set("Multiplier Update Ratio", 0.0,
            "Projected CG: the multiplier mu of G x = 0 is updated after a Newton step when ||Phi|| <= this "
            "times ||G x|| (SMALBE's M); 0: after every Newton step (measured fastest on the brick, "
            "docs/semismooth.md)",
            range<double>(0.0, 1e6));
    pl->set("Nonmonotone Memory", 3,
            "Projected CG: Armijo's condition asks the decrease of the largest 1/2 ||Phi||^2 of this many last "
            "Newton steps (1: of the last, monotone); 3 measured best on the brick from k = 8 to 48 "
            "(docs/semismooth.md)",
            range<int>(1, 1000));
    pl->set("Maximum Forcing Term", 0.2,
            "Projected CG: the largest relative residual eta_k of a Newton system (Eisenstat-Walker forcing "
            "terms below it)",
            range<double>(1e-12, 0.99));
    pl->set("Changing Set Forcing Term", 0.1,
            "Projected CG: the smallest eta_k of a Newton system whose fixed and free directions differ from "
            "the previous step's at some contact: such a step is a guess of the contact state, and solving it "
            "tighter than the state is known buys nothing (0: Eisenstat-Walker alone; docs/semismooth.md)",
            range<double>(0.0, 0.99));
    pl->set("Exact Velocity Steps", 10,
            "Projected CG: v = H x - (b - G'mu) is computed from x (one application of A) after this many Newton "
            "steps that carried it as v + t H d, and before the stopping test is believed",
            range<int>(1, 1000000));
    pl->set("Slip Bound Freeze Steps", 6,
            "Projected CG, Coulomb: when the stopping measure has not halved over this many Newton steps, the slip "
            "bounds are frozen at their current values and the steps solve that Tresca problem, whose Jacobian is "
            "exact, until its residual is a tenth of the Coulomb one; then they follow the normal multipliers "
            "again. Steps that lag the slip bound can cycle between two points where a contact changes state "
            "back and forth (docs/semismooth.md)",
            range<int>(1, 1000000));
    pl->set("Stall Steps", 30,
            "Projected CG: stop as stalled when the stopping measure has not halved over this many Newton steps",
            range<int>(1, 1000000));
    pl->set("Maximum CG Iterations", 1000, "Projected CG: iterations per Newton system", range<int>(1, 1000000));
  }
  return pl;
}

SemismoothNewton::SemismoothNewton(const ParameterList& params) : SingleLoopSolver(params, validParameters()) {}

bool SemismoothNewton::matrixFree(long long rows) const {
  const std::string& solver = params_.get<std::string>("Linear Solver");
  return solver == "Projected CG" ||
         (solver == "Auto" && explicitA_ == nullptr && rows > params_.get<int>("Dense Limit"));
}

void SemismoothNewton::checkDualRows(long long rows) const {
  if (matrixFree(rows)) return;
  const int limit = params_.get<int>("Dense Limit");
  TRIBOS_REQUIRE(explicitA_ || rows <= limit,
                 "Semismooth Newton: the dual has " << rows << " rows, more than its Dense Limit = " << limit
                     << " (Linear Solver = Dense LU holds the dual densely on every rank, about 24 n^2 bytes for n "
                        "rows); raise Semismooth Newton/Dense Limit, or take Linear Solver = Projected CG or Auto");
}

void SemismoothNewton::setHessianMatrix(const LocalCsr* A, double scale) {
  explicitA_ = A;
  explicitScale_ = scale;
}

// The Newton system of a contact problem: v = A z - b for z = (x, alpha),
// x on the contact structure's rows (n), alpha the r multipliers of the
// border rows h = border z - e (r = 0: none).
struct SemismoothNewton::NewtonSystem {
  const ContactDual* structure;
  LocalCsr A;       // n x (n + r)
  std::vector<double> b, bReference;
  LocalCsr border;  // r x (n + r)
  std::vector<double> e;
};

namespace {

std::vector<double> data(const Vector& v) {
  auto d = v.getData();
  return std::vector<double>(d.begin(), d.end());
}

// J (n x (n + r), from the Alart-Curnier Jacobian) with the border rows and
// -mu on their diagonal appended.
void appendBorder(const LocalCsr& J, const LocalCsr& border, double mu, LocalCsr& out) {
  out = J;
  out.rows = J.rows + border.rows;
  for (int i = 0; i < border.rows; ++i) {
    for (int k = border.rowptr[i]; k < border.rowptr[i + 1]; ++k) {
      out.col.push_back(border.col[k]);
      out.val.push_back(border.val[k] - (border.col[k] == J.rows + i ? mu : 0.0));
    }
    out.rowptr.push_back(static_cast<int>(out.col.size()));
  }
}

}  // namespace

FrictionStatus SemismoothNewton::solve(const ContactDual& dual, Vector& xVector) {
  dual.check();
  TRIBOS_REQUIRE(dual.frictionCoefficient.size() == dual.normalRows.size(),
                 "Semismooth Newton: Coulomb friction needs a friction coefficient per contact");
  if (matrixFree(static_cast<long long>(dual.map()->getGlobalNumElements()))) {
    TRIBOS_REQUIRE(!measure_, "Semismooth Newton: a stopping measure needs Linear Solver = Dense LU");
    return NewtonPCG(params_).solve(dual, xVector, warm_, final_, out_);
  }
  FrictionStatus st;
  const auto start = std::chrono::steady_clock::now();
  if (explicitA_) {
    // The caller's matrix (FCLIB's W): the problem as given, on one rank.
    const auto map = dual.map();
    TRIBOS_REQUIRE(dual.G.is_null() && map->getComm()->getSize() == 1,
                   "Semismooth Newton: an explicit matrix is taken for a serial problem without equality constraint");
    const int n = static_cast<int>(map->getNodeNumElements());
    TRIBOS_REQUIRE(explicitA_->rows == n && explicitA_->cols == n,
                   "Semismooth Newton: the explicit matrix is " << explicitA_->rows << " x " << explicitA_->cols
                                                                << ", the dual has " << n << " rows");
    NewtonSystem sys{&dual, *explicitA_, data(*dual.b), data(dual.bReference.is_null() ? *dual.b : *dual.bReference),
                     LocalCsr(), {}};
    for (double& a : sys.A.val) a *= explicitScale_;
    sys.border.cols = n;
    std::vector<double> z = data(xVector);
    iterate(sys, z, st, start);
    auto xv = xVector.getDataNonConst();
    std::copy(z.begin(), z.end(), xv.begin());
  } else {
    // Dense, reduced to the contact rows: free rows and G x = 0 eliminated
    // (Tribos_ContactRowReduction.hpp), the same on every rank.
    TRIBOS_REQUIRE(!measure_, "Semismooth Newton: a stopping measure needs the explicit matrix");
    checkDualRows(static_cast<long long>(dual.map()->getGlobalNumElements()));
    auto reduction = std::make_unique<ContactRowReduction>(dual);
    const ReducedContactProblem& p = reduction->reduced();
    st.n_A += reduction->applications();
    NewtonSystem sys{&p.contacts, p.A, data(*p.contacts.b), data(*p.contacts.bReference), p.border, p.e};
    std::vector<double> z = reduction->restrict(xVector);
    iterate(sys, z, st, start);
    reduction->expand(z, xVector);
  }
  st.slipBound = dual.coulombSlipBound(xVector);
  st.n_A_qpp = st.n_A;
  return st;
}

void SemismoothNewton::iterate(const NewtonSystem& sys, std::vector<double>& z, FrictionStatus& st,
                               std::chrono::steady_clock::time_point start) const {
  const ContactDual& dual = *sys.structure;
  const int n = sys.A.rows, r = sys.border.rows, nz = n + r;
  const LocalCsr& A = sys.A;
  const double rhoFactor = params_.get<double>("rho Factor");
  double maxDiag = A.maxAbsDiagonal();
  if (!(maxDiag > 0)) maxDiag = 1.0;
  auto rhoOf = [&](double a) { return rhoFactor / (a > 1e-12 * maxDiag ? a : maxDiag); };
  std::vector<double> rho(n, 0.0);
  for (int i = 0; i < n; ++i) rho[i] = rhoOf(diagonalEntry(A, i));
  for (int k = 0; k < dual.numLocalContacts(); ++k) {
    const LO t1 = dual.tangentRows[2 * k], t2 = dual.tangentRows[2 * k + 1];
    if (t1 >= 0 && t2 >= 0) rho[t1] = rho[t2] = rhoOf(0.5 * (diagonalEntry(A, t1) + diagonalEntry(A, t2)));
  }
  const AlartCurnier ac(dual, rho);

  const std::vector<double>& b = sys.b;
  std::vector<double> v(n), phi(n), d(nz), w(n), zt(nz), vt(n), phit(n), rhs(nz), h(r), ht(r);
  auto velocity = [&](const std::vector<double>& y, std::vector<double>& out) {
    A.multiply(y.data(), out.data());
    for (int i = 0; i < n; ++i) out[i] -= b[i];
    ++st.n_A;
  };
  auto borderResidual = [&](const std::vector<double>& y, std::vector<double>& out) {
    if (r == 0) return;
    sys.border.multiply(y.data(), out.data());
    for (int i = 0; i < r; ++i) out[i] -= sys.e[i];
  };
  double normRhoB = 0;
  for (int i = 0; i < n; ++i) normRhoB += rho[i] * sys.bReference[i] * rho[i] * sys.bReference[i];
  normRhoB = std::sqrt(normRhoB);
  if (!(normRhoB > 0)) normRhoB = 1.0;
  // ||(Phi, h)||: the Alart-Curnier residual and that of the border rows.
  auto residualNorm = [&](const std::vector<double>& p, const std::vector<double>& q) {
    const double a = norm2(p), c = norm2(q);
    return std::sqrt(a * a + c * c);
  };
  const Measure measure = measure_ ? measure_ : Measure([&](const std::vector<double>&, const std::vector<double>&) {
    return residualNorm(phi, h) / normRhoB;
  });

  RCP<NewtonLinearSolver> linear = linear_.is_null() ? denseLuSolver() : linear_;
  const double tol = params_.get<double>("Relative Tolerance");
  const int maxIter = params_.get<int>("Maximum Iterations");
  const bool armijo = params_.get<std::string>("Line Search") == "Armijo";
  const double sigma = params_.get<double>("sigma"), beta = params_.get<double>("Backtracking Factor");
  const int maxBack = params_.get<int>("Maximum Backtracking Steps");
  const double regularization = params_.get<double>("Regularization");

  velocity(z, v);
  ac.value(z, v, phi);
  borderResidual(z, h);
  const double phi0 = std::max(residualNorm(phi, h), 1e-300);
  LocalCsr J0, J;
  int lineSearchFailures = 0;
  const double kMaxLambda = 1e2;
  double lambda = regularization;
  for (int it = 0;; ++it) {
    const double normPhi = residualNorm(phi, h);
    const double m = measure(z, v);
    st.norm_gP = normPhi;
    st.norm_Gx = norm2(h);
    if (!out_.is_null())
      *out_ << "Semismooth Newton " << std::setw(3) << it << "  measure " << std::scientific << std::setprecision(3) << m
            << "  ||Phi|| " << normPhi << "\n";
    if (newtonStepEnds(st, it, m, st.norm_Gx / normRhoB, tol, maxIter, start)) break;
    // The Newton direction, regularized when the factorization fails.
    double mu = lambda * std::min(1.0, normPhi / phi0);
    bool factored = false;
    for (int attempt = 0; attempt < 4 && !factored; ++attempt) {
      ac.jacobian(z, v, A, mu, J0);
      if (r > 0) appendBorder(J0, sys.border, mu, J);
      factored = linear->factor(r > 0 ? J : J0);
      mu = std::max(mu * 1e3, 1e-10);
    }
    if (!factored) {
      st.reason = "Semismooth Newton: the generalized Jacobian is singular at step " + std::to_string(it);
      break;
    }
    for (int i = 0; i < n; ++i) rhs[i] = -phi[i];
    for (int i = 0; i < r; ++i) rhs[n + i] = -h[i];
    linear->solve(rhs.data(), d.data());
    A.multiply(d.data(), w.data());
    ++st.n_A;
    const double psi = 0.5 * normPhi * normPhi;
    double t = 1.0;
    bool accepted = false;
    for (int k = 0; k <= (armijo ? maxBack : 0); ++k) {
      for (int i = 0; i < nz; ++i) zt[i] = z[i] + t * d[i];
      for (int i = 0; i < n; ++i) vt[i] = v[i] + t * w[i];
      ac.value(zt, vt, phit);
      borderResidual(zt, ht);
      const double nt = residualNorm(phit, ht);
      if (!armijo || 0.5 * nt * nt <= (1.0 - 2.0 * sigma * t) * psi) {
        accepted = true;
        break;
      }
      ++st.inner_iterations;
      if (k < maxBack) t *= beta;
    }
    st.outer_iterations = it + 1;
    // Adaptive Levenberg-Marquardt weight: a step cut short (the direction
    // is poor where A is singular) raises lambda for the next direction, a
    // full step lowers it back towards Regularization. Without any Armijo
    // step the iterate stays and the direction is recomputed with the larger
    // lambda, as long as lambda may still grow.
    if (armijo && (!accepted || t < 1e-3) && lambda < kMaxLambda) {
      lambda = std::min(kMaxLambda, std::max(10.0 * lambda, 1e-8));
      if (!accepted) continue;
    } else if (t == 1.0) {
      lambda = std::max(regularization, 0.1 * lambda);
    }
    if (!accepted) ++lineSearchFailures;
    z.swap(zt);
    velocity(z, v);  // exact, not v + t w, so that round-off does not accumulate
    ac.value(z, v, phi);
    borderResidual(z, h);
  }
  if (lineSearchFailures > 0) st.reason += " (" + std::to_string(lineSearchFailures) + " line-search failures)";
}

}  // namespace Friction
}  // namespace Tribos
