#include "FrictionTestProblems.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Tribos_QP_EqualityConstraint.hpp"

namespace frictest {

using namespace Tribos;

// ------------------------------------------------------------------ dense

Vec multiply(const Dense& A, const Vec& x) {
  Vec y(A.n, 0.0);
  for (int i = 0; i < A.n; ++i)
    for (int j = 0; j < A.n; ++j) y[i] += A(i, j) * x[j];
  return y;
}

double norm(const Vec& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return std::sqrt(s);
}

double maxAbsDiff(const Vec& a, const Vec& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

bool solveDense(Dense A, Vec b, Vec& x) {
  const int n = A.n;
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(A(r, c)) > std::abs(A(piv, c))) piv = r;
    if (std::abs(A(piv, c)) < 1e-13) return false;
    for (int j = 0; j < n; ++j) std::swap(A(c, j), A(piv, j));
    std::swap(b[c], b[piv]);
    for (int r = c + 1; r < n; ++r) {
      const double f = A(r, c) / A(c, c);
      for (int j = c; j < n; ++j) A(r, j) -= f * A(c, j);
      b[r] -= f * b[c];
    }
  }
  x.assign(n, 0.0);
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < n; ++j) s -= A(i, j) * x[j];
    x[i] = s / A(i, i);
  }
  return true;
}

namespace {

// Deterministic uniform numbers in [-1, 1] (the tests must not depend on a
// library's random generator).
double uniform(unsigned& state) {
  state = state * 1664525u + 1013904223u;
  return 2.0 * (state >> 8) / double(1u << 24) - 1.0;
}

double dot(const Vec& a, const Vec& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// Orthonormal rows orthogonal to x: G x = 0 holds exactly for the manufactured x.
std::vector<Vec> equalityRows(int rows, const Vec& x, unsigned& state) {
  std::vector<Vec> basis{x}, G;
  for (auto& v : basis) {
    const double nv = norm(v);
    for (double& e : v) e /= nv;
  }
  for (int r = 0; r < rows; ++r) {
    Vec w(x.size());
    for (double& e : w) e = uniform(state);
    for (const Vec& q : basis) {
      const double c = dot(w, q);
      for (size_t i = 0; i < w.size(); ++i) w[i] -= c * q[i];
    }
    const double nw = norm(w);
    for (double& e : w) e /= nw;
    basis.push_back(w);
    G.push_back(w);
  }
  return G;
}

}  // namespace

Dense spdMatrix(int n, unsigned seed, double coupling) {
  Dense M(n), A(n);
  for (double& v : M.a) v = uniform(seed);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 0;
      for (int k = 0; k < n; ++k) s += M(i, k) * M(j, k);
      A(i, j) = (i == j ? 1.0 : 0.0) + coupling * s / n;
    }
  // Divide by the largest absolute row sum, a bound of ||A||.
  double rowMax = 0;
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int j = 0; j < n; ++j) s += std::abs(A(i, j));
    rowMax = std::max(rowMax, s);
  }
  for (double& v : A.a) v /= rowMax;
  return A;
}

Dense withoutNormalTangentialCoupling(const Problem& p, Dense A) {
  auto isNormal = [&](int i) { return i % p.dofsPerContact() == 0; };
  for (int i = 0; i < A.n; ++i)
    for (int j = 0; j < A.n; ++j)
      if (isNormal(i) != isNormal(j)) A(i, j) = 0.0;
  return A;
}

// ------------------------------------------------------------------ manufactured

namespace {

Vec direction(const Problem& p, double angle) {
  if (p.tangent == Tangent::Interval) return {std::cos(angle) >= 0 ? 1.0 : -1.0};
  return {std::cos(angle), std::sin(angle)};
}

}  // namespace

