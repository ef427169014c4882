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

}  // namespace Contact
}  // namespace Tribos
