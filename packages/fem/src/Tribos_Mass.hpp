// Tribos_Mass.hpp: the consistent mass matrix of Tribos' cells,
//   M[3a+i][3b+j] = delta_ij int rho N_a N_b dV,
// per element and assembled per subdomain in the CSR layout of the
// subdomain stiffness (Tribos_Assembly.hpp), the first building block of
// implicit dynamics (docs/dynamics.md). DOF layout: dof = 3 * node + component.
//
// Only the consistent mass is offered. The row-sum lumped mass of Tet10
// gives its corners a negative mass (-1/20 of the cell's each, the integral
// of a corner shape function, as its consistent volume loads), and Hex20's
// is negative at the corners too (-1/8 of a parallelepiped's each): a
// diagonal mass with negative entries is no mass. The consistent mass is
// symmetric positive definite for every cell type.
#pragma once

#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_LocalCsr.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_ShapeFunctions.hpp"

namespace Tribos {
namespace Fem {

// The density (mass per unit volume) of every body of a mesh
// (Mesh::bodyOf), as BodyMaterials gives its material: one for all bodies
// (implicitly from a double) or one per body. Every density must be positive
// and finite: the mass matrix must be positive definite.
class BodyDensities {
 public:
  BodyDensities(double all);  // NOLINT: every body has it
  explicit BodyDensities(std::vector<double> perBody);
  double ofBody(int body) const { return perBody_.size() == 1 ? perBody_[0] : perBody_.at(body); }
  double ofCell(const Mesh::Mesh& mesh, int cell) const { return ofBody(mesh.bodyOf(cell)); }
  int size() const { return static_cast<int>(perBody_.size()); }

 private:
  std::vector<double> perBody_;
};

// The consistent element mass (row-major, 3*npc x 3*npc) of a cell with the
// given nodes and density:
//   Tet4 in closed form, rho V (1 + delta_ab) / 20;
//   Tet10 with its 14-point rule of degree 5: exact on straight-sided cells
//     (N_a N_b has degree 4, det J is constant);
//   Hex8 with 3x3x3 and Hex20 with 4x4x4 Gauss (accurateQuadrature): exact
//     on every cell whose edges are straight, where the map is trilinear and
//     det J has degree 2 in each coordinate, so N_a N_b det J has degree 4
//     (Hex8) or 6 (Hex20) in each. The stiffness rules (2x2x2, 3x3x3) would
//     be exact only on parallelepipeds, and a wrong moment of inertia on a
//     distorted cell would show as a wrong rotational frequency.
// Throws Tribos::Error when the density is not positive and finite, or
// where elementStiffness refuses the cell (det J <= 0).
std::vector<double> elementMass(Mesh::CellType type, const std::vector<Point>& X, double density);

// The mass matrix of a subdomain: the same dofs, local node numbers and CSR
// pattern as assembleSubdomain's K (Tribos_Assembly.hpp), so that
// K + M / (beta dt^2) is a sum of the value arrays.
LocalCsr assembleSubdomainMass(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyDensities& rho);
// Subdomain s of this rank's part (as assembleSubdomain of a Discretization).
LocalCsr assembleSubdomainMass(const Mesh::Discretization& disc, int s, const BodyDensities& rho);

}  // namespace Fem
}  // namespace Tribos