// KKT of min 1/2 x'Ax - b'x on Omega, G x = 0: s = A x - b + G'mu with
// s_N >= 0 where x_N = l (0 where x_N > l), s_T = -nu t where x_T = g t slips
// (0 where it sticks). Choose x, s and mu, then b = A x + G'mu - s.
Manufactured manufacture(const std::vector<ContactState>& states, const ManufacturedOptions& opt) {
  Manufactured m;
  Problem& p = m.problem;
  p.contacts = static_cast<int>(states.size());
  p.tangent = opt.tangent;
  p.law = opt.law;
  p.lower.assign(p.contacts, opt.lower);
  p.offset.assign(p.contacts, opt.offset);
  if (p.law == Law::Coulomb) p.friction.assign(p.contacts, opt.friction);
  p.A = spdMatrix(p.size(), opt.seed, opt.coupling);
  if (opt.decoupled) p.A = withoutNormalTangentialCoupling(p, p.A);
  Vec& x = m.x;
  Vec s(p.size(), 0.0);
  x.assign(p.size(), 0.0);
  for (int k = 0; k < p.contacts; ++k) {
    const ContactState& c = states[k];
    const int n = p.normal(k);
    x[n] = c.touching ? opt.lower + 0.5 + 0.25 * k : opt.lower;
    s[n] = c.touching ? 0.0 : 0.3 + 0.1 * k;
    const double g = p.law == Law::Tresca ? 0.4 + 0.1 * k : opt.friction * std::max(x[n] + opt.offset, 0.0);
    if (p.law == Law::Tresca) p.slipBound.push_back(g);
    const Vec t = direction(p, c.angle);
    const double nu = 0.2 + 0.1 * k;
    for (int j = 0; j < p.tangentialDims(); ++j) {
      x[p.tangential(k, j)] = (c.slipping ? 1.0 : 0.5) * g * t[j];
      // On a disk of radius 0 every s_T is admissible: make it nonzero.
      s[p.tangential(k, j)] = (c.slipping || g == 0.0) ? -nu * t[j] : 0.0;
    }
  }
  unsigned state = opt.seed + 7;
  p.G = equalityRows(opt.equalityRows, x, state);
  m.mu.resize(opt.equalityRows);
  for (int r = 0; r < opt.equalityRows; ++r) m.mu[r] = 0.3 - 0.5 * r;
  p.b = multiply(p.A, x);
  for (int i = 0; i < p.size(); ++i) {
    p.b[i] -= s[i];
    for (int r = 0; r < opt.equalityRows; ++r) p.b[i] += p.G[r][i] * m.mu[r];
  }
  return m;
}

// ------------------------------------------------------------------ residuals

Vec slipBoundAt(const Problem& p, const Vec& x) {
  if (p.law == Law::Tresca) return p.slipBound;
  Vec g(p.contacts);
  for (int k = 0; k < p.contacts; ++k) g[k] = p.friction[k] * std::max(x[p.normal(k)] + p.offset[k], 0.0);
  return g;
}

namespace {

Vec lagrangianGradient(const Problem& p, const Vec& x, const Vec& mu) {
  Vec s = multiply(p.A, x);
  for (int i = 0; i < p.size(); ++i) {
    s[i] -= p.b[i];
    for (size_t r = 0; r < p.G.size(); ++r) s[i] += p.G[r][i] * mu[r];
  }
  return s;
}

// Projection of the tangential pair (or single value) of contact k on the
// disk (interval) of radius g.
void projectTangential(const Problem& p, int k, double g, Vec& y) {
  double r2 = 0;
  for (int j = 0; j < p.tangentialDims(); ++j) r2 += y[p.tangential(k, j)] * y[p.tangential(k, j)];
  const double r = std::sqrt(r2);
  if (r <= g) return;
  for (int j = 0; j < p.tangentialDims(); ++j) y[p.tangential(k, j)] *= g / r;
}

}  // namespace

double naturalResidual(const Problem& p, const Vec& x, const Vec& mu, const Vec& g) {
  const Vec s = lagrangianGradient(p, x, mu);
  Vec y(p.size());
  for (int i = 0; i < p.size(); ++i) y[i] = x[i] - s[i];
  for (int k = 0; k < p.contacts; ++k) {
    y[p.normal(k)] = std::max(y[p.normal(k)], p.lower[k]);
    projectTangential(p, k, std::max(g[k], 0.0), y);
  }
  Vec r(p.size());
  for (int i = 0; i < p.size(); ++i) r[i] = x[i] - y[i];
  return norm(r) / norm(p.b);
}

