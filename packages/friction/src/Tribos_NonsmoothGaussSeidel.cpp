#include "Tribos_NonsmoothGaussSeidel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>

#include "Tribos_DenseBlas.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_SemismoothNewton.hpp"
#include "Tribos_Validators.hpp"

namespace Tribos {
namespace Friction {

using Teuchos::ParameterList;

namespace {

// y += sign * M x, M 3 x 3 row-major: every product with a contact block.
inline void addProduct(const double* M, const double* x, double* y, double sign = 1.0) {
  for (int a = 0; a < 3; ++a) y[a] += sign * (M[3 * a] * x[0] + M[3 * a + 1] * x[1] + M[3 * a + 2] * x[2]);
}

// W read by contact: rows 3c, 3c+1, 3c+2 of the CSR arrays as they are (no
// copy: a problem solved in a few sweeps would pay more for a blocked copy
// than for its sweeps), and the diagonal blocks W_cc (row-major, 9 values),
// found by binary search in the sorted rows when first needed: a contact
// that opens at every sweep (r_c = 0) never needs its own, and on multibody
// problems most contacts do.
struct ContactRows {
  const CsrView& W;
  mutable std::vector<double> diag;         // 9 per contact, valid where 'known'
  mutable std::vector<unsigned char> known;

  ContactRows(const CsrView& matrix, int nc)
      : W(matrix), diag(9 * static_cast<size_t>(nc), 0.0), known(static_cast<size_t>(nc), 0) {}

  // W_cc.
  const double* block(int c) const {
    double* d = &diag[9 * static_cast<size_t>(c)];
    if (known[c]) return d;
    for (int a = 0; a < 3; ++a) {
      const int i = 3 * c + a;
      const int* first = W.col + W.rowptr[i];
      const int* last = W.col + W.rowptr[i + 1];
      for (const int* k = std::lower_bound(first, last, 3 * c); k != last && *k < 3 * c + 3; ++k)
        d[3 * a + (*k - 3 * c)] += W.val[k - W.col];
    }
    known[c] = 1;
    return d;
  }

  // Every W_cc (for the blocked copy).
  const std::vector<double>& blocks() const {
    for (int c = 0; c < static_cast<int>(known.size()); ++c) block(c);
    return diag;
  }

  // q_i + sum of W_ik r_k over the entries [k, end) of row i. Four partial
  // sums: a single one makes each product wait for the previous addition,
  // which on rows of a few dozen entries costs more than the loads.
  double rowSum(int k, int end, const double* r, double qi) const {
    double s0 = qi, s1 = 0, s2 = 0, s3 = 0;
    for (; k + 3 < end; k += 4) {
      s0 += W.val[k] * r[W.col[k]];
      s1 += W.val[k + 1] * r[W.col[k + 1]];
      s2 += W.val[k + 2] * r[W.col[k + 2]];
      s3 += W.val[k + 3] * r[W.col[k + 3]];
    }
    for (; k < end; ++k) s0 += W.val[k] * r[W.col[k]];
    return (s0 + s1) + (s2 + s3);
  }

  // y = (W r)_c + q_c, the velocity of contact c.
  void velocity(int c, const double* r, const double* q, double y[3]) const {
    for (int a = 0; a < 3; ++a) y[a] = rowSum(W.rowptr[3 * c + a], W.rowptr[3 * c + a + 1], r, q[3 * c + a]);
  }

  // y = sum_{d != c} W_cd r_d + q_c: the velocity of contact c without its own force.
  void offDiagonal(int c, const double* r, const double* q, double y[3]) const {
    velocity(c, r, q, y);
    const double* rc = r + 3 * c;
    if (rc[0] != 0.0 || rc[1] != 0.0 || rc[2] != 0.0) addProduct(block(c), rc, y, -1.0);
  }

