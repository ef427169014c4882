// Tribos_DirichletAtContact.hpp: Dirichlet conditions at a contact node and
// its partners checked against the contact conditions there, before any
// work (the FETI rows and the semismooth* method take them as given).
#pragma once

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace Tribos {
namespace Fem {

// The Dirichlet values at a contact node (at x) and its partners must leave
// its contact conditions meaningful; both throw Tribos::Error naming the
// node and its position otherwise.
//  - A normal fixed at the slave node and every master node takes the node
//    out of the contact set: right only if the values keep it from passing
//    through its partner (requireNoPrescribedPenetration).
//  - A tangential axis fixed there leaves the friction law (above): right
//    only if the values prescribe no slip along it (a symmetry plane) or the
//    contact has no friction, since friction would oppose a prescribed slip
//    with a force that the Dirichlet reaction hides (requireNoPrescribedSlip,
//    for contacts with friction).
// `terms` lists every node of the contact row with its coefficient (+1 at
// the slave node, -N_i at its masters; Feti::ContactConstraint::terms());
// empty: the node alone against a rigid obstacle.
void requireNoPrescribedPenetration(const std::map<long long, double>& dirichlet, int node,
                                    const std::array<double, 3>& x, const std::array<double, 3>& normal, double gap,
                                    const std::vector<std::pair<int, double>>& terms);
void requireNoPrescribedSlip(const std::map<long long, double>& dirichlet, int node, const std::array<double, 3>& x,
                             const std::array<double, 3>& normal, const std::vector<std::pair<int, double>>& terms);

}  // namespace Fem
}  // namespace Tribos
