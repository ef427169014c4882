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
//
// On a second-order slave surface the row of a mid-edge node s acts on its
// value in mortar's transformed basis (Tribos_Mortar.hpp), a combination
// u~_s = sum_b S_b u_b of s and the corners of its edge (weights summing to
// 1), in place of u_s: then (u~_s - sum_i N_i u_i) . n <= g_s.
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
  std::vector<std::pair<int, double>> slave;   // u~_s = sum S_b u_b; empty: u_s (weight 1)

  // Every node of the row with its coefficient: the slave side (+1 at node,
  // or +S_b), then the master nodes (-N_i). The rows of B, the relative
  // displacement and the forces the multiplier puts on nodes all read it.
  std::vector<std::pair<int, double>> terms() const;
};

// The terms of a contact row (ContactConstraint::terms()): the slave side,
// +1 at the node or +S_b where `slave` lists them, then -N_i per master.
std::vector<std::pair<int, double>> rowTerms(int node, const std::vector<std::pair<int, double>>& slave,
                                             const std::vector<std::pair<int, double>>& master);

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
