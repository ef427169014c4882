#include "Tribos_ResultKKT.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Tribos_ContactKKT.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Fem {

FrictionLaw::Kind FrictionLaw::parse(const std::string& name) {
  if (name == "Frictionless") return Frictionless;
  if (name == "Tresca") return Tresca;
  if (name == "Coulomb") return Coulomb;
  throw Error("unknown friction law \"" + name + "\"; valid: Frictionless, Tresca, Coulomb");
}

const char* FrictionLaw::name(Kind k) {
  return k == Frictionless ? "Frictionless" : (k == Tresca ? "Tresca" : "Coulomb");
}

double ResultKKT::worst(std::string* which) const {
  const std::pair<const char*, double> all[] = {{"equilibrium", equilibrium},
                                                {"dirichlet", dirichlet},
                                                {"nonpenetration", nonpenetration},
                                                {"complementarity", complementarity},
                                                {"friction_law", frictionLaw}};
  auto best = all[0];
  for (const auto& p : all)
    if (!(p.second <= best.second)) best = p;  // NaN counts as the worst
  if (which) *which = best.first;
  return best.second;
}

NodalVector contactForces(const RCP<const NodalLayout>& layout, const std::vector<ContactNodeForce>& contact) {
  NodalVector phi(layout);
  for (const auto& c : contact)
    for (int d = 0; d < 3; ++d) {
      const double force = -c.normalForce * c.normal[d] + c.tangentialForce[d];
      phi.at(c.node)[d] += force;
      for (const auto& [node, weight] : c.master) phi.at(node)[d] -= weight * force;
    }
  layout->sumOverHolders(phi.values());
  return phi;
}

