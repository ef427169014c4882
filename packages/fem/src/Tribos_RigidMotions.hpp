// Tribos_RigidMotions.hpp: which rigid motions of a body its Dirichlet
// conditions leave free. Solvers that eliminate the Dirichlet dofs and factor
// (or iterate on) K restricted to the remaining ones (the monolithic solve,
// the semismooth* method) need that matrix regular, which fails exactly when
// a rigid motion (a combination of the 3 translations and 3 rotations)
// vanishes at every Dirichlet dof: a floating body, or one held only by its
// contact (a semicoercive problem).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace Tribos {
namespace Fem {

// Names of the free rigid motions: "translation x", "rotation about z", or
// for a free motion that is not along a coordinate axis
// "translation along (0.707, 0.707, 0)". Rotations are about axes through
// some point; only the axis direction is named. Empty when every rigid
// motion is held. coords: node coordinates; dirichlet: global dof
// (3 node + c) -> prescribed value (only the dofs matter).
std::vector<std::string> freeRigidMotions(const std::vector<std::array<double, 3>>& coords,
                                          const std::map<long long, double>& dirichlet);

// The same for general held directions: the displacement of node `node`
// (an index into coords) along `direction` is held, e.g. by a contact's
// normal. Directions of zero length hold nothing.
struct HeldDirection {
  int node = -1;
  std::array<double, 3> direction{0, 0, 0};
};
std::vector<std::string> freeRigidMotions(const std::vector<std::array<double, 3>>& coords,
                                          const std::vector<HeldDirection>& held);

// Throws Tribos::CollectiveError naming the free rigid motions, if any:
// "<method>: the Dirichlet conditions leave the rigid motion(s) ... free; <advice>".
void requireRigidMotionsHeld(const std::vector<std::array<double, 3>>& coords,
                             const std::map<long long, double>& dirichlet, const std::string& method,
                             const std::string& advice);

}  // namespace Fem
}  // namespace Tribos