double feasibilityViolation(const Problem& p, const Vec& x, const Vec& g) {
  double v = 0;
  for (int k = 0; k < p.contacts; ++k) {
    v = std::max(v, p.lower[k] - x[p.normal(k)]);
    double r2 = 0;
    for (int j = 0; j < p.tangentialDims(); ++j) r2 += x[p.tangential(k, j)] * x[p.tangential(k, j)];
    v = std::max(v, std::sqrt(r2) - std::max(g[k], 0.0));
  }
  for (const Vec& row : p.G) v = std::max(v, std::abs(dot(row, x)));
  return v;
}

// ------------------------------------------------------------------ enumeration

namespace {

enum class NormalState { Separated, Touching };
enum class TangentState { Stick, SlipPlus, SlipMinus };

// The linear system of one choice of states: a row of A x = b for every
// unknown whose gradient vanishes, the active constraint otherwise.
bool solveStates(const Problem& p, const std::vector<NormalState>& ns, const std::vector<TangentState>& ts, Vec& x) {
  Dense M(p.size());
  Vec rhs(p.size(), 0.0);
  auto gradientRow = [&](int i) {
    for (int j = 0; j < p.size(); ++j) M(i, j) = p.A(i, j);
    rhs[i] = p.b[i];
  };
  for (int k = 0; k < p.contacts; ++k) {
    const int n = p.normal(k), t = p.tangential(k, 0);
    if (ns[k] == NormalState::Touching) {
      gradientRow(n);
    } else {
      M(n, n) = 1.0;
      rhs[n] = p.lower[k];
    }
    if (ts[k] == TangentState::Stick) {
      gradientRow(t);
      continue;
    }
    const double sign = ts[k] == TangentState::SlipPlus ? 1.0 : -1.0;
    M(t, t) = 1.0;
    if (p.law == Law::Tresca) {
      rhs[t] = sign * p.slipBound[k];
    } else {  // x_T = sign F (x_N + offset)
      M(t, n) = -sign * p.friction[k];
      rhs[t] = sign * p.friction[k] * p.offset[k];
    }
  }
  return solveDense(M, rhs, x);
}

bool consistent(const Problem& p, const std::vector<NormalState>& ns, const std::vector<TangentState>& ts, const Vec& x) {
  const double tol = 1e-12 * (1.0 + norm(p.b));
  const Vec r = lagrangianGradient(p, x, Vec(p.G.size(), 0.0));
  const Vec g = slipBoundAt(p, x);
  for (int k = 0; k < p.contacts; ++k) {
    const int n = p.normal(k), t = p.tangential(k, 0);
    if (ns[k] == NormalState::Separated && r[n] < -tol) return false;
    if (ns[k] == NormalState::Touching && x[n] < p.lower[k] - tol) return false;
    if (p.law == Law::Coulomb && ts[k] != TangentState::Stick && x[n] + p.offset[k] < -tol) return false;
    if (ts[k] == TangentState::Stick && std::abs(x[t]) > g[k] + tol) return false;
    if (ts[k] == TangentState::SlipPlus && r[t] > tol) return false;
    if (ts[k] == TangentState::SlipMinus && r[t] < -tol) return false;
  }
  return true;
}

}  // namespace

std::vector<Vec> enumerateSolutions(const Problem& p) {
  if (p.tangent != Tangent::Interval || !p.G.empty())
    throw std::logic_error("enumerateSolutions: Interval problems without G only");
  std::vector<Vec> found;
  int combinations = 1;
  for (int k = 0; k < p.contacts; ++k) combinations *= 6;
  for (int c = 0; c < combinations; ++c) {
    std::vector<NormalState> ns(p.contacts);
    std::vector<TangentState> ts(p.contacts);
    for (int k = 0, code = c; k < p.contacts; ++k, code /= 6) {
      ns[k] = static_cast<NormalState>(code % 2);
      ts[k] = static_cast<TangentState>((code / 2) % 3);
    }
    Vec x;
    if (!solveStates(p, ns, ts, x) || !consistent(p, ns, ts, x)) continue;
    const bool known = std::any_of(found.begin(), found.end(), [&](const Vec& y) { return maxAbsDiff(x, y) < 1e-10; });
    if (!known) found.push_back(x);
  }
  return found;
}

// ------------------------------------------------------------------ Tpetra

