// QPTestUtils.hpp: dense references and distributed problem builders shared
// by the qp tests. Every rank builds the same dense data from a fixed seed;
// references are computed densely (independently of the library) on every rank.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_QP_ConstraintSet.hpp"
#include "Tribos_QP_Solver.hpp"
#include "Tribos_QP_Status.hpp"
#include "Tribos_Types.hpp"

namespace qptest {

using namespace Tribos;
using Vec = std::vector<double>;
const double inf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------- checks
template <class F>
bool throwsWith(F f, const std::string& fragment, std::string* msg = nullptr) {
  try {
    f();
  } catch (const std::exception& e) {
    if (msg) *msg = e.what();
    return std::string(e.what()).find(fragment) != std::string::npos;
  }
  return false;
}

inline std::string str(double v) {
  std::ostringstream os;
  os.precision(3);
  os << std::scientific << v;
  return os.str();
}

// ---------------------------------------------------------------- dense linear algebra
struct Dense {
  int n = 0;
  Vec a;  // row-major
  double& operator()(int i, int j) { return a[i * n + j]; }
  double operator()(int i, int j) const { return a[i * n + j]; }
};

class Rng {
 public:
  explicit Rng(uint32_t seed) : g_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * (g_() / 4294967296.0); }

 private:
  std::mt19937 g_;
};

// A = R'R/n + shift I with R uniform in (-1,1): SPD, condition number moderate.
inline Dense randomSPD(int n, uint32_t seed, double shift = 0.3) {
  Rng rng(seed);
  Dense R{n, Vec(n * n)}, A{n, Vec(n * n, 0.0)};
  for (auto& r : R.a) r = rng.uniform(-1, 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 0;
      for (int k = 0; k < n; ++k) s += R(k, i) * R(k, j);
      A(i, j) = s / n + (i == j ? shift : 0.0);
    }
  return A;
}

inline Vec randomVec(int n, uint32_t seed, double lo, double hi) {
  Rng rng(seed);
  Vec v(n);
  for (auto& x : v) x = rng.uniform(lo, hi);
  return v;
}

inline Vec matvec(const Dense& A, const Vec& x) {
  Vec y(A.n, 0.0);
  for (int i = 0; i < A.n; ++i)
    for (int j = 0; j < A.n; ++j) y[i] += A(i, j) * x[j];
  return y;
}

inline double dot(const Vec& x, const Vec& y) {
  double s = 0;
  for (size_t i = 0; i < x.size(); ++i) s += x[i] * y[i];
  return s;
}

