#include "Tribos_SolveResult.hpp"

#include <Teuchos_CommHelpers.hpp>

namespace Tribos {
namespace Contact {

std::vector<ContactNodeForce> ContactNodeResults::forces() const {
  std::vector<ContactNodeForce> out(nodes.size());
  for (size_t k = 0; k < nodes.size(); ++k) {
    out[k].node = nodes[k];
    out[k].normalForce = normalForce[k];
    for (int d = 0; d < 3; ++d) out[k].tangentialForce[d] = tangentialForce[3 * k + d];
    out[k].slipBound = slipBound[k];
    out[k].frictionCoefficient = frictionCoefficient[k];
    out[k].normal = constraint[k].normal;
    out[k].gap = constraint[k].gap;
    out[k].master = constraint[k].master;
    out[k].slave = constraint[k].slave;
    if (!previousRelative.empty())
      for (int d = 0; d < 3; ++d) out[k].previousRelative[d] = previousRelative[3 * k + d];
  }
  out.insert(out.end(), bonded.begin(), bonded.end());
  return out;
}

double ContactNodeResults::normalTraction(size_t k) const {
  const double area = constraint[k].area;
  return area > 0 ? normalForce[k] / area : 0.0;
}

std::array<double, 3> ContactNodeResults::tangentialTraction(size_t k) const {
  const double area = constraint[k].area;
  std::array<double, 3> t{0, 0, 0};
  if (area > 0)
    for (int d = 0; d < 3; ++d) t[d] = tangentialForce[3 * k + d] / area;
  return t;
}

std::array<double, 3> ContactNodeResults::slipIncrement(size_t k) const {
  std::array<double, 3> s{slip[3 * k], slip[3 * k + 1], slip[3 * k + 2]};
  if (previousRelative.empty()) return s;
  const auto& n = constraint[k].normal;
  const double* w = &previousRelative[3 * k];
  const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
  for (int d = 0; d < 3; ++d) s[d] -= w[d] - wn * n[d];
  return s;
}

double ContactNodeResults::frictionDissipation(size_t k) const {
  const auto s = slipIncrement(k);
  double work = 0;
  for (int d = 0; d < 3; ++d) work += tangentialForce[3 * k + d] * s[d];
  return -work;
}

Fem::NodalVector supportReactions(const Fem::NodalVector& Ku, const Fem::NodalVector& f,
                                  const ContactNodeResults& contact, const std::map<long long, double>& dirichlet) {
  const auto phi = contactForces(Ku.layoutPtr(), contact.forces());
  Fem::NodalVector r(Ku.layoutPtr());
  const auto& nodes = Ku.layout().nodes();
  for (size_t i = 0; i < nodes.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (dirichlet.count(3LL * nodes[i] + c)) {
        const size_t k = 3 * i + c;
        r.values()[k] = Ku.values()[k] - f.values()[k] - phi.values()[k];
      }
  return r;
}

ContactCounts countContacts(const ContactNodeResults& nodes, const Comm& comm) {
  long long local[4] = {static_cast<long long>(nodes.nodes.size()), 0, 0, 0}, global[4];
  for (int st : nodes.status) local[1] += st > 0, local[2] += st == 1, local[3] += st == 2;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 4, local, global);
  return {global[0], global[1], global[2], global[3]};
}

std::vector<PairForce> pairForces(const ContactNodeResults& nodes, int numPairs, const Comm& comm) {
  std::vector<double> local(4 * static_cast<size_t>(numPairs), 0.0), global(local.size(), 0.0);
  for (size_t k = 0; k < nodes.nodes.size(); ++k) {
    const int pair = nodes.constraint[k].pair;
    if (pair < 0 || pair >= numPairs) continue;
    local[4 * pair] += nodes.normalForce[k];
    for (int d = 0; d < 3; ++d) local[4 * pair + 1 + d] += nodes.tangentialForce[3 * k + d];
  }
  if (numPairs > 0) Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 4 * numPairs, local.data(), global.data());
  std::vector<PairForce> out(numPairs);
  for (int p = 0; p < numPairs; ++p) out[p] = {global[4 * p], {global[4 * p + 1], global[4 * p + 2], global[4 * p + 3]}};
  return out;
}

std::vector<PairMotion> pairMotions(const ContactNodeResults& nodes, int numPairs, const Comm& comm) {
  // Per pair: area-weighted slip (3), area, dissipation.
  std::vector<double> local(5 * static_cast<size_t>(numPairs), 0.0), global(local.size(), 0.0);
  for (size_t k = 0; k < nodes.nodes.size(); ++k) {
    const int pair = nodes.constraint[k].pair;
    if (pair < 0 || pair >= numPairs) continue;
    const double area = nodes.constraint[k].area;
    if (area > 0) {
      for (int d = 0; d < 3; ++d) local[5 * pair + d] += area * nodes.slip[3 * k + d];
      local[5 * pair + 3] += area;
    }
    local[5 * pair + 4] += nodes.frictionDissipation(k);
  }
  if (numPairs > 0) Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 5 * numPairs, local.data(), global.data());
  std::vector<PairMotion> out(numPairs);
  for (int p = 0; p < numPairs; ++p) {
    const double* g = &global[5 * p];
    out[p].area = g[3];
    for (int d = 0; d < 3; ++d) out[p].relativeTangentialDisplacement[d] = g[3] > 0 ? g[d] / g[3] : 0.0;
    out[p].dissipation = g[4];
  }
  return out;
}

}  // namespace Contact
}  // namespace Tribos