ResultKKT resultKKT(const NodalVector& u, const NodalVector& Ku, const NodalVector& f,
                    const std::map<long long, double>& dirichlet, const FrictionLaw& law,
                    const std::vector<ContactNodeForce>& contact) {
  TRIBOS_REQUIRE(!u.empty() && Ku.layoutPtr().get() == u.layoutPtr().get() && f.layoutPtr().get() == u.layoutPtr().get(),
                 "resultKKT: u, Ku and f must be nodal vectors of one layout");
  const NodalLayout& layout = u.layout();
  const Comm& comm = *layout.comm();
  const auto phi = contactForces(u.layoutPtr(), contact);
  ResultKKT res;
  res.displacementScale = u.normInf();
  res.forceScale = std::max({f.normInf(), Ku.normInf(), phi.normInf()});
  const double U = std::max(res.displacementScale, 1e-300);
  const double P = std::max(res.forceScale, 1e-300);

  // Equilibrium at the owned dofs without a Dirichlet condition, summed over
  // the ranks; the Dirichlet values at the owned nodes.
  double r2 = 0, dir = 0, ubarMax = 0;
  const auto& nodes = layout.nodes();
  for (int i = 0; i < layout.numOwned(); ++i)
    for (int c = 0; c < 3; ++c) {
      const size_t k = 3 * static_cast<size_t>(i) + c;
      const auto it = dirichlet.find(3LL * nodes[i] + c);
      if (it != dirichlet.end()) {
        dir = std::max(dir, std::abs(u.values()[k] - it->second));
        ubarMax = std::max(ubarMax, std::abs(it->second));
        continue;
      }
      const double r = Ku.values()[k] - f.values()[k] - phi.values()[k];
      r2 += r * r;
    }
  res.equilibrium = std::sqrt(sumOver(r2, comm)) / std::max({f.norm2(), Ku.norm2(), phi.norm2(), 1e-300});
  res.dirichlet = maxOver(dir, comm) / std::max(U, maxOver(ubarMax, comm));

  // Contact node by node (rank-local nodes, then the maximum over ranks).
  Friction::ContactKKT kkt(P, U);
  double bondedGap = 0;
  for (const auto& c : contact) {
    // w: the relative displacement of the slave node and its partner.
    Vec3 w;
    for (int d = 0; d < 3; ++d) w[d] = u.at(c.node)[d];
    for (const auto& [node, weight] : c.master)
      for (int d = 0; d < 3; ++d) w[d] -= weight * u.at(node)[d];
    const double wn = dot(c.normal, w);
    if (c.bonded) {
      bondedGap = std::max({bondedGap, std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
      continue;
    }
    double g = 0;
    if (law.kind == FrictionLaw::Tresca) g = c.slipBound;
    if (law.kind == FrictionLaw::Coulomb) g = c.frictionCoefficient * std::max(c.normalForce, 0.0);
    // Slip and friction force in the tangent plane, without the components
    // that Dirichlet conditions fix at the slave node and every master node.
    double s[3], phiT[3];
    for (int d = 0; d < 3; ++d) {
      bool fixed = dirichlet.count(3LL * c.node + d) > 0;
      for (const auto& m : c.master) fixed = fixed && dirichlet.count(3LL * m.first + d) > 0;
      s[d] = fixed ? 0.0 : w[d] - wn * c.normal[d];
      phiT[d] = fixed ? 0.0 : c.tangentialForce[d];
    }
    kkt.add(c.normalForce, c.gap - wn /* d - w.n */, phiT, s, 3, g);
  }
  res.nonpenetration = maxOver(std::max(kkt.nonpenetration(), bondedGap / U), comm);
  res.complementarity = maxOver(kkt.complementarity(), comm);
  res.frictionLaw = maxOver(kkt.frictionLaw(), comm);
  return res;
}

namespace {

// Per axis d: whether Dirichlet conditions fix it at the slave node and
// every master node, and then the prescribed relative displacement
// w_d = ubar_s - sum N_i ubar_i and the size of the values (for round-off).
struct PrescribedRelativeMotion {
  std::array<bool, 3> fixed{};
  std::array<double, 3> w{}, scale{};
  std::string where;  // "contact node N at (x, y, z)"
};

PrescribedRelativeMotion prescribedRelativeMotion(const std::map<long long, double>& dirichlet, int node,
                                                  const std::array<double, 3>& x,
                                                  const std::vector<std::pair<int, double>>& master) {
  PrescribedRelativeMotion m;
  for (int d = 0; d < 3; ++d) {
    auto value = [&](int n) {
      const auto it = dirichlet.find(3LL * n + d);
      return it == dirichlet.end() ? std::nan("") : it->second;
    };
    m.fixed[d] = !std::isnan(value(node));
    m.w[d] = m.fixed[d] ? value(node) : 0.0;
    m.scale[d] = std::abs(m.w[d]);
    for (const auto& [mn, weight] : master) {
      m.fixed[d] = m.fixed[d] && !std::isnan(value(mn));
      if (m.fixed[d]) m.w[d] -= weight * value(mn), m.scale[d] = std::max(m.scale[d], std::abs(value(mn)));
    }
  }
  std::ostringstream os;
  os << "contact node " << node << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ")";
  m.where = os.str();
  return m;
}

bool tangentialAxis(const std::array<double, 3>& normal, int d) {
  return std::abs(normal[d]) <= 1e-12 * norm(normal);
}

}  // namespace

void requireNoPrescribedPenetration(const std::map<long long, double>& dirichlet, int node,
                                    const std::array<double, 3>& x, const std::array<double, 3>& normal, double gap,
                                    const std::vector<std::pair<int, double>>& master) {
  const auto m = prescribedRelativeMotion(dirichlet, node, x, master);
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
                             const std::array<double, 3>& normal, const std::vector<std::pair<int, double>>& master) {
  const auto m = prescribedRelativeMotion(dirichlet, node, x, master);
  for (int d = 0; d < 3; ++d)
    TRIBOS_REQUIRE(!tangentialAxis(normal, d) || !m.fixed[d] || std::abs(m.w[d]) <= 1e-10 * m.scale[d],
                   m.where << ": its Dirichlet values make it slide " << m.w[d] << " along " << "xyz"[d]
                           << " against the surface it contacts, with friction; friction against a prescribed "
                              "sliding is not modelled: prescribe the motion away from the contact surface, the "
                              "same value on both sides, or no friction");
}

ResultVerdict resultVerdict(const ResultKKT& kkt, bool solverConverged, const std::string& solverReason,
                            double tolerance, double factor) {
  ResultVerdict v;
  v.limit = factor * tolerance;
  std::string worstName;
  const double worst = kkt.worst(&worstName);
  v.converged = solverConverged && worst <= v.limit;
  if (v.converged) {
    v.stopReason = solverReason.empty() ? "converged" : solverReason;
  } else if (!solverConverged) {
    v.stopReason = solverReason.empty() ? "the solver did not converge" : solverReason;
  } else {
    std::ostringstream os;
    os << "the " << worstName << " residual of the result, " << worst << ", exceeds " << v.limit
       << " (Result Check Factor " << factor << " times the requested tolerance " << tolerance << ")";
    v.stopReason = os.str();
  }
  return v;
}

}  // namespace Fem
}  // namespace Tribos