inline double normInf(const Vec& x) {
  double m = 0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

// Gaussian elimination with partial pivoting on a general m x m system.
inline Vec denseSolve(std::vector<Vec> M, Vec r) {
  const int m = static_cast<int>(r.size());
  for (int k = 0; k < m; ++k) {
    int piv = k;
    for (int i = k + 1; i < m; ++i)
      if (std::abs(M[i][k]) > std::abs(M[piv][k])) piv = i;
    std::swap(M[k], M[piv]);
    std::swap(r[k], r[piv]);
    if (M[k][k] == 0) throw std::runtime_error("denseSolve: singular");
    for (int i = k + 1; i < m; ++i) {
      const double f = M[i][k] / M[k][k];
      for (int j = k; j < m; ++j) M[i][j] -= f * M[k][j];
      r[i] -= f * r[k];
    }
  }
  Vec x(m);
  for (int k = m - 1; k >= 0; --k) {
    double s = r[k];
    for (int j = k + 1; j < m; ++j) s -= M[k][j] * x[j];
    x[k] = s / M[k][k];
  }
  return x;
}

inline Vec denseSolve(const Dense& A, const Vec& b) {
  std::vector<Vec> M(A.n, Vec(A.n));
  for (int i = 0; i < A.n; ++i)
    for (int j = 0; j < A.n; ++j) M[i][j] = A(i, j);
  return denseSolve(M, b);
}

// ---------------------------------------------------------------- feasible sets, densely
// Per global index: 'F' free, 'L' lower, 'B' box, 'X' fixed, 'C' circle
// (pairs 2k, 2k+1 with radius r[k]).
struct SetSpec {
  std::string kind;
  Vec lo, up, r;  // r indexed by pair k = i/2
  int n() const { return static_cast<int>(kind.size()); }
};

// Dense projection onto the set; fixed components are kept at xfix.
inline void denseProject(const SetSpec& s, Vec& x, const Vec& xfix) {
  for (int i = 0; i < s.n(); ++i) {
    switch (s.kind[i]) {
      case 'L': x[i] = std::max(x[i], s.lo[i]); break;
      case 'B': x[i] = std::min(std::max(x[i], s.lo[i]), s.up[i]); break;
      case 'X': x[i] = xfix[i]; break;
      case 'C':
        if (i % 2 == 0) {
          const double nx = std::hypot(x[i], x[i + 1]), r = s.r[i / 2];
          if (nx > r) {
            x[i] = nx > 0 ? x[i] * r / nx : 0;
            x[i + 1] = nx > 0 ? x[i + 1] * r / nx : 0;
          }
        }
        break;
      default: break;
    }
  }
}

// Projected-gradient reference: x <- P(x - g/L), L = ||A||_F >= ||A||_2,
// until the step is below 1e-15 relative (or maxIt).
inline Vec projectedGradientReference(const Dense& A, const Vec& b, const SetSpec& s, Vec x, int maxIt = 2000000) {
  double L = 0;
  for (double v : A.a) L += v * v;
  L = std::sqrt(L);
  const Vec xfix = x;
  denseProject(s, x, xfix);
  for (int it = 0; it < maxIt; ++it) {
    Vec g = matvec(A, x);
    Vec y = x;
    for (int i = 0; i < A.n; ++i) y[i] -= (g[i] - b[i]) / L;
    denseProject(s, y, xfix);
    double d = 0;
    for (int i = 0; i < A.n; ++i) d = std::max(d, std::abs(y[i] - x[i]));
    x = y;
    if (d <= 1e-15 * (1 + normInf(x))) break;
  }
  return x;
}

// KKT residual of x for min 1/2 x'Ax - b'x + (optional) mu'Gx over the set:
// max over components of the violation of feasibility, stationarity
// (free: g = 0; lower active: g >= 0; upper active: g <= 0; circle boundary:
// g = -lambda n with lambda >= 0) and complementarity. g is given.
inline double kktViolation(const SetSpec& s, const Vec& x, const Vec& g, double activeTol = 1e-8) {
  double v = 0;
  for (int i = 0; i < s.n(); ++i) {
    const char k = s.kind[i];
    if (k == 'F') v = std::max(v, std::abs(g[i]));
    if (k == 'L' || k == 'B') {
      v = std::max(v, s.lo[i] - x[i]);  // feasibility
      if (k == 'B') v = std::max(v, x[i] - s.up[i]);
      const bool atLo = x[i] <= s.lo[i] + activeTol;
      const bool atUp = k == 'B' && x[i] >= s.up[i] - activeTol;
      if (atLo && !atUp) v = std::max(v, -g[i]);          // multiplier g_i >= 0
      else if (atUp && !atLo) v = std::max(v, g[i]);      // multiplier -g_i >= 0
      else if (!atLo && !atUp) v = std::max(v, std::abs(g[i]));  // inactive: g_i = 0
      // complementarity: multiplier times slack
      v = std::max(v, std::abs(g[i]) * std::min(std::abs(x[i] - s.lo[i]), k == 'B' ? std::abs(s.up[i] - x[i]) : inf));
    }
    if (k == 'C' && i % 2 == 0) {
      const double r = s.r[i / 2], nx = std::hypot(x[i], x[i + 1]);
      v = std::max(v, nx - r);
      if (r == 0) continue;  // a point: any gradient is stationary
      if (nx < r - activeTol) {
        v = std::max(v, std::hypot(g[i], g[i + 1]));
      } else {
        const double n1 = x[i] / nx, n2 = x[i + 1] / nx;
        const double lambda = -(n1 * g[i] + n2 * g[i + 1]);
        v = std::max(v, -lambda);                                                // lambda >= 0
        v = std::max(v, std::hypot(g[i] + lambda * n1, g[i + 1] + lambda * n2));  // tangential part 0
        v = std::max(v, std::abs(lambda) * std::abs(r - nx));                      // complementarity
      }
    }
  }
  return v;
}

// ---------------------------------------------------------------- distributed objects
// Map with n global entries; ranks get whole pairs so that circles are local.
inline RCP<const Map> pairMap(int n, const RCP<const Comm>& comm) {
  const int P = comm->getSize(), p = comm->getRank();
  const int pairs = n / 2;
  int myPairs = pairs / P + (p < pairs % P ? 1 : 0);
  int local = 2 * myPairs + ((n % 2 == 1 && p == P - 1) ? 1 : 0);
  return rcp(new Map(static_cast<Tpetra::global_size_t>(n), static_cast<size_t>(local), 0, comm));
}

inline RCP<CrsMatrix> toCrs(const RCP<const Map>& map, const Dense& A) {
  auto M = rcp(new CrsMatrix(map, A.n));
  std::vector<GO> cols(A.n);
  for (int j = 0; j < A.n; ++j) cols[j] = j;
  for (size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO i = map->getGlobalElement(static_cast<LO>(l));
    Vec row(A.a.begin() + i * A.n, A.a.begin() + (i + 1) * A.n);
    M->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(row));
  }
  M->fillComplete();
  return M;
}

