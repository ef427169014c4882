// Tribos_ContactConditions.hpp: contact as an application states it, a
// condition per contact node, from which Tribos builds the rows of B in its
// own frame: per node the Normal row (u . n <= gap) and the Tangent1,
// Tangent2 rows along (t1, t2) = Feti::tangents(n), with the node's
// ContactConstraint (frame, gap, area, pair) that the friction law and the
// result check read. The application never computes a tangent frame, and
// contact forces, slips and the KKT residuals come back in this frame.
//
// A node pressed on a rigid obstacle has no master nodes; a node against
// another body's facet names the facet's nodes with the weights N_i of its
// projection (node-to-segment: (u_s - sum N_i u_i) . n <= gap, the rows'
// copies the slave's with weight 1 and the masters' with -N_i).
#pragma once

#include <array>
#include <vector>

#include "Tribos_FetiProblem.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

struct ContactCondition {
  int node = -1;                         // global node number of the contact (slave) node
  int subdomain = -1, localNode = -1;    // the copy of the node the rows act on
  std::array<double, 3> normal{0, 0, 0};  // outward normal of the body at the node (normalized here)
  double gap = 0.0;                      // initial normal gap: u . n <= gap
  double area = 1.0;                     // the node's share of the contact surface (Tresca: g = traction x area)
  int pair = 0;                          // the contact pair: its friction is the solver's "Friction"/"Pair <pair>"
  struct Master {
    int node = -1;                       // global node number
    int subdomain = -1, localNode = -1;  // its copy the rows act on
    double N = 0.0;                      // its weight (shape function at the projection), the N sum to 1
  };
  std::vector<Master> master;            // empty: a rigid obstacle
};

// Appends the rows and constraints of `conditions` to `constraints`. Every
// rank gives the same list or only the conditions of its own subdomains'
// nodes, as for the rows of B (FetiProblem keeps each rank's own). Refuses
// (CollectiveError on every rank, naming the condition and its node) a
// normal that is zero or not finite, a gap, area or weight that is not
// finite, a negative area or pair, master weights that do not sum to 1, and
// a node given twice. The Dirichlet conditions already in
// constraints.dirichlet are read as a mesh's are (Feti::contactRows): a
// friction direction they fix at the slave node (a symmetry plane through
// it) and a direction they fix at the slave and every master node get no
// row; give them before the contact conditions. FetiProblem checks the
// copies. Collective.
void addContactConditions(FetiConstraints& constraints, const std::vector<ContactCondition>& conditions,
                          const Comm& comm);

}  // namespace Feti
}  // namespace Tribos
