// Tribos_MortarElement.hpp: what mortar integration needs of a facet of a
// contact surface, independent of its order: shape functions on a reference
// polygon, the map to space, the projection of points along a direction,
// and a quadrature of polygons in the reference plane.
//
// The mortar integrals are taken in the reference coordinates xi of the
// slave facet: master facets are projected onto it, clipped against its
// reference polygon (clipPolygon), the pieces cut into triangles and each
// triangle integrated with a rule of degree 5 (first-order facets) or 8
// (second-order ones, whose integrands are products of two quadratic or
// serendipity functions; integratePolygon), weighted by the surface
// Jacobian J(xi). The same rule integrates the facet's own mass matrix, so
// that the dual basis and the segments see one measure. The facets are
// those of the meshes' cells: 3- and 6-node triangles, 4- and 8-node
// quadrilaterals (Fem::facetShape's node orders: corners, then the mid-edge
// nodes edge by edge).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "Tribos_Mesh.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

using Point2 = std::array<double, 2>;

// Shape functions of a reference facet.
class SurfaceShape {
 public:
  virtual ~SurfaceShape() = default;
  virtual int numNodes() const = 0;
  // N[a], dN1[a] = dN_a/dxi_1, dN2[a] = dN_a/dxi_2 at xi (arrays of numNodes()).
  virtual void evaluate(const Point2& xi, double* N, double* dN1, double* dN2) const = 0;
  // The reference polygon, counter-clockwise (convex): the corner nodes,
  // which come first in the node order.
  virtual const std::vector<Point2>& corners() const = 0;
  // Whether mid-edge nodes follow the corners (6- and 8-node facets).
  bool secondOrder() const { return numNodes() > static_cast<int>(corners().size()); }
  // The degree of the rule that integrates products of two shape functions
  // (exactly on flat facets): 5, or 8 for second-order facets.
  int productDegree() const { return secondOrder() ? 8 : 5; }
};

// The shape of a facet with that many nodes (3, 4, 6 or 8); throws for others.
const SurfaceShape& surfaceShape(int numNodes);

// A facet of a contact surface in the reference configuration.
class SurfaceElement {
 public:
  SurfaceElement(const Mesh::Facet& facet, const Mesh::Mesh& mesh);
  const std::vector<int>& nodes() const { return nodes_; }
  const SurfaceShape& shape() const { return *shape_; }
  int size() const { return static_cast<int>(nodes_.size()); }
  Vec3 position(const Point2& xi) const;
  // The area element |x_1 x x_2| and unit outward normal at xi.
  double jacobian(const Point2& xi) const;
  Vec3 normal(const Point2& xi) const;
  // The centroid of the reference polygon.
  Point2 center() const;
  // The reference coordinates where the line x + t d meets the facet's
  // surface (extended beyond its polygon; Newton, exact in one step for
  // flat facets). False when d runs parallel to the facet.
  bool project(const Vec3& x, const Vec3& d, Point2& xi) const;
  // A sphere around the facet: its node average and the largest distance to a node.
  const Vec3& middle() const { return middle_; }
  double radius() const { return radius_; }
  // normal(center()), kept: the search asks it of every candidate.
  const Vec3& centreNormal() const { return centreNormal_; }

 private:
  void derivatives(const Point2& xi, Vec3& x1, Vec3& x2) const;
  const SurfaceShape* shape_;
  std::vector<int> nodes_;
  std::vector<Vec3> X_;
  Vec3 middle_{}, centreNormal_{};
  double radius_ = 0;
};

// sum_q w_q f(xi_q) over the polygon (its vertices in order, either
// orientation; convex, or star-shaped about its vertex average): a fan of
// triangles from the vertex average, each with a rule exact for polynomials
// of the degree, at most 8 (Fem::triangleQuadrature: 7 points up to degree
// 5, exact for products of two bilinear functions on parallelograms; 25
// beyond).
void integratePolygon(const std::vector<Point2>& polygon, const std::function<void(const Point2&, double)>& f,
                      int degree = 5);

// The area of a polygon (positive when counter-clockwise).
double signedArea(const std::vector<Point2>& polygon);

// The part of `subject` inside the convex, counter-clockwise polygon `clip`
// (Sutherland-Hodgman): empty when they do not overlap.
std::vector<Point2> clipPolygon(const std::vector<Point2>& subject, const std::vector<Point2>& clip);

}  // namespace Contact
}  // namespace Tribos
