#include "Tribos_FCLIB_Accuracy.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "Tribos_ArrayScan.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {
namespace FCLIB {

namespace {

// sqrt(a^2 + b^2): the plain formula where its squares can neither
// overflow nor lose digits to underflow, and 0 for a = b = 0 (a contact
// without tangential force or slip: most contacts of a multibody problem);
// std::hypot (several times slower) elsewhere. The natural map takes two
// per contact.
inline double length2(double a, double b) {
  const double s = a * a + b * b;
  if (s < 1e300 && s > 1e-300) return std::sqrt(s);
  return a == 0.0 && b == 0.0 ? 0.0 : std::hypot(a, b);
}

}  // namespace

std::array<double, 3> projectOntoCoulombCone(const std::array<double, 3>& r, double mu) {
  const double normal = r[0];
  const double normT = length2(r[1], r[2]);
  if (mu * normT <= -normal) return {0.0, 0.0, 0.0};  // polar cone
  if (normT <= mu * normal) return r;                 // already in K
  // Here normT > 0: otherwise one of the two tests above holds.
  const double t = (normal + mu * normT) / (1.0 + mu * mu);
  const double scale = mu * t / normT;
  return {t, scale * r[1], scale * r[2]};
}

namespace {

// A non-finite normalizer (inf or nan in q, r or u) gives nan, never the 0
// that value / inf would: an error relative to an infinite scale says nothing.
double safeDivide(double value, double normalizer) {
  if (!std::isfinite(normalizer)) return std::numeric_limits<double>::quiet_NaN();
  return normalizer > DBL_MIN ? value / normalizer : value;
}

}  // namespace

NaturalMapError naturalMapError(const std::vector<double>& r, const std::vector<double>& u,
                                const std::vector<double>& mu, const std::vector<double>& q) {
  const std::size_t m = 3 * mu.size();
  if (r.size() != m || u.size() != m || q.size() != m)
    throw Error("naturalMapError: r, u, q have " + std::to_string(r.size()) + ", " +
                             std::to_string(u.size()) + ", " + std::to_string(q.size()) +
                             " entries, expected 3 x " + std::to_string(mu.size()) +
                             " contacts");
  double sum = 0.0;
  for (std::size_t c = 0; c < mu.size(); ++c) {
    const double* rc = &r[3 * c];
    const double* uc = &u[3 * c];
    const double uNmodified = uc[0] + mu[c] * length2(uc[1], uc[2]);
    const std::array<double, 3> p =
        projectOntoCoulombCone({rc[0] - uNmodified, rc[1] - uc[1], rc[2] - uc[2]}, mu[c]);
    for (int k = 0; k < 3; ++k) sum += (rc[k] - p[k]) * (rc[k] - p[k]);
  }
  NaturalMapError e;
  e.absolute = std::sqrt(sum);
  e.normQ = norm2(q);
  e.normR = norm2(r);
  e.normU = norm2(u);
  e.relativeToQ = safeDivide(e.absolute, e.normQ);
  // std::max would drop a nan norm; the sum keeps it (and an inf).
  const double anyNonFinite = e.normQ + e.normR + e.normU;
  e.relativeToMax = safeDivide(e.absolute, std::isfinite(anyNonFinite)
                                               ? std::max({e.normQ, e.normR, e.normU})
                                               : anyNonFinite);
  return e;
}

NaturalMapError naturalMapError(const LocalProblem& problem, const std::vector<double>& r) {
  if (problem.spacedim != 3)
    throw Error("naturalMapError: only spacedim = 3 is supported");
  std::vector<double> u;
  problem.W.multiply(r, u);
  for (std::size_t k = 0; k < u.size(); ++k) u[k] += problem.q[k];
  return naturalMapError(r, u, problem.mu, problem.q);
}

GlobalReduction reduceGlobal(const GlobalProblem& problem, const std::vector<double>& r,
                             const SolveM& solveM) {
  if (problem.G)
    throw Error("reduceGlobal: problems with equality constraints G are not "
                             "supported");
  GlobalReduction out;
  // v = M^{-1}(H r + f)
  std::vector<double> rhs;
  problem.H.multiply(r, rhs);
  for (std::size_t k = 0; k < rhs.size(); ++k) rhs[k] += problem.f[k];
  solveM(rhs, out.v);
  problem.H.multiplyTranspose(out.v, out.u);
  for (std::size_t k = 0; k < out.u.size(); ++k) out.u[k] += problem.w[k];
  // q = H' M^{-1} f + w: the velocity at r = 0.
  std::vector<double> vFree;
  solveM(problem.f, vFree);
  problem.H.multiplyTranspose(vFree, out.q);
  for (std::size_t k = 0; k < out.q.size(); ++k) out.q[k] += problem.w[k];
  return out;
}

NaturalMapError naturalMapError(const GlobalProblem& problem, const std::vector<double>& r,
                                const SolveM& solveM) {
  if (problem.spacedim != 3)
    throw Error("naturalMapError: only spacedim = 3 is supported");
  const GlobalReduction red = reduceGlobal(problem, r, solveM);
  return naturalMapError(r, red.u, problem.mu, red.q);
}

}  // namespace FCLIB
}  // namespace Tribos
