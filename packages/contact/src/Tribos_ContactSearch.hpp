// Tribos_ContactSearch.hpp: the contact constraints of a mesh, node by node
// (Feti::ContactConstraint, the form the rows of B take them in).
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
//
// A pair uses mortar by default (ContactDiscretization::Mortar,
// Tribos_Mortar.hpp): the same one row per slave node, with the weights
// M_sm / D_s of dual mortar, the master normal averaged over the node,
// the gap n_s . (sum_m (M_sm / D_s) x_m - x_s) (the row applied to the
// reference positions) and the area D_s. It passes the contact patch test
// on any two meshes. Slave nodes whose mortar segments cover less than half
// of their area (edges of the slave surface beyond the master) keep a
// node-to-segment row. Against a rigid plane both are the same rows: the
// gap is linear in x, so its weighted gap int psi_s g dA is D_s g(x_s).
#pragma once

#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "Tribos_ContactConstraint.hpp"
#include "Tribos_ContactDiscretization.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Types.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

// How a pair's rows are formed, ContactDiscretization: "Node To Segment"
// (closest-point projection of each slave node) or "Mortar" (dual mortar
// segments); discretizationName(), discretizationValidator()
// (Tribos_ContactDiscretization.hpp).

struct ContactPair {
  std::string name;            // for messages (the input's sublist name)
  std::string slave;           // face of the mesh
  std::string master;          // face of the mesh; empty: the rigid plane below
  bool glued = false;          // bonded: the relative displacement vanishes
  ContactDiscretization discretization = ContactDiscretization::Mortar;
  std::array<double, 3> planePoint{0, 0, 0};
  std::array<double, 3> planeNormal{0, 0, 1};  // unit, out of the obstacle towards the body
  // Slave nodes farther than this from their projection get no constraint.
  double searchDistance = std::numeric_limits<double>::infinity();
  // searchDistance is automaticSearchDistance()'s: the nodes it leaves out
  // are listed (ContactSearch::leftOut) for the result check, not warned of.
  bool automaticSearch = false;
};

// The search distance of a pair whose input leaves it to the geometry and
// the loads (Search Distance = 0): kAutoSearchShare of the diagonal of the
// slave surface's bounding box, and at least kAutoSearchDisplacements times
// the largest prescribed displacement of the history. In small-strain
// elasticity a surface moves by a small part of its size, so a slave node
// farther than that from the master cannot reach it; the result check
// proves it for every left-out node after every step (leftOutMargin), and a
// step where it cannot is not converged. Nodes far from the contact (the
// rim of a Hertz sphere, 10 contact radii away) then take no row, which
// makes F smaller and cheaper to apply.
constexpr double kAutoSearchShare = 0.05, kAutoSearchDisplacements = 4.0;
double automaticSearchDistance(const Mesh::Mesh& mesh, const std::string& slave, double largestPrescribedDisplacement);

// A slave node of a pair with an automatic search distance that the search
// left out: its distance to the master surface (to its closest point on a
// facet) or to the rigid plane in the reference configuration.
struct LeftOutNode {
  int node = -1, pair = -1;
  double gap = 0;
};

// What the search found besides the constraints: the warnings (`notes`),
// the left-out nodes of pairs with an automatic search distance, and per
// pair its distance and counts (slave nodes, rows, left out, mortar nodes
// that took a node-to-segment row because the master covers less than half
// of their area).
struct PairSearch {
  std::string name;
  std::string master;                 // the master surface, empty: the rigid plane of planeNormal
  Vec3 planeNormal{0, 0, 1};
  double searchDistance = 0;
  bool automatic = false;
  long long slaveNodes = 0, rows = 0, leftOut = 0, nodeToSegment = 0;
};
struct ContactSearch {
  std::vector<std::string> notes;
  std::vector<LeftOutNode> leftOut;
  std::vector<PairSearch> pairs;
};

// A lower bound of the gap of a left-out node after a step: gap - |u_s| -
// masterMotion (the largest displacement of the master surface's nodes),
// or for a rigid plane with normal m the gap itself, gap + u_s . m (both as
// the linearized gaps of the rows would measure it). Positive: the node
// stayed out of contact.
double leftOutMargin(const LeftOutNode& node, const Vec3& u, bool plane, const Vec3& planeNormal, double masterMotion);

// The constraints of all pairs, ordered by pair, then slave node. A slave
// node in two pairs, a pair whose slave and master surface coincide, a
// plane normal that is not a unit vector and faces the mesh lacks are
// refused (Tribos::Error naming the pair). Slave nodes that no master facet
// within the search distance takes are left out, one line per pair added to
// `notes` (counts and the first node ids); so are mortar pairs' slave nodes
// that fall back to node-to-segment.
std::vector<Feti::ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                        std::vector<std::string>* notes = nullptr);
// The same, with the left-out nodes and the counts of each pair (`found`).
std::vector<Feti::ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                        ContactSearch& found);

// Refuses (Tribos::Error naming the body, the free motions and the pairs on
// it) a body that can move rigidly while every other body stays: a motion
// that neither its Dirichlet dofs (dirichlet: constrained dofs 3 n + c)
// nor a contact row between it and another body or a rigid plane touches
// (the rows' normals; their tangents too where holdsTangentially[pair]:
// friction or a glued pair). Bodies that share nodes count as one. Where a
// pair's master surface does not face its slave surface (its normal more
// than 60 degrees from the slave's at every slave node), the message says
// that this is why the pair holds nothing along the slave's normal.
void requireEveryBodyHeldAlone(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                               const std::vector<ContactPair>& pairs, const std::vector<char>& holdsTangentially,
                               const std::vector<Feti::ContactConstraint>& constraints);

// The rigid plane a distance gap beyond a planar face, parallel to it
// (Contact/Face and Gap of a one-face run): every node of the face gets the
// gap `gap` along the face's outward normal.
ContactPair planeBeyondFace(const Mesh::Mesh& mesh, const std::string& face, double gap);

// Contact of one face with a rigid plane parallel to it: u . n <= gap at
// every node of the face (n the outward normal of the face), two tangents
// per node. The one-face case of ContactPair (planeBeyondFace).
struct ContactSpec {
  bool enabled = false;
  std::string face = "zmin";
  double gap = 0.0;
};

// The constraints of ContactSpec on the ranks' parts of a decomposed mesh
// (for Feti::FetiProblem): the plane of the lowest rank whose part has
// facets on the face (each part checks its facets are planar, and the
// parts' planes must agree), then each rank's constraints at the face's
// nodes in its part (mesh node numbers), their areas summed over the ranks
// holding a node. None when the contact is not enabled. Collective.
std::vector<Feti::ContactConstraint> faceContactConstraints(const Mesh::Discretization& disc, const ContactSpec& contact,
                                                            const RCP<const Comm>& comm);

// Outward unit normal of a face of the box ("xmin", ..., "zmax").
std::array<double, 3> faceNormal(const std::string& face);
// Outward unit normal of a named face of a mesh, from its facets' geometry
// (a box's faces or a Gmsh file's physical surfaces alike). Throws naming
// the face when it is not planar ("contact surface 'bottom' is not planar"):
// the contact partner is a rigid plane, which a curved surface cannot meet.
std::array<double, 3> faceNormal(const Mesh::Mesh& mesh, const std::string& face);

}  // namespace Contact
}  // namespace Tribos