  // u = W r + q.
  void velocities(const std::vector<double>& r, const double* q, std::vector<double>& u) const {
    const int nc = static_cast<int>(known.size());
    u.resize(3 * static_cast<size_t>(nc));
    for (int c = 0; c < nc; ++c) velocity(c, r.data(), q, &u[3 * c]);
  }
};

// W copied by contact: per contact its off-diagonal blocks W_cd (row-major,
// 9 values each; the diagonal blocks are ContactRows'), so that a sweep
// reads each r_d once per block instead of once per entry: a quarter faster
// per sweep than ContactRows, for the price of about three sweeps to build.
struct BlockRows {
  const std::vector<double>& diag;  // W_cc, 9 per contact (ContactRows::diag)
  std::vector<int> ptr;             // blocks of contact c: ptr[c] .. ptr[c+1]
  std::vector<int> col;             // the contact d of each block
  std::vector<double> val;          // 9 per block

  // Rows 3c, 3c+1, 3c+2 of W merged by block column d = column / 3: two
  // passes over the indices (count, then fill), no search.
  BlockRows(const CsrView& W, const std::vector<double>& diagonal) : diag(diagonal), ptr(diagonal.size() / 9 + 1, 0) {
    const int nc = static_cast<int>(diagonal.size() / 9);
    for (int c = 0; c < nc; ++c) ptr[c + 1] = ptr[c] + merge(W, c, nullptr);
    col.resize(ptr[nc]);
    val.assign(9 * static_cast<size_t>(ptr[nc]), 0.0);
    for (int c = 0; c < nc; ++c) merge(W, c, this);
  }

  // The off-diagonal blocks of contact c in ascending d (rows sorted by
  // column, as CSR holds them); with 'fill', their values are stored.
  // Returns their number.
  static int merge(const CsrView& W, int c, BlockRows* fill) {
    int k[3], end[3];
    for (int a = 0; a < 3; ++a) k[a] = W.rowptr[3 * c + a], end[a] = W.rowptr[3 * c + a + 1];
    int blocks = 0;
    for (;;) {
      int d = -1;
      for (int a = 0; a < 3; ++a)
        if (k[a] < end[a] && (d < 0 || W.col[k[a]] / 3 < d)) d = W.col[k[a]] / 3;
      if (d < 0) return blocks;
      double* block = nullptr;
      if (fill && d != c) {
        block = &fill->val[9 * static_cast<size_t>(fill->ptr[c] + blocks)];
        fill->col[fill->ptr[c] + blocks] = d;
      }
      for (int a = 0; a < 3; ++a)
        for (; k[a] < end[a] && W.col[k[a]] / 3 == d; ++k[a])
          if (block) block[3 * a + W.col[k[a]] % 3] += W.val[k[a]];
      if (d != c) ++blocks;
    }
  }

  // y = sum_{d != c} W_cd r_d + q_c (the velocity of contact c without its own force).
  void offDiagonal(int c, const double* r, const double* q, double y[3]) const {
    y[0] = q[3 * c], y[1] = q[3 * c + 1], y[2] = q[3 * c + 2];
    for (int j = ptr[c]; j < ptr[c + 1]; ++j) addProduct(&val[9 * static_cast<size_t>(j)], r + 3 * col[j], y);
  }

  // u = W r + q.
  void velocities(const std::vector<double>& r, const double* q, std::vector<double>& u) const {
    const int nc = static_cast<int>(ptr.size()) - 1;
    u.resize(3 * static_cast<size_t>(nc));
    for (int c = 0; c < nc; ++c) {
      offDiagonal(c, r.data(), q, &u[3 * c]);
      addProduct(&diag[9 * static_cast<size_t>(c)], &r[3 * c], &u[3 * c]);
    }
  }
};

// W copied densely, row after row, in single precision, when its rows are
// mostly full (a few bodies with many contacts each: FCLIB's global
// problems, where W = H'M^-1 H couples every contact of a body with every
// other). A contact's velocity is then three dot products over contiguous
// memory, which run in vector registers (Blas::dot3), where BlockRows adds
// 9-value blocks one after the other, each addition waiting on the
// previous one; and a sweep, which reads all of W, reads half the bytes.
// The floats are widened as they are read, so the sweeps see one fixed
// matrix W~ (each entry within 6e-8 of W's); the solve corrects q for the
// difference until the exact W meets the tolerance (solve, below).
struct DenseRows {
  const std::vector<double>& diag;  // W_cc, 9 per contact (ContactRows::diag)
  int n;
  std::vector<float> val;           // n x n, row-major

