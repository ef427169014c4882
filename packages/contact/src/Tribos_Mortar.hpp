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
// The normal n_s of a slave node is the master's inward normal averaged
// over the node's support, n_s ~ -int N_s n^(2) dA: a flat master gives
// every slave node its exact normal, as node-to-segment does, however the
// slave surface is curved or cut. The slave's own averaged normal would
// tilt at the edges of a cut slave surface (a quarter model's symmetry
// planes see the facets of one side only), where the node's Dirichlet
// components then fix an oblique mix of normal and tangential motion.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_MortarElement.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

// The mortar integrals of one slave node.
struct MortarNode {
  int node = -1;
  double area = 0;          // int N_s dA over the node's slave facets
  std::map<int, double> M;  // master node m -> M_sm over the covered part
  Vec3 normal{0, 0, 0};     // unit, from the node into the master: -int N_s n^(2) dA normalized
  // int psi_s dA over the covered part: sum_m M_sm (the master's shape
  // functions sum to one); equal to D_s = area where the master covers all
  // of the node's facets.
  double covered() const;
};

// The dual basis of a slave facet: psi_j = sum_k A[j][k] N_k, and
// D[j] = int_e N_j dA (= int_e psi_j N_j dA), the row sums of its mass matrix.
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
