// Tribos_ContactSearch.hpp: the contact constraints of a mesh, node by node.
//
// A contact pair presses the nodes of a slave surface against a master
// surface of another body, or against a rigid plane. Each slave node s gets
// one constraint on the relative displacement along its contact normal n:
//
//   (u_s - sum_i N_i u_i) . n <= g_s        (node-to-segment, small sliding)
//
// where the sum runs over the nodes i of the master facet that the closest-
// point projection of x_s lands on, N_i are the facet's shape functions at
// that point, n = -(outward normal of the master facet there) and
// g_s = (x_p - x_s) . n the initial normal gap. Geometry is fixed at the
// reference configuration, as in the seeds' small-deformation setting.
// Node-matching interfaces are the special case where x_p is a master node
// (one weight 1): the seed's mapping chi, with the normal as the critical
// direction. A rigid plane through p with normal m (pointing out of the
// obstacle, towards the body) has no master nodes: n = -m, g_s = (x_s - p).m.
// The friction directions t1, t2 complete n to an orthonormal frame
// (Feti::tangents), and the slip is the relative tangential displacement.
// A glued (bonded) pair makes the three components of the relative
// displacement equality rows instead.
//
// Known limits of node-to-segment (docs/contact.md): it passes the contact
// patch test exactly only for node-matching meshes (a non-matching one
// transmits a uniform pressure up to an error that falls with h); slave
// nodes whose projection falls outside every master facet get no constraint
// (reported); the slave side should be the finer one.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

struct ContactPair {
  std::string name;            // for messages (the input's sublist name)
  std::string slave;           // face of the mesh
  std::string master;          // face of the mesh; empty: the rigid plane below
  bool glued = false;          // bonded: the relative displacement vanishes
  std::array<double, 3> planePoint{0, 0, 0};
  std::array<double, 3> planeNormal{0, 0, 1};  // unit, out of the obstacle towards the body
  // Slave nodes farther than this from their projection get no constraint.
  double searchDistance = std::numeric_limits<double>::infinity();
};

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

// The constraints of all pairs, ordered by pair, then slave node. A slave
// node in two pairs, a pair whose slave and master surface coincide, a
// plane normal that is not a unit vector and faces the mesh lacks are
// refused (Tribos::Error naming the pair). Slave nodes that no master facet
// within the search distance takes are left out, one line per pair added to
// `notes` (counts and the first node ids).
std::vector<ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                  std::vector<std::string>* notes = nullptr);

// The rigid plane a distance gap beyond a planar face, parallel to it
// (Contact/Face and Gap of a one-face run): every node of the face gets the
// gap `gap` along the face's outward normal.
ContactPair planeBeyondFace(const Mesh::Mesh& mesh, const std::string& face, double gap);

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