  DenseRows(const CsrView& W, const std::vector<double>& diagonal)
      : diag(diagonal), n(W.rows), val(static_cast<size_t>(W.rows) * W.rows, 0.0f) {
    std::vector<double> row(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      std::fill(row.begin(), row.end(), 0.0);
      for (int k = W.rowptr[i]; k < W.rowptr[i + 1]; ++k) row[W.col[k]] += W.val[k];
      std::copy(row.begin(), row.end(), val.begin() + static_cast<size_t>(i) * n);
    }
  }
  // Whether W is full enough for this copy to pay: at least half its
  // entries stored (the copy then takes at most a third of the CSR's
  // memory), and at most 1 GB.
  static bool suits(const CsrView& W) {
    const double n = W.rows, nnz = W.rowptr[W.rows];
    return nnz >= 0.5 * n * n && n * n * 4.0 <= 1024.0 * 1024 * 1024;
  }

  // y = (W~ r)_c + q_c, the velocity of contact c.
  void velocity(int c, const double* r, const double* q, double y[3]) const {
    const float* row = &val[static_cast<size_t>(3 * c) * n];
    Blas::dot3(n, row, row + n, row + 2 * n, r, y);
    for (int a = 0; a < 3; ++a) y[a] += q[3 * c + a];
  }

  // y = sum_{d != c} W_cd r_d + q_c (the velocity of contact c without its own force).
  void offDiagonal(int c, const double* r, const double* q, double y[3]) const {
    velocity(c, r, q, y);
    addProduct(&diag[9 * static_cast<size_t>(c)], r + 3 * c, y, -1.0);
  }

  // u = W~ r + q.
  void velocities(const std::vector<double>& r, const double* q, std::vector<double>& u) const {
    u.resize(static_cast<size_t>(n));
    for (int c = 0; 3 * c < n; ++c) velocity(c, r.data(), q, &u[3 * c]);
  }
};

// Solves the 3 x 3 system A x = b by Gaussian elimination with partial
// pivoting; false when a pivot vanishes relative to max |A_ij|.
bool solve3(double A[3][3], double b[3], double x[3]) {
  double scale = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) scale = std::max(scale, std::abs(A[i][j]));
  if (!(scale > 0)) return false;
  for (int k = 0; k < 3; ++k) {
    int p = k;
    for (int i = k + 1; i < 3; ++i)
      if (std::abs(A[i][k]) > std::abs(A[p][k])) p = i;
    if (!(std::abs(A[p][k]) > 1e-14 * scale)) return false;
    if (p != k) {
      std::swap(A[p], A[k]);
      std::swap(b[p], b[k]);
    }
    for (int i = k + 1; i < 3; ++i) {
      const double f = A[i][k] / A[k][k];
      for (int j = k; j < 3; ++j) A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  for (int i = 2; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < 3; ++j) s -= A[i][j] * x[j];
    x[i] = s / A[i][i];
  }
  return true;
}

// One contact's Coulomb problem: r in the cone with u = W r + qt (W = W_cc,
// held by ContactRows).
class LocalCoulomb {
 public:
  LocalCoulomb(const double* W, double mu, double tolerance, int maxIterations)
      : W_(W), tol_(tolerance), maxIt_(maxIterations) {
    contact_ = {0, {1, 2}, 2, 0.0, 0.0, {0.0, 0.0}, mu, 0.0};
    double wmax = 0;
    for (int i = 0; i < 9; ++i) wmax = std::max(wmax, std::abs(W[i]));
    // rho as the global Newton method takes it (1 / diagonal), 1 / max|W|
    // where the diagonal is not positive.
    const double fallback = wmax > 0 ? 1.0 / wmax : 1.0;
    rhoN_ = W[0] > 0 ? 1.0 / W[0] : fallback;
    rhoT_ = W[4] + W[8] > 0 ? 2.0 / (W[4] + W[8]) : rhoN_;
    // The stick solution needs W_cc^-1: the adjugate over the determinant,
    // once; a determinant below round-off relative to |W_cc|^3 leaves the
    // stick case to the Newton iteration.
    const double c00 = W[4] * W[8] - W[5] * W[7], c01 = W[5] * W[6] - W[3] * W[8], c02 = W[3] * W[7] - W[4] * W[6];
    const double det = W[0] * c00 + W[1] * c01 + W[2] * c02;
    invertible_ = std::abs(det) > 1e-13 * wmax * wmax * wmax && wmax > 0;
    if (invertible_) {
      const double inv[9] = {c00, W[2] * W[7] - W[1] * W[8], W[1] * W[5] - W[2] * W[4],
                             c01, W[0] * W[8] - W[2] * W[6], W[2] * W[3] - W[0] * W[5],
                             c02, W[1] * W[6] - W[0] * W[7], W[0] * W[4] - W[1] * W[3]};
      for (int i = 0; i < 9; ++i) inverse_[i] = inv[i] / det;
    }
  }

