#include "Tribos_RigidMotions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Fem {

namespace {

// Eigen-decomposition of a small symmetric n x n matrix (row-major) by
// cyclic Jacobi rotations: A = V diag(values) V', V row-major with the
// eigenvectors as columns.
void symmetricEigen(int n, std::vector<double> A, std::vector<double>& values, std::vector<double>& V) {
  V.assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) V[i * n + i] = 1;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0, diag = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) (i == j ? diag : off) += A[i * n + j] * A[i * n + j];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = A[p * n + q];
        if (apq == 0) continue;
        const double theta = (A[q * n + q] - A[p * n + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {  // A <- A J
          const double akp = A[k * n + p], akq = A[k * n + q];
          A[k * n + p] = c * akp - s * akq;
          A[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // A <- J' A
          const double apk = A[p * n + k], aqk = A[q * n + k];
          A[p * n + k] = c * apk - s * aqk;
          A[q * n + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {  // V <- V J
          const double vkp = V[k * n + p], vkq = V[k * n + q];
          V[k * n + p] = c * vkp - s * vkq;
          V[k * n + q] = s * vkp + c * vkq;
        }
      }
  }
  values.resize(n);
  for (int i = 0; i < n; ++i) values[i] = A[i * n + i];
}

// Names the directions spanned by dirs (3-vectors): by coordinate axis when
// the span is spanned by axes ("translation x"), else by the vectors.
void nameDirections(std::vector<std::array<double, 3>> dirs, const std::string& kind, std::vector<std::string>& out) {
  // Orthonormal basis of the span (Gram-Schmidt; the vectors are independent).
  std::vector<std::array<double, 3>> basis;
  for (auto d : dirs) {
    for (const auto& b : basis) {
      const double s = dot(d, b);
      for (int a = 0; a < 3; ++a) d[a] -= s * b[a];
    }
    const double len = norm(d);
    if (len < 1e-8) continue;
    for (double& v : d) v /= len;
    basis.push_back(d);
  }
  std::vector<int> axes;
  for (int a = 0; a < 3; ++a) {
    double proj = 0;  // ||P e_a||^2
    for (const auto& b : basis) proj += b[a] * b[a];
    if (proj > 1 - 1e-8) axes.push_back(a);
  }
  const std::string prefix = kind == "rotation" ? "rotation about " : "translation ";
  if (axes.size() == basis.size()) {
    for (int a : axes) out.push_back(prefix + "xyz"[a]);
    return;
  }
  for (const auto& b : basis) {
    std::ostringstream os;
    os << (kind == "rotation" ? "rotation about the axis (" : "translation along (");
    for (int a = 0; a < 3; ++a) os << (a ? ", " : "") << (std::abs(b[a]) < 5e-4 ? 0.0 : std::round(b[a] * 1000) / 1000);
    os << ")";
    out.push_back(os.str());
  }
}

}  // namespace

std::vector<std::string> freeRigidMotions(const std::vector<std::array<double, 3>>& coords,
                                          const std::map<long long, double>& dirichlet) {
  std::vector<HeldDirection> held;
  held.reserve(dirichlet.size());
  for (const auto& entry : dirichlet) {
    const long long dof = entry.first;
    TRIBOS_REQUIRE(dof >= 0 && static_cast<size_t>(dof / 3) < coords.size(),
                   "rigid motions: Dirichlet dof " << dof << " out of range");
    HeldDirection h{static_cast<int>(dof / 3), {0, 0, 0}};
    h.direction[dof % 3] = 1;
    held.push_back(h);
  }
  return freeRigidMotions(coords, held);
}

std::vector<std::string> freeRigidMotions(const std::vector<std::array<double, 3>>& coords,
                                          const std::vector<HeldDirection>& held) {
  const size_t N = coords.size();
  TRIBOS_REQUIRE(N > 0, "rigid motions: no node coordinates");
  // Rigid motions about the centroid, rotations scaled by the body's size, so
  // that all six columns have entries of order one.
  std::array<double, 3> c{0, 0, 0};
  for (const auto& X : coords)
    for (int a = 0; a < 3; ++a) c[a] += X[a] / N;
  double L = 0;
  for (const auto& X : coords)
    L = std::max(L, std::sqrt((X[0] - c[0]) * (X[0] - c[0]) + (X[1] - c[1]) * (X[1] - c[1]) + (X[2] - c[2]) * (X[2] - c[2])));
  if (L == 0) L = 1;

  // M = D'D, D = the six motions along the held directions: its null space
  // is the set of motions they leave free.
  std::vector<double> M(36, 0.0);
  for (const auto& h : held) {
    TRIBOS_REQUIRE(h.node >= 0 && static_cast<size_t>(h.node) < N, "rigid motions: node " << h.node << " out of range");
    const auto& X = coords[h.node];
    const double norm = std::sqrt(h.direction[0] * h.direction[0] + h.direction[1] * h.direction[1] +
                                  h.direction[2] * h.direction[2]);
    if (norm == 0) continue;
    const Point r{(X[0] - c[0]) / L, (X[1] - c[1]) / L, (X[2] - c[2]) / L};
    // Columns: translation along axis b, then rotation about axis b (e_b x r),
    // so that the rotational part of a motion is its axis.
    double row[6] = {0, 0, 0, 0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      const double d = h.direction[a] / norm;
      row[a] = d;
      for (int b = 0; b < 3; ++b) row[3 + b] += d * rotation(b, r)[a];
    }
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) M[6 * i + j] += row[i] * row[j];
  }
  std::vector<double> lambda, V;
  symmetricEigen(6, M, lambda, V);
  const double lmax = *std::max_element(lambda.begin(), lambda.end());
  std::vector<std::array<double, 6>> nullspace;
  for (int k = 0; k < 6; ++k)
    if (lambda[k] <= 1e-10 * lmax || lmax <= 0) {
      std::array<double, 6> v;
      for (int i = 0; i < 6; ++i) v[i] = V[6 * i + k];
      nullspace.push_back(v);
    }
  const int kdim = static_cast<int>(nullspace.size());
  if (kdim == 0) return {};

  // Split the free motions into pure translations (no rotational part) and
  // rotations: the eigenvectors of W'W, W = rotational parts of the null
  // vectors.
  std::vector<double> WtW(static_cast<size_t>(kdim) * kdim, 0.0);
  for (int i = 0; i < kdim; ++i)
    for (int j = 0; j < kdim; ++j)
      for (int b = 0; b < 3; ++b) WtW[i * kdim + j] += nullspace[i][3 + b] * nullspace[j][3 + b];
  std::vector<double> mu, Z;
  symmetricEigen(kdim, WtW, mu, Z);
  std::vector<std::array<double, 3>> translations, rotations;
  for (int k = 0; k < kdim; ++k) {
    std::array<double, 3> t{0, 0, 0}, w{0, 0, 0};
    for (int i = 0; i < kdim; ++i)
      for (int b = 0; b < 3; ++b) {
        t[b] += Z[i * kdim + k] * nullspace[i][b];
        w[b] += Z[i * kdim + k] * nullspace[i][3 + b];
      }
    if (mu[k] <= 1e-10) translations.push_back(t);
    else rotations.push_back(w);
  }
  std::vector<std::string> names;
  nameDirections(translations, "translation", names);
  nameDirections(rotations, "rotation", names);
  return names;
}

void requireRigidMotionsHeld(const std::vector<std::array<double, 3>>& coords,
                             const std::map<long long, double>& dirichlet, const std::string& method,
                             const std::string& advice) {
  const std::vector<std::string> free = freeRigidMotions(coords, dirichlet);
  if (free.empty()) return;
  std::string list;
  for (size_t k = 0; k < free.size(); ++k) list += (k ? ", " : "") + free[k];
  throw CollectiveError(method + ": the Dirichlet conditions leave the rigid motion" + (free.size() > 1 ? "s " : " ") +
                        list + " free; " + advice);
}

}  // namespace Fem
}  // namespace Tribos