inline RCP<Vector> toVector(const RCP<const Map>& map, const Vec& v) {
  auto x = rcp(new Vector(map));
  auto xv = x->getDataNonConst();
  for (size_t l = 0; l < map->getNodeNumElements(); ++l) xv[l] = v[map->getGlobalElement(static_cast<LO>(l))];
  return x;
}

// The whole vector on every rank.
inline Vec gather(const Vector& x) {
  const auto& map = x.getMap();
  auto rep = rcp(new Map(map->getGlobalNumElements(), 0, map->getComm(), Tpetra::LocallyReplicated));
  Import imp(map, rep);
  Vector xr(rep);
  xr.doImport(x, imp, Tpetra::INSERT);
  auto d = xr.getData();
  return Vec(d.begin(), d.end());
}

inline QP::ConstraintSet makeSet(const RCP<const Map>& map, const SetSpec& s) {
  QP::ConstraintSet Omega(map);
  std::vector<SC> radii;
  for (size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO i = map->getGlobalElement(static_cast<LO>(l));
    switch (s.kind[i]) {
      case 'L': Omega.setLower(l, s.lo[i]); break;
      case 'B': Omega.setBox(l, s.lo[i], s.up[i]); break;
      case 'X': Omega.setFixed(l); break;
      case 'C':
        if (i % 2 == 0) {
          Omega.setCircle(l, l + 1, static_cast<int>(radii.size()));
          radii.push_back(s.r[i / 2]);
        }
        break;
      default: break;
    }
  }
  Omega.setRadii(radii);
  return Omega;
}

// Wraps A and counts its applications.
class CountingOperator : public Operator {
 public:
  explicit CountingOperator(RCP<const Operator> A) : A_(A) {}
  RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    count += static_cast<long>(X.getNumVectors());
    A_->apply(X, Y, mode, alpha, beta);
  }
  mutable long count = 0;

 private:
  RCP<const Operator> A_;
};

}  // namespace qptest

namespace qptest {

// Exact solution of min 1/2 x'Ax - b'x s.t. lo <= x <= up (entries may be
// infinite) and G x = 0 (rows of G, possibly none), by enumerating all
// active sets: for each, solve the KKT system of the free part and accept
// the one that is feasible with multipliers of the right sign. Strict
// convexity makes it unique. Returns false if none is found.
inline bool enumerateActiveSets(const Dense& A, const Vec& b, const Vec& lo, const Vec& up,
                                const std::vector<Vec>& G, Vec& x, Vec& mu, double tol = 1e-10) {
  const int n = A.n, m = static_cast<int>(G.size());
  std::vector<int> state(n, 0);  // 0 free, 1 at lower, 2 at upper
  auto allowed = [&](int i, int s) { return s == 0 || (s == 1 && std::isfinite(lo[i])) || (s == 2 && std::isfinite(up[i])); };
  for (;;) {
    bool valid = true;
    for (int i = 0; i < n; ++i) valid = valid && allowed(i, state[i]);
    if (valid) {
      std::vector<int> F;
      Vec xs(n, 0.0);
      for (int i = 0; i < n; ++i) {
        if (state[i] == 0) F.push_back(i);
        else xs[i] = state[i] == 1 ? lo[i] : up[i];
      }
      const int nf = static_cast<int>(F.size()), k = nf + m;
      std::vector<Vec> K(k, Vec(k, 0.0));
      Vec r(k, 0.0);
      const Vec Axs = matvec(A, xs);
      for (int a = 0; a < nf; ++a) {
        for (int c = 0; c < nf; ++c) K[a][c] = A(F[a], F[c]);
        for (int j = 0; j < m; ++j) K[a][nf + j] = K[nf + j][a] = G[j][F[a]];
        r[a] = b[F[a]] - Axs[F[a]];
      }
      for (int j = 0; j < m; ++j) r[nf + j] = -dot(G[j], xs);
      bool solved = true;
      Vec z;
      try {
        z = k > 0 ? denseSolve(K, r) : Vec();
      } catch (...) {
        solved = false;
      }
      if (solved) {
        Vec xc = xs, muc(m);
        for (int a = 0; a < nf; ++a) xc[F[a]] = z[a];
        for (int j = 0; j < m; ++j) muc[j] = z[nf + j];
        Vec g = matvec(A, xc);
        for (int i = 0; i < n; ++i) {
          g[i] -= b[i];
          for (int j = 0; j < m; ++j) g[i] += G[j][i] * muc[j];
        }
        bool ok = true;
        for (int i = 0; i < n && ok; ++i) {
          ok = xc[i] >= lo[i] - tol && xc[i] <= up[i] + tol;
          if (state[i] == 1) ok = ok && g[i] >= -tol;
          if (state[i] == 2) ok = ok && g[i] <= tol;
        }
        if (ok) {
          x = xc;
          mu = muc;
          return true;
        }
      }
    }
    int i = 0;  // next state (odometer)
    while (i < n && state[i] == 2) state[i++] = 0;
    if (i == n) return false;
    ++state[i];
  }
}

// Largest |x_i - ref_i| over the global vector.
inline double maxError(const Vector& x, const Vec& ref) {
  const Vec xg = gather(x);
  double m = 0;
  for (size_t i = 0; i < ref.size(); ++i) m = std::max(m, std::abs(xg[i] - ref[i]));
  return m;
}

inline Vec gradient(const Dense& A, const Vec& b, const Vec& x) {
  Vec g = matvec(A, x);
  for (size_t i = 0; i < g.size(); ++i) g[i] -= b[i];
  return g;
}

}  // namespace qptest

