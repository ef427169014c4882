#include "Tribos_ResultKKT.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Tribos_ContactKKT.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

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

Fem::NodalVector contactForces(const RCP<const Fem::NodalLayout>& layout, const std::vector<ContactNodeForce>& contact) {
  Fem::NodalVector phi(layout);
  for (const auto& c : contact)
    for (int d = 0; d < 3; ++d) {
      const double force = -c.normalForce * c.normal[d] + c.tangentialForce[d];
      for (const auto& [node, weight] : c.terms()) phi.at(node)[d] += weight * force;
    }
  layout->sumOverHolders(phi.values());
  return phi;
}

ResultKKT resultKKT(const Fem::NodalVector& u, const Fem::NodalVector& Ku, const Fem::NodalVector& f,
                    const std::map<long long, double>& dirichlet, FrictionLaw law,
                    const std::vector<ContactNodeForce>& contact, std::vector<int>* states) {
  TRIBOS_REQUIRE(!u.empty() && Ku.layoutPtr().get() == u.layoutPtr().get() && f.layoutPtr().get() == u.layoutPtr().get(),
                 "resultKKT: u, Ku and f must be nodal vectors of one layout");
  const Fem::NodalLayout& layout = u.layout();
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
  ContactKKT kkt(P, U);
  double bondedGap = 0, largestNormal = 0;
  for (const auto& c : contact) largestNormal = std::max(largestNormal, c.normalForce);
  const double activeForce = 1e-8 * maxOver(largestNormal, comm);
  if (states) states->assign(contact.size(), 1);
  for (size_t k = 0; k < contact.size(); ++k) {
    const ContactNodeForce& c = contact[k];
    // w: the relative displacement of the slave node and its partner.
    Vec3 w{0, 0, 0};
    for (const auto& [node, weight] : c.terms())
      for (int d = 0; d < 3; ++d) w[d] += weight * u.at(node)[d];
    const double wn = dot(c.normal, w);
    if (c.bonded) {
      bondedGap = std::max({bondedGap, std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
      continue;
    }
    double g = 0;
    if (law == FrictionLaw::Tresca) g = c.slipBound;
    if (law == FrictionLaw::Coulomb) g = c.frictionCoefficient * std::max(c.normalForce, 0.0);
    // Slip and friction force in the tangent plane, without the components
    // that Dirichlet conditions fix at the slave node (which carry no
    // friction row: Feti::meshConstraintRows). The slip is the increment since
    // the previous load step.
    Vec3 dw;
    for (int d = 0; d < 3; ++d) dw[d] = w[d] - c.previousRelative[d];
    const double dwn = dot(c.normal, dw);
    double s[3], phiT[3];
    for (int d = 0; d < 3; ++d) {
      const bool fixed = dirichlet.count(3LL * c.node + d) > 0;
      s[d] = fixed ? 0.0 : dw[d] - dwn * c.normal[d];
      phiT[d] = fixed ? 0.0 : c.tangentialForce[d];
    }
    kkt.add(c.normalForce, c.gap - wn /* d - w.n */, phiT, s, 3, g);
    if (states) (*states)[k] = c.normalForce <= activeForce ? 0 : kkt.slips(phiT, s, 3, g) ? 2 : 1;
  }
  res.nonpenetration = maxOver(std::max(kkt.nonpenetration(), bondedGap / U), comm);
  res.complementarity = maxOver(kkt.complementarity(), comm);
  res.frictionLaw = maxOver(kkt.frictionLaw(), comm);
  return res;
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

}  // namespace Contact
}  // namespace Tribos