  // r: the previous force on input, the solution on output; returns the
  // Newton iterations (0 for take-off and stick, which are exact).
  int solve(const double qt[3], double r[3]) const {
    if (qt[0] >= 0) {  // take-off: u = qt has u_N >= 0 at r = 0
      r[0] = r[1] = r[2] = 0.0;
      return 0;
    }
    if (invertible_) {  // stick: u = 0
      double s[3] = {0, 0, 0};
      addProduct(inverse_, qt, s, -1.0);
      if (s[0] > 0 && std::hypot(s[1], s[2]) <= contact_.friction * s[0]) {
        std::copy(s, s + 3, r);
        return 0;
      }
    }
    // Slip: the previous force is the start when it presses; otherwise the
    // normal force that closes the gap alone.
    if (!(r[0] > 0)) r[0] = -qt[0] * rhoN_, r[1] = r[2] = 0.0;
    return newton(qt, r);
  }
  // Phi of the contact at force x and velocity v.
  void residual(const double* x, const double* v, AlartCurnier::Blocks& b) const {
    AlartCurnier::blocks(contact_, x, v, rhoN_, rhoT_, b);
  }
  double rhoN() const { return rhoN_; }
  double rhoT() const { return rhoT_; }

 private:
  void residualAt(const double qt[3], const double x[3], AlartCurnier::Blocks& b) const {
    double v[3] = {qt[0], qt[1], qt[2]};
    addProduct(W_, x, v);
    residual(x, v, b);
  }
  static double norm2(const double a[3]) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; }

  int newton(const double qt[3], double x[3]) const {
    const double scale = rhoN_ * std::sqrt(norm2(qt));
    AlartCurnier::Blocks b;
    residualAt(qt, x, b);
    double psi = norm2(b.phi);
    int it = 0;
    for (; it < maxIt_; ++it) {
      if (std::sqrt(psi) <= tol_ * (std::sqrt(norm2(x)) + scale)) break;
      double J[3][3], rhs[3], d[3];
      for (int i = 0; i < 3; ++i) {
        rhs[i] = -b.phi[i];
        for (int j = 0; j < 3; ++j)
          J[i][j] = b.Dx[i][j] + b.Dv[i][0] * W_[j] + b.Dv[i][1] * W_[3 + j] + b.Dv[i][2] * W_[6 + j];
      }
      if (!solve3(J, rhs, d)) break;
      // Armijo on psi = ||Phi||^2: psi(x + t d) <= (1 - 2 sigma t) psi(x).
      double t = 1.0, trial[3];
      AlartCurnier::Blocks bt;
      bool accepted = false;
      for (int k = 0; k < 40 && !accepted; ++k, t *= 0.5) {
        for (int i = 0; i < 3; ++i) trial[i] = x[i] + t * d[i];
        residualAt(qt, trial, bt);
        accepted = norm2(bt.phi) <= (1.0 - 2e-4 * t) * psi;
      }
      if (!accepted) break;  // no descent left: round-off
      std::copy(trial, trial + 3, x);
      b = bt;
      psi = norm2(b.phi);
    }
    return it;
  }

