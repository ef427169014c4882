#include "Tribos_DirichletAtContact.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Fem {

namespace {

// Per axis d: whether Dirichlet conditions fix it at every node of the row
// (terms: node and coefficient; empty: the node alone, coefficient 1), and
// then the prescribed relative displacement w_d = sum c_k ubar_k (ubar_s -
// sum N_i ubar_i for a slave node and its masters) and the size of the
// values (for round-off).
struct PrescribedRelativeMotion {
  std::array<bool, 3> fixed{};
  std::array<double, 3> w{}, scale{};
  std::string where;  // "contact node N at (x, y, z)"
};

PrescribedRelativeMotion prescribedRelativeMotion(const std::map<long long, double>& dirichlet, int node,
                                                  const std::array<double, 3>& x,
                                                  const std::vector<std::pair<int, double>>& terms) {
  PrescribedRelativeMotion m;
  const std::vector<std::pair<int, double>> row = terms.empty() ? std::vector<std::pair<int, double>>{{node, 1.0}} : terms;
  for (int d = 0; d < 3; ++d) {
    m.fixed[d] = true;
    for (const auto& [n, coefficient] : row) {
      const auto it = dirichlet.find(3LL * n + d);
      m.fixed[d] = m.fixed[d] && it != dirichlet.end();
      if (!m.fixed[d]) break;
      m.w[d] += coefficient * it->second, m.scale[d] = std::max(m.scale[d], std::abs(it->second));
    }
    if (!m.fixed[d]) m.w[d] = 0;
  }
  std::ostringstream os;
  os << "contact node " << node;
  if (std::isfinite(x[0])) os << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ")";  // NaN: not known
  m.where = os.str();
  return m;
}

bool tangentialAxis(const std::array<double, 3>& normal, int d) {
  return std::abs(normal[d]) <= 1e-12 * norm(normal);
}

}  // namespace

void requireNoPrescribedPenetration(const std::map<long long, double>& dirichlet, int node,
                                    const std::array<double, 3>& x, const std::array<double, 3>& normal, double gap,
                                    const std::vector<std::pair<int, double>>& terms) {
  const auto m = prescribedRelativeMotion(dirichlet, node, x, terms);
  const double nn = norm(normal);
  double wn = 0, scale = std::abs(gap);
  for (int d = 0; d < 3; ++d) {
    if (tangentialAxis(normal, d)) continue;
    if (!m.fixed[d]) return;  // the normal motion is free: the contact rows decide
    wn += normal[d] / nn * m.w[d];
    scale = std::max(scale, m.scale[d]);
  }
  TRIBOS_REQUIRE(wn <= gap + 1e-10 * scale,
                 m.where << ": its Dirichlet values move it " << wn - gap << " through the surface it contacts");
}

void requireNoPrescribedSlip(const std::map<long long, double>& dirichlet, int node, const std::array<double, 3>& x,
                             const std::array<double, 3>& normal, const std::vector<std::pair<int, double>>& terms) {
  const auto m = prescribedRelativeMotion(dirichlet, node, x, terms);
  for (int d = 0; d < 3; ++d)
    TRIBOS_REQUIRE(!tangentialAxis(normal, d) || !m.fixed[d] || std::abs(m.w[d]) <= 1e-10 * m.scale[d],
                   m.where << ": its Dirichlet values make it slide " << m.w[d] << " along " << "xyz"[d]
                           << " against the surface it contacts, with friction; friction against a prescribed "
                              "sliding is not modelled: prescribe the motion away from the contact surface, the "
                              "same value on both sides, or no friction");
}

}  // namespace Fem
}  // namespace Tribos
