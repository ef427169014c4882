// Tribos_Mortar.hpp: the mortar coupling of a slave and a master surface,
// with dual Lagrange multipliers (segment-to-segment, small sliding).
//
// The contact traction on the slave surface is lambda = sum_s lambda_s psi_s
// with dual shape functions psi_s, biorthogonal to the slave's shape
// functions on every slave facet e:
//
//   int_e psi_j N_k dA = delta_jk int_e N_k dA,   psi_j = sum_k A_jk N_k,
//   A = D_e M_e^-1,  M_e = (int_e N_j N_k dA),  D_e = diag(int_e N_j dA).
//
// The non-penetration of the surfaces, tested with each psi_s, reads
//
//   D_s u_s . n_s - sum_m M_sm u_m . n_s <= g~_s,
//   D_s = int psi_s N_s dA (= int N_s dA),  M_sm = int psi_s N_m dA,
//
// with m over the master nodes and the integrals over the part of the
// slave surface that the master covers. D is diagonal: the biorthogonality
// removes every other slave node, so the row of slave node s divided by
// D_s has the node-to-segment form u_s - sum_m (M_sm / D_s) u_m, one row
// per slave node, with its multiplier the nodal force D_s lambda_s. A
// uniform pressure gives the slave nodes D_s p and the master nodes
// sum_s M_sm p = int N_m p (the psi_s sum to one): their consistent nodal
// forces, which is why the contact patch test passes on any two meshes.
//
// The integrals are taken on mortar segments: for each slave facet e, the
// master facets that face it are projected onto e along e's normal at its
// centre, clipped against e's reference polygon, and the pieces integrated
// in e's reference coordinates (Tribos_MortarElement.hpp). Geometry is the
// reference configuration.
//
// Second-order slave facets (6-node triangles, 8-node quadrilaterals): a
// corner's quadratic function has int N_c dA = 0 (flat 6-node triangle) or
// -A/12 (8-node quadrilateral), so its dual function would carry no force,
// or a tensile one, under a uniform pressure. As Popp, Wohlmuth, Gee and
// Wall (2012) do, the slave side is written in the transformed basis
//
//   N~_c = N_c + alpha sum_{m on an edge of c} N_m,   N~_m = (1 - 2 alpha) N_m,
//
// alpha = kMidEdgeShare = 1/5, which keeps the partition of unity and makes
// every int N~ dA positive (flat facets: 2A/15 at a triangle's corners and
// A/5 at its mid-edge nodes; A/20 and A/5 for the quadrilateral). The dual
// basis, D and the normals are built on N~ (first-order facets have
// N~ = N). The nodal values of the slave displacement in that basis are
// u~_c = u_c at a corner and u~_m = (u_m - alpha (u_a + u_b)) / (1 - 2 alpha)
// at the mid-edge node of the edge a-b, so a mid-edge node's row acts on
// three slave nodes (transformedNodes); a uniform pressure still gives every
// node lambda_s = p and the consistent nodal forces p int N_b dA.
//
// The normal n_s of a slave node is the master's inward normal averaged
// over the node's support, n_s ~ -int N~_s n^(2) dA: a flat master gives
// every slave node its exact normal, as node-to-segment does, however the
// slave surface is curved or cut. The slave's own averaged normal would
// tilt at the edges of a cut slave surface (a quarter model's symmetry
// planes see the facets of one side only), where the node's Dirichlet
// components then fix an oblique mix of normal and tangential motion.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_MortarElement.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

// The share of each mid-edge function moved to the corners of its edge in
// the transformed basis of second-order slave facets.
constexpr double kMidEdgeShare = 0.2;

// The transformed shape functions N~ of the facet at xi (numNodes() values).
void transformedShape(const SurfaceShape& shape, const Point2& xi, double* N);

// The slave side of the rows of a face's mid-edge nodes: for each, its
// value in the transformed basis as a combination of nodal displacements,
// u~_m = sum_b S_b u_b = (u_m - alpha (u_a + u_b)) / (1 - 2 alpha) (weights
// summing to 1). Empty for a first-order face; corners are not listed
// (u~_c = u_c).
std::map<int, std::vector<std::pair<int, double>>> transformedNodes(const Mesh::Mesh& mesh, const std::string& face);

// int N~_s dA of every node of the face (mesh numbering; 0 off the face):
// the areas D_s of its rows against a rigid plane.
std::vector<double> transformedAreas(const Mesh::Mesh& mesh, const std::string& face);

// The mortar integrals of one slave node.
struct MortarNode {
  int node = -1;
  double area = 0;          // int N~_s dA over the node's slave facets (N~ = N on first-order ones)
  std::map<int, double> M;  // master node m -> M_sm over the covered part
  Vec3 normal{0, 0, 0};     // unit, from the node into the master: -int N_s n^(2) dA normalized
  // int psi_s dA over the covered part: sum_m M_sm (the master's shape
  // functions sum to one); equal to D_s = area where the master covers all
  // of the node's facets.
  double covered() const;
};

// The dual basis of a slave facet: psi_j = sum_k A[j][k] N~_k, and
// D[j] = int_e N~_j dA (= int_e psi_j N~_j dA), the row sums of its mass
// matrix (of the transformed basis N~).
struct DualBasis {
  std::vector<std::vector<double>> A;
  std::vector<double> D;
};
DualBasis dualBasis(const SurfaceElement& e);

// The mortar integrals of every node of the slave surface (face names of
// `mesh`), in the order of mesh.faceNodes(slave). Master facets take part
// where they face the slave facet (opposite normals) and lie within `reach`
// of it along its normal.
std::vector<MortarNode> mortarCoupling(const Mesh::Mesh& mesh, const std::string& slave, const std::string& master,
                                       double reach = std::numeric_limits<double>::infinity());

}  // namespace Contact
}  // namespace Tribos