  AlartCurnier::Contact contact_;
  const double* W_;
  double inverse_[9];
  bool invertible_ = false;
  double rhoN_ = 1, rhoT_ = 1, tol_;
  int maxIt_;
};

// ||Phi(r)|| / ||rho q||: the Alart-Curnier residual of the whole problem
// with the contacts' rho (the default stopping measure).
template <class LocalOf>
double alartCurnierMeasure(LocalOf&& localOf, int nc, const std::vector<double>& r, const std::vector<double>& u,
                           const double* q) {
  double phi2 = 0, q2 = 0;
  for (int c = 0; c < nc; ++c) {
    AlartCurnier::Blocks b;
    const LocalCoulomb& local = localOf(c);
    local.residual(&r[3 * c], &u[3 * c], b);
    const double rhoN = local.rhoN(), rhoT = local.rhoT();
    phi2 += b.phi[0] * b.phi[0] + b.phi[1] * b.phi[1] + b.phi[2] * b.phi[2];
    q2 += rhoN * rhoN * q[3 * c] * q[3 * c] + rhoT * rhoT * (q[3 * c + 1] * q[3 * c + 1] + q[3 * c + 2] * q[3 * c + 2]);
  }
  return q2 > 0 ? std::sqrt(phi2 / q2) : std::sqrt(phi2);
}

}  // namespace

RCP<const ParameterList> NonsmoothGaussSeidel::validParameters() {
  static RCP<ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("NSGS");
    pl->set("Relative Tolerance", 1e-8,
            "stop when the stopping measure (default ||Phi(r)|| / ||rho q||, the Alart-Curnier residual; FCLIB: "
            "||F_nat|| / ||q||) is at most this; it is evaluated when a sweep changes r by at most this relative "
            "to ||r||",
            range<double>(1e-15, 1.0));
    pl->set("Maximum Iterations", 10000, "sweeps over the contacts", range<int>(1, 100000000));
    pl->set("Local Tolerance", 1e-14,
            "a sliding contact's Newton iteration stops at ||Phi_c|| <= this times (||r_c|| + rho_N ||q~_c||)",
            range<double>(1e-16, 1e-2));
    pl->set("Local Maximum Iterations", 30, "Newton steps per sliding contact and sweep", range<int>(1, 1000));
  }
  return pl;
}

NonsmoothGaussSeidel::NonsmoothGaussSeidel(const ParameterList& params) : SingleLoopSolver(params, validParameters()) {
  readSettings();
}

void NonsmoothGaussSeidel::readSettings() {
  tol_ = params_.get<double>("Relative Tolerance");
  maxSweeps_ = params_.get<int>("Maximum Iterations");
  localTol_ = params_.get<double>("Local Tolerance");
  localMaxIt_ = params_.get<int>("Local Maximum Iterations");
}

FrictionStatus NonsmoothGaussSeidel::solve(const ContactDual&, Vector&) {
  throw Error("NSGS reads the entries of W: it solves explicit (FCLIB) problems, not the FETI dual, whose operator is "
              "only applied; use Algorithm2 or Semismooth Newton there");
}

