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
    if (!previousRelative.empty())
      for (int d = 0; d < 3; ++d) out[k].previousRelative[d] = previousRelative[3 * k + d];
  }
  out.insert(out.end(), bonded.begin(), bonded.end());
  return out;
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

}  // namespace Contact
}  // namespace Tribos