namespace qptest {

// Result of one solve in the tests: status, solution gathered to every rank,
// and the Hessian applications counted by the test's own counting operator.
struct Run {
  Tribos::QP::QPStatus st;
  Vec x;
  long counted = 0;
};

// Solves min 1/2 x'Ax - b'x on Omega(s) from x0, distributed by pairMap; with
// `keep` (global flags), the entries outside it are frozen at x0.
inline Run solve(QP::QPSolver& solver, const RCP<const Comm>& comm, const Dense& A, const Vec& b, const SetSpec& s,
                 const Vec& x0, const std::vector<char>& keep = {}) {
  auto map = pairMap(A.n, comm);
  CountingOperator Aop(toCrs(map, A));
  auto bv = toVector(map, b);
  auto x = toVector(map, x0);
  QP::ConstraintSet Omega = makeSet(map, s);
  if (!keep.empty()) {
    std::vector<char> keepLocal(map->getNodeNumElements());
    for (size_t l = 0; l < keepLocal.size(); ++l) keepLocal[l] = keep[map->getGlobalElement(static_cast<LO>(l))];
    Omega = Omega.fixedOutside(keepLocal);
  }
  Run r;
  r.st = solver.solve(Aop, *bv, Omega, *x);
  r.x = gather(*x);
  r.counted = Aop.count;
  return r;
}

// n_A = the norm estimate's Lanczos steps + initial gradient + one per CG / proportioning
// step + two per expansion step (A p, then A x after the projection).
// `power`: the Lanczos steps asked for, of which the estimate takes at most
// n (the problem's dimension, r.x.size()).
void checkCounts(const Run& r, int power, const std::string& name, Teuchos::FancyOStream& out, bool& success) {
  out << name << ": counts\n";
  TEST_EQUALITY(r.counted, r.st.n_A);  // n_A is the number of applications of A
  const long expected = std::min<long>(power, static_cast<long>(r.x.size())) + 1 + r.st.cg_steps + r.st.proportioning_steps + 2L * r.st.expansion_steps;
  TEST_EQUALITY(r.st.n_A, expected);  // the step accounting
  TEST_EQUALITY(r.st.iterations, r.st.cg_steps + r.st.expansion_steps + r.st.proportioning_steps);  // step counts add up
}

// max_i |a_i - b_i|
inline double maxDiff(const Vec& a, const Vec& b) {
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

// Solver parameters with the given relative tolerance and iteration limit.
inline Teuchos::RCP<Teuchos::ParameterList> params(double rtol, int maxIt = 2000) {
  auto p = Teuchos::rcp(new Teuchos::ParameterList);
  p->set("Relative Tolerance", rtol);
  p->set("Maximum Iterations", maxIt);
  return p;
}

}  // namespace qptest