FrictionStatus NonsmoothGaussSeidel::solve(const ExplicitCoulombProblem& p, std::vector<double>& r,
                                           std::vector<double>& u) const {
  const auto start = std::chrono::steady_clock::now();
  const int nc = p.contacts, n = 3 * nc;
  TRIBOS_REQUIRE(p.W.rows == n && p.W.cols == n && static_cast<int>(r.size()) == n,
                 "NSGS: W is " << p.W.rows << " x " << p.W.cols << " and r has " << r.size() << " entries for " << nc
                               << " contacts");
  const ContactRows rows(p.W, nc);
  // A contact's local solver, made when a sweep first finds it pressed.
  std::vector<std::optional<LocalCoulomb>> local(nc);
  auto localOf = [&](int c) -> const LocalCoulomb& {
    if (!local[c]) local[c].emplace(rows.block(c), p.mu[c], localTol_, localMaxIt_);
    return *local[c];
  };
  // The blocked copy of W (or the dense one, when W is mostly full), made
  // once a problem has taken kBlockedAfter sweeps.
  constexpr int kBlockedAfter = 8;
  std::unique_ptr<const BlockRows> blocked;
  std::unique_ptr<const DenseRows> dense;
  // The q the sweeps use: p.q, and with W read from float rows (dense)
  // q~ = q + (W - W~) r_k at the last correction point r_k, so that W~ r +
  // q~ = W r + q there and the fixed point of the sweeps solves the exact
  // problem (defect correction).
  std::vector<double> q(p.q, p.q + n);
  constexpr int kMaxCorrections = 4;
  int corrections = 0;
  auto measure = [&](const std::vector<double>& rr, const std::vector<double>& uu) {
    return measure_ ? measure_(rr, uu) : alartCurnierMeasure(localOf, nc, rr, uu, p.q);
  };
  // The contacts whose force is not zero are counted: while there are none,
  // q~_c = q_c and a contact's rows need not be read. From r = 0 the first
  // sweep reads rows only from the first pressed contact on.
  auto hasForce = [](const double* f) { return f[0] != 0.0 || f[1] != 0.0 || f[2] != 0.0; };
  int forced = 0;
  for (int c = 0; c < nc; ++c) forced += hasForce(&r[3 * c]);
  // One sweep over the contacts with W read through M. It also writes each
  // contact's velocity u_c = q~_c + W_cc r_c as it leaves the contact; when
  // the sweep changed no force, every u_c saw the final forces of the
  // others, so u = W r + q without another pass over W (finite termination,
  // common when contacts open or stick). Returns whether r moved by at most
  // the tolerance relative to ||r||.
  bool unchanged = false;
  auto sweepWith = [&](const auto& M, FrictionStatus& st) {
    double change = 0, size = 0;
    unchanged = true;
    u.resize(n);
    for (int c = 0; c < nc; ++c) {
      double qt[3] = {q[3 * c], q[3 * c + 1], q[3 * c + 2]}, rc[3] = {r[3 * c], r[3 * c + 1], r[3 * c + 2]};
      const bool hadForce = hasForce(rc);
      if (forced > 0) M.offDiagonal(c, r.data(), q.data(), qt);
      double* uc = &u[3 * c];
      uc[0] = qt[0], uc[1] = qt[1], uc[2] = qt[2];
      if (qt[0] >= 0) {  // take-off, exact: neither W_cc nor the local solver is needed
        rc[0] = rc[1] = rc[2] = 0.0;
      } else {
        st.inner_iterations += localOf(c).solve(qt, rc);
        addProduct(rows.block(c), rc, uc);
      }
      for (int a = 0; a < 3; ++a) {
        const double d = rc[a] - r[3 * c + a];
        unchanged = unchanged && d == 0.0;
        change += d * d;
        size += rc[a] * rc[a];
        r[3 * c + a] = rc[a];
      }
      forced += int(hasForce(rc)) - int(hadForce);
    }
    return change <= tol_ * tol_ * size;
  };

  FrictionStatus st;
  // One check: u = W r + q (unless the last sweep left it so) and the
  // measure, recorded as a step.
  auto check = [&](int sweep, bool uCurrent) {
    if (forced == 0) {  // u = q without a pass over W
      u.assign(p.q, p.q + n);
    } else if (!uCurrent) {
      if (dense) dense->velocities(r, q.data(), u);
      else if (blocked) blocked->velocities(r, p.q, u);
      else rows.velocities(r, p.q, u);
      ++st.n_A;
    }
    const double m = measure(r, u);
    st.history.push_back(m);
    st.norm_gP = m;
    OuterStep step;
    step.iteration = sweep;
    step.projectedGradient = m;
    step.normGx = 0;
    step.slipBoundChange = std::numeric_limits<double>::quiet_NaN();
    step.n_A = st.n_A;
    step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    st.steps.push_back(step);
    if (!out_.is_null())
      *out_ << "NSGS sweep " << std::setw(6) << sweep << "  measure " << std::scientific << std::setprecision(3) << m
            << "\n";
    Progress::iteration([&] {
      return "NSGS sweep " + std::to_string(sweep) + ": measure " + Progress::sci(m) + ", tolerance " +
             Progress::sci(tol_);
    });
    return m;
  };

  // W~ met the tolerance: the measure again with u = W r + q from the exact
  // W (one pass over its CSR rows). When that misses, q is corrected at r,
  // q~ = q + W r - W~ r = u_exact - (u~ - q~), and the sweeps go on.
  auto confirmExact = [&]() {
    std::vector<double> exact;
    rows.velocities(r, p.q, exact);
    ++st.n_A;
    const double m = measure(r, exact);
    if (!out_.is_null())
      *out_ << "NSGS: the measure with the exact W " << std::scientific << std::setprecision(3) << m
            << (m <= tol_ || corrections == kMaxCorrections ? "" : "; q corrected for W's float rows") << "\n";
    st.history.back() = m;
    st.norm_gP = m;
    st.steps.back().projectedGradient = m;
    if (m > tol_ && corrections < kMaxCorrections) {
      for (int i = 0; i < n; ++i) q[i] = exact[i] - (u[i] - q[i]);
      ++corrections;
    }
    u.swap(exact);
    return m;
  };

  // A warm start may already solve the problem: measured. From r = 0 the
  // measure is taken only when r = 0 can be the solution, i.e. when every
  // contact opens, q_N >= 0 (r = 0 satisfies De Saxce's law iff
  // [u_N + mu ||u_T||, u_T] lies in the dual cone, i.e. u_N >= 0); otherwise
  // the first sweep moves r and the light test decides when to measure.
  const bool fromZero = forced == 0;
  bool zeroMaySolve = true;
  for (int c = 0; c < nc; ++c) zeroMaySolve = zeroMaySolve && p.q[3 * c] >= 0;
  double m = !fromZero || zeroMaySolve ? check(0, false) : std::numeric_limits<double>::max();
  int sweep = 0, gap = 1, nextCheck = 1;
  while (std::isfinite(m) && m > tol_ && sweep < maxSweeps_) {
    ++sweep;
    ++st.n_A;
    if (sweep == kBlockedAfter) {
      if (DenseRows::suits(p.W)) dense = std::make_unique<const DenseRows>(p.W, rows.blocks());
      else blocked = std::make_unique<const BlockRows>(p.W, rows.blocks());
    }
    const bool settled = dense ? sweepWith(*dense, st) : blocked ? sweepWith(*blocked, st) : sweepWith(rows, st);
    // The measure needs u = W r + q, another pass over W: when the sweep
    // moved r by at most the tolerance (the light test), at growing
    // intervals while that test passes and the measure does not, and every
    // kCheckEvery sweeps (with W singular, r may keep moving along ker W
    // while u has converged).
    constexpr int kCheckEvery = 64;
    if ((settled && sweep >= nextCheck) || sweep % kCheckEvery == 0 || sweep == maxSweeps_) {
      m = check(sweep, unchanged);
      if (dense && m <= tol_) m = confirmExact();
      nextCheck = sweep + gap;
      gap = std::min(2 * gap, 16);
    }
  }
  st.outer_iterations = sweep;
  st.slip_bound_change = 0;
  if (!std::isfinite(m)) {
    st.reason = "NSGS: the stopping measure is not finite after sweep " + std::to_string(sweep);
  } else if (m <= tol_) {
    st.converged = true;
    st.reason = "NSGS: stopping measure below tolerance after " + std::to_string(sweep) + " sweep(s)";
  } else {
    st.reason = "Maximum Iterations (" + std::to_string(maxSweeps_) + ") of NSGS reached";
  }
  return st;
}

}  // namespace Friction
}  // namespace Tribos
