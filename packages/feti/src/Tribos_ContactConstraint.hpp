// Tribos_ContactConstraint.hpp: the constraint of one contact node, as the
// rows of B take it.
//
// A slave node s is pressed against a master surface of another body, or
// against a rigid plane, along its contact normal n:
//
//   (u_s - sum_i N_i u_i) . n <= g_s
//
// where i runs over the master nodes with weights N_i (the shape functions
// of the master facet at the node's projection; none for a rigid plane) and
// g_s is the initial normal gap. The friction directions t1, t2 complete n
// to an orthonormal frame (tangents()), and the slip is the relative
// tangential displacement. A glued (bonded) constraint makes the three
// components of the relative displacement equality rows instead.
// Contact::contactConstraints finds these constraints on a mesh
// (packages/contact/src/Tribos_ContactSearch.hpp); an application may give
// its own (FetiConstraints::contact).
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

// The constraint of one slave node (global mesh numbers).
struct ContactConstraint {
  int node = -1;                             // the slave node
  int pair = -1;                             // index in the pair list
  bool glued = false;
  std::vector<std::pair<int, double>> master;  // master nodes and weights N_i (sum 1); empty: rigid plane
  std::array<double, 3> normal{0, 0, 0}, t1{0, 0, 0}, t2{0, 0, 0};
  double gap = 0.0;                          // (u_s - sum N_i u_i) . n <= gap
  double area = 0.0;                         // the slave node's share of the slave surface
};

// Two unit tangents completing n to a right-handed orthonormal frame (n, t1, t2).
void tangents(const std::array<double, 3>& n, std::array<double, 3>& t1, std::array<double, 3>& t2);

// Every rank's constraints, in rank order, on every rank (for writers of a
// global problem such as the FCLIB export). Collective.
std::vector<ContactConstraint> gatherContactConstraints(const std::vector<ContactConstraint>& local, const Comm& comm);

// The constraints that `root` found on the whole mesh, each sent to the rank
// that owns its slave node (the rank of its contact rows): no rank holds
// the list of another's. Collective.
std::vector<ContactConstraint> scatterContactConstraints(const std::vector<ContactConstraint>& onRoot,
                                                         const Mesh::Discretization& disc, const Comm& comm,
                                                         int root = 0);

// The relative displacement (u_s - sum N_i u_i) of a constraint, from a
// nodal displacement that holds its nodes.
std::array<double, 3> relativeDisplacement(const ContactConstraint& c, const Fem::NodalVector& u);

}  // namespace Feti
}  // namespace Tribos
