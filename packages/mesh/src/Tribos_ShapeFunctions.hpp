// Tribos_ShapeFunctions.hpp: the reference cells and facets of Tribos'
// elements, their shape functions and the quadrature rules the element
// integrals use (docs/quadratic_elements.md). They live in the mesh package,
// whose readers check det J of second-order cells with them; the fem
// package's element kernels integrate with them (namespace Fem).
//
// Reference cells and node orderings (Gmsh's):
//   Tet4, Tet10: the unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1);
//     Tet10 adds the mid-edge nodes 4 = 0-1, 5 = 1-2, 6 = 2-0, 7 = 3-0,
//     8 = 3-2, 9 = 3-1 (P2 Lagrange).
//   Hex8, Hex20: [-1,1]^3, corners 0-3 the bottom (z = -1) counter-clockwise
//     seen from above starting at (-1,-1,-1), 4-7 the top; Hex20 adds the
//     mid-edge nodes 8 = 0-1, 9 = 0-3, 10 = 0-4, 11 = 1-2, 12 = 1-5, 13 = 2-3,
//     14 = 2-6, 15 = 3-7, 16 = 4-5, 17 = 4-7, 18 = 5-6, 19 = 6-7 (serendipity).
//   Facets: 3- and 6-node triangles on (0,0), (1,0), (0,1); 4- and 8-node
//     quadrilaterals on [-1,1]^2 from (-1,-1) counter-clockwise; the mid-edge
//     nodes follow the corners edge by edge (0-1, 1-2, 2-0 or 0-1, 1-2, 2-3,
//     3-0).
#pragma once

#include <array>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Fem {

using Point = std::array<double, 3>;

constexpr int kMaxNodesPerCell = 20;
constexpr int kMaxNodesPerFacet = 8;

// Shape functions N (nodesPerCell values) and their derivatives with respect
// to the reference coordinates, dNdxi[a][i] = dN_a / dxi_i, at xi.
void referenceShape(Mesh::CellType type, const Point& xi, double N[], double dNdxi[][3]);

// The Jacobian of the isoparametric map x(xi) = sum_a N_a(xi) X_a at the
// point where dNdxi was evaluated, transposed: J[i][j] = dx_j / dxi_i (its
// determinant is det J); X holds the cell's npc node coordinates.
void isoparametricJacobian(const double dNdxi[][3], const Point* X, int npc, double J[3][3]);
double determinant3(const double J[3][3]);

// The nodes of the reference cell, in the node order above.
std::vector<Point> referenceNodes(Mesh::CellType type);

struct QuadraturePoint {
  Point xi;
  double weight;  // in reference coordinates
};

// The rule of the element integrals of the second-order cells (stiffness,
// volume forces, stress average), and of Hex8's stiffness:
//   Hex8: 2x2x2 Gauss;
//   Tet10: 14 points of degree 5 (Walkington; Grundmann-Moeller), all
//     weights positive;
//   Hex20: 3x3x3 Gauss (degree 5 in each coordinate).
// On straight-sided Tet10 cells and parallelepiped Hex20 cells they
// integrate the stiffness exactly. On curved cells the stiffness integrand
// is rational and no rule is exact; but div-type integrals such as int
// grad N_a dV, a Jacobian determinant of three shape-function maps, are
// polynomials of degree 3 (Tet10) or 5 in each coordinate (Hex20), which
// these rules integrate exactly: the patch test holds on curved meshes.
// Tet4 has no rule here: its strain is constant.
std::vector<QuadraturePoint> cellQuadrature(Mesh::CellType type);

// A rule exact for polynomials of degree 3 at least, for error norms of
// manufactured solutions: Tet4 Keast's 5 points (degree 3), Hex8 3x3x3 Gauss,
// Tet10 the 14 points above (degree 5), Hex20 4x4x4 Gauss (degree 7 in each
// coordinate).
std::vector<QuadraturePoint> accurateQuadrature(Mesh::CellType type);

// Facets: shape functions and derivatives dNds[a] = (dN_a/ds, dN_a/dt) of a
// facet with 3, 4, 6 or 8 nodes at (s, t).
void facetShape(int nodes, double s, double t, double N[], double dNds[][2]);

struct FacetQuadraturePoint {
  double s, t;
  double weight;  // in reference coordinates
};

// The rule of the facet integrals: 4 nodes 2x2 Gauss; 6 nodes Radon's 7
// points (degree 5); 8 nodes 3x3 Gauss (degree 5 in each coordinate). The
// surface element |x_s x x_t| of a curved facet is not a polynomial, but
// for a facet that is flat (its mid-edge nodes moved within its plane) it is,
// and the consistent loads there are exact: N_a |x_s x x_t| has degree 4
// (6 nodes) or 5 in each coordinate (8 nodes).
std::vector<FacetQuadraturePoint> facetQuadrature(int nodes);

// A rule on the triangle (0,0), (1,0), (0,1) (weights summing to 1/2) exact
// for polynomials of the given degree, at most 8: Radon's 7 points up to
// degree 5, a collapsed 5x5 Gauss product beyond (the mortar integrals of
// second-order facets, products of two quadratic or serendipity functions).
std::vector<FacetQuadraturePoint> triangleQuadrature(int degree);

}  // namespace Fem
}  // namespace Tribos
