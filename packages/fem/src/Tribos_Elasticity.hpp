// Tribos_Elasticity.hpp: 3D isotropic linear elasticity on P1 tetrahedra and
// Q1 hexahedra (2x2x2 Gauss), and at the element level on the second-order
// Tet10 and Hex20 cells (Tribos_ShapeFunctions.hpp, docs/quadratic_elements.md):
// element stiffness, loads and stresses. DOF layout everywhere:
// dof = 3 * node + component.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_ShapeFunctions.hpp"

namespace Tribos {
namespace Fem {

struct Material {
  double E = 1.0;    // Young's modulus
  double nu = 0.3;   // Poisson's ratio
  double lameLambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  double lameMu() const { return E / (2 * (1 + nu)); }
  // Voigt stress-strain matrix D (6x6, row-major), strain order xx,yy,zz,yz,xz,xy
  // with engineering shear strains.
  std::array<double, 36> D() const;
};

// The material of every body of a mesh (Mesh::bodyOf): one for all bodies
// (implicitly from a Material) or one per body.
class BodyMaterials {
 public:
  BodyMaterials(const Material& all) : perBody_{all} {}  // NOLINT: every body has it
  explicit BodyMaterials(std::vector<Material> perBody) : perBody_(std::move(perBody)) {}
  const Material& ofBody(int body) const { return perBody_.size() == 1 ? perBody_[0] : perBody_.at(body); }
  const Material& ofCell(const Mesh::Mesh& mesh, int cell) const { return ofBody(mesh.bodyOf(cell)); }
  int size() const { return static_cast<int>(perBody_.size()); }

 private:
  std::vector<Material> perBody_;
};

// Element stiffness (row-major, 3*npc x 3*npc) of a cell with the given nodes:
// Tet4 exactly (constant strain), the others with cellQuadrature(type).
// Throws Tribos::Error when det J <= 0 at a quadrature point or, for Tet10
// and Hex20, at a node of the cell: the isoparametric map of a cell whose
// mid-edge node has moved along its edge by more than a quarter of the edge
// from the middle folds at a corner, while every quadrature point may still
// see det J > 0.
std::vector<double> elementStiffness(Mesh::CellType type, const std::vector<Point>& X, const Material& mat);

// Shape function gradients dN/dx (npc x 3, row-major) at reference point xi
// (ignored for Tet4); returns det J, and throws Tribos::Error naming the cell
// type and the point when det J <= 0 (an inverted or degenerate cell).
double shapeGradients(Mesh::CellType type, const std::vector<Point>& X, const Point& xi, std::vector<double>& dN);

// Refuses (Tribos::Error naming the node) a Tet10 or Hex20 cell whose map
// folds at one of its nodes: its quadrature points do not see a fold at a
// corner (a mid-edge node moved along its edge by more than a quarter of the
// edge from the middle). Nothing to check for Tet4 and Hex8.
void requirePositiveJacobianAtNodes(Mesh::CellType type, const std::vector<Point>& X);

// Shape function values at reference point xi (Tribos_ShapeFunctions.hpp:
// Tet4, Tet10 on the unit tetrahedron (0,0,0),(1,0,0),(0,1,0),(0,0,1); Hex8,
// Hex20 on [-1,1]^3).
std::vector<double> shapeFunctions(Mesh::CellType type, const Point& xi);

// Cauchy stress (Voigt) of a cell from its nodal displacements: Tet4 and Hex8
// at the cell centre; Tet10 and Hex20 the average over the cell's volume,
// int sigma dV / V, with cellQuadrature(type) (exact for the linear stress
// of a straight-sided Tet10 and of a parallelepiped Hex20): their stress
// varies within the cell, and a cell field holds one value, its mean.
std::array<double, 6> cellStress(Mesh::CellType type, const std::vector<Point>& X, const std::vector<double>& ue,
                                 const Material& mat);
double vonMises(const std::array<double, 6>& s);

// Consistent nodal forces of a constant traction t (per unit area) on a
// facet of 3, 4, 6 or 8 nodes (corners first, then mid-edge nodes:
// Tribos_ShapeFunctions.hpp): facetNodalAreas x t.
std::vector<double> facetTractionForces(const std::vector<Point>& X, const Point& t);
// Nodal weights of the facet area (integral of each shape function over the
// facet, facetQuadrature), used to turn a traction bound into nodal slip
// bounds. On a flat 6-node triangle whose edges are straight the corners
// weigh 0 and the mid-edge nodes 1/3 of the area; on a flat 8-node
// quadrilateral (a parallelogram) the corners -1/12 and the mid-edge nodes 1/3.
std::vector<double> facetNodalAreas(const std::vector<Point>& X);
// Consistent nodal forces of a constant volume force b on a cell (Tet4
// exactly, the others with cellQuadrature(type)); on a straight-sided Tet10
// the corners get -1/20 and the mid-edge nodes 1/5 of the total.
std::vector<double> cellVolumeForces(Mesh::CellType type, const std::vector<Point>& X, const Point& b);

// The rigid motions at a point r (relative to a centre), written once for
// every kernel basis in Tribos (FETI's R, MueLu's null spaces, the check of
// the motions Dirichlet conditions hold):
//   rotation about axis b: e_b x r;
//   rigidBodyMode(k, r), k = 0..5: translations e_x, e_y, e_z, then the
//   rotations (y,-x,0), (0,-z,y), (z,0,-x) = -e_z x r, e_x x r, e_y x r.
inline Point rotation(int b, const Point& r) {
  Point w{0, 0, 0};
  w[(b + 1) % 3] = -r[(b + 2) % 3];
  w[(b + 2) % 3] = r[(b + 1) % 3];
  return w;
}
inline Point rigidBodyMode(int k, const Point& r) {
  if (k < 3) {
    Point t{0, 0, 0};
    t[k] = 1.0;
    return t;
  }
  static constexpr int axis[3] = {2, 0, 1}, sign[3] = {-1, 1, 1};
  Point w = rotation(axis[k - 3], r);
  if (sign[k - 3] < 0)
    for (double& v : w) v = -v;
  return w;
}

// Makes the k columns of R (m x k, column-major) orthonormal (modified
// Gram-Schmidt twice); throws Tribos::Error(degenerate) when they are
// linearly dependent.
void orthonormalizeColumns(std::vector<double>& R, size_t m, int k, const std::string& degenerate);

// Rigid-body modes of a set of points about their centroid, the six of
// rigidBodyMode() orthonormalized (modified Gram-Schmidt twice).
// Column-major, 3*n x 6.
std::vector<double> rigidBodyModes(const std::vector<Point>& X);

}  // namespace Fem
}  // namespace Tribos