RCP<Vector> toVector(const RCP<const Map>& map, const Vec& x) {
  auto v = rcp(new Vector(map));
  auto data = v->getDataNonConst();
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) data[l] = x[map->getGlobalElement(l)];
  return v;
}

Vec gather(const Vector& x) {
  const auto& map = *x.getMap();
  Vec local(map.getGlobalNumElements(), 0.0), global(local.size(), 0.0);
  auto data = x.getData();
  for (LO l = 0; l < static_cast<LO>(map.getNodeNumElements()); ++l) local[map.getGlobalElement(l)] = data[l];
  Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(), global.data());
  return global;
}

Vec gatherContacts(const Vec& local, const DistributedDual& d, int contacts) {
  Vec part(contacts, 0.0), global(contacts, 0.0);
  for (size_t k = 0; k < local.size(); ++k) part[d.firstContact + k] = local[k];
  Teuchos::reduceAll(*d.map->getComm(), Teuchos::REDUCE_SUM, contacts, part.data(), global.data());
  return global;
}

namespace {

RCP<CrsMatrix> denseRows(const RCP<const Map>& rowMap, int columns, const std::vector<Vec>& rows) {
  auto M = rcp(new CrsMatrix(rowMap, columns));
  std::vector<GO> cols(columns);
  for (int j = 0; j < columns; ++j) cols[j] = j;
  for (LO l = 0; l < static_cast<LO>(rowMap->getNodeNumElements()); ++l) {
    const GO r = rowMap->getGlobalElement(l);
    M->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const SC>(rows[r]));
  }
  return M;
}

std::vector<Vec> rowsOf(const Dense& A) {
  std::vector<Vec> rows(A.n);
  for (int i = 0; i < A.n; ++i) rows[i].assign(A.a.begin() + i * A.n, A.a.begin() + (i + 1) * A.n);
  return rows;
}

}  // namespace

DistributedDual buildDual(const Problem& p, const RCP<const Comm>& comm) {
  DistributedDual d;
  const int P = comm->getSize(), r = comm->getRank(), dofs = p.dofsPerContact();
  d.firstContact = p.contacts * r / P;
  const int count = p.contacts * (r + 1) / P - d.firstContact;
  d.map = rcp(new Map(static_cast<Tpetra::global_size_t>(p.size()), static_cast<size_t>(count * dofs), 0, comm));
  auto A = denseRows(d.map, p.size(), rowsOf(p.A));
  A->fillComplete();
  Friction::ContactDual& dual = d.dual;
  dual.A = A;
  dual.b = toVector(d.map, p.b);
  if (!p.G.empty()) {
    auto coarse = rcp(new Map(static_cast<Tpetra::global_size_t>(p.G.size()), 0, comm));
    auto G = denseRows(coarse, p.size(), p.G);
    G->fillComplete(d.map, coarse);
    dual.G = rcp(new QP::CrsEqualityConstraint(G));
  }
  for (int k = 0; k < count; ++k) {
    const int global = d.firstContact + k;
    dual.normalRows.push_back(dofs * k);
    dual.tangentRows.push_back(dofs * k + 1);
    dual.tangentRows.push_back(p.tangent == Tangent::Disk ? dofs * k + 2 : -1);
    dual.normalLower.push_back(p.lower[global]);
    dual.normalOffset.push_back(p.offset[global]);
    if (p.law == Law::Tresca) dual.slipBound.push_back(p.slipBound[global]);
    else dual.frictionCoefficient.push_back(p.friction[global]);
  }
  return d;
}

Teuchos::ParameterList solverParameters(double tolerance) {
  Teuchos::ParameterList pl("Solver");
  auto& a1 = pl.sublist("Algorithm 1");
  a1.sublist("SMALBE").set("Relative Tolerance", tolerance);
  a1.sublist("SMALBE").set("Maximum Outer Iterations", 1000);
  pl.sublist("MSA").set("Tolerance", tolerance);
  pl.sublist("MSA").set("Maximum Iterations", 500);
  pl.sublist("Algorithm 2").set("Relative Tolerance", tolerance);
  pl.sublist("Algorithm 2").set("Maximum Iterations", 5000);
  pl.sublist("Semismooth Newton").set("Relative Tolerance", tolerance);
  return pl;
}

}  // namespace frictest
