#include "Tribos_MortarElement.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_ShapeFunctions.hpp"

namespace Tribos {
namespace Contact {

namespace {

// The facets of the meshes: 3- and 6-node triangles on (0,0), (1,0), (0,1),
// 4- and 8-node quadrilaterals on [-1,1]^2 (Fem::facetShape, whose node
// orders the mesh's facets follow).
class FacetShape : public SurfaceShape {
 public:
  FacetShape(int nodes, std::vector<Point2> corners) : nodes_(nodes), corners_(std::move(corners)) {}
  int numNodes() const override { return nodes_; }
  void evaluate(const Point2& xi, double* N, double* dN1, double* dN2) const override {
    double dN[Fem::kMaxNodesPerFacet][2];
    Fem::facetShape(nodes_, xi[0], xi[1], N, dN);
    for (int a = 0; a < nodes_; ++a) dN1[a] = dN[a][0], dN2[a] = dN[a][1];
  }
  const std::vector<Point2>& corners() const override { return corners_; }

 private:
  int nodes_;
  std::vector<Point2> corners_;
};

constexpr int kMaxNodes = 9;

double cross2(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

}  // namespace

const SurfaceShape& surfaceShape(int numNodes) {
  static const std::vector<Point2> triangle = {{0, 0}, {1, 0}, {0, 1}}, square = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  static const FacetShape tri3(3, triangle), quad4(4, square), tri6(6, triangle), quad8(8, square);
  switch (numNodes) {
    case 3: return tri3;
    case 4: return quad4;
    case 6: return tri6;
    case 8: return quad8;
  }
  throw Error("contact: a facet with " + std::to_string(numNodes) + " nodes (3, 4, 6 or 8 expected)");
}

SurfaceElement::SurfaceElement(const Mesh::Facet& facet, const Mesh::Mesh& mesh)
    : shape_(&surfaceShape(static_cast<int>(facet.nodes.size()))), nodes_(facet.nodes) {
  for (int n : nodes_) X_.push_back(mesh.coords[n]);
  for (const Vec3& x : X_)
    for (int d = 0; d < 3; ++d) middle_[d] += x[d] / X_.size();
  for (const Vec3& x : X_) radius_ = std::max(radius_, norm(minus(x, middle_)));
  centreNormal_ = normal(center());
}

Vec3 SurfaceElement::position(const Point2& xi) const {
  double N[kMaxNodes], d1[kMaxNodes], d2[kMaxNodes];
  shape_->evaluate(xi, N, d1, d2);
  Vec3 x{0, 0, 0};
  for (int a = 0; a < size(); ++a)
    for (int d = 0; d < 3; ++d) x[d] += N[a] * X_[a][d];
  return x;
}

void SurfaceElement::derivatives(const Point2& xi, Vec3& x1, Vec3& x2) const {
  double N[kMaxNodes], d1[kMaxNodes], d2[kMaxNodes];
  shape_->evaluate(xi, N, d1, d2);
  x1 = x2 = Vec3{0, 0, 0};
  for (int a = 0; a < size(); ++a)
    for (int d = 0; d < 3; ++d) x1[d] += d1[a] * X_[a][d], x2[d] += d2[a] * X_[a][d];
}

double SurfaceElement::jacobian(const Point2& xi) const {
  Vec3 x1, x2;
  derivatives(xi, x1, x2);
  return norm(cross(x1, x2));
}

Vec3 SurfaceElement::normal(const Point2& xi) const {
  Vec3 x1, x2;
  derivatives(xi, x1, x2);
  return normalized(cross(x1, x2));
}

Point2 SurfaceElement::center() const {
  Point2 c{0, 0};
  for (const Point2& p : shape_->corners()) c[0] += p[0], c[1] += p[1];
  const double n = static_cast<double>(shape_->corners().size());
  return {c[0] / n, c[1] / n};
}

bool SurfaceElement::project(const Vec3& x, const Vec3& d, Point2& xi) const {
  // Solve position(xi) - t d = x for (xi_1, xi_2, t) by Newton, Cramer's rule
  // on the 3 x 3 Jacobian [x_1, x_2, -d].
  xi = center();
  for (int it = 0; it < 20; ++it) {
    Vec3 x1, x2;
    derivatives(xi, x1, x2);
    const Vec3 r = minus(x, position(xi)), md = {-d[0], -d[1], -d[2]};
    const double det = dot(x1, cross(x2, md));
    if (!(std::abs(det) > 1e-12 * norm(x1) * norm(x2))) return false;
    const double dxi1 = dot(r, cross(x2, md)) / det, dxi2 = dot(x1, cross(r, md)) / det;
    xi[0] += dxi1, xi[1] += dxi2;
    if (std::abs(dxi1) + std::abs(dxi2) < 1e-14) return true;
  }
  return std::isfinite(xi[0]) && std::isfinite(xi[1]);
}

double signedArea(const std::vector<Point2>& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2 &u = p[i], &v = p[(i + 1) % p.size()];
    a += u[0] * v[1] - v[0] * u[1];
  }
  return a / 2;
}

void integratePolygon(const std::vector<Point2>& polygon, const std::function<void(const Point2&, double)>& f,
                      int degree) {
  static const std::vector<Fem::FacetQuadraturePoint> rule5 = Fem::triangleQuadrature(5),
                                                      rule8 = Fem::triangleQuadrature(8);
  const auto& rule = degree <= 5 ? rule5 : rule8;
  TRIBOS_REQUIRE(degree <= 8, "integratePolygon: no rule of degree " << degree);
  if (polygon.size() < 3) return;
  Point2 c{0, 0};
  for (const Point2& p : polygon) c[0] += p[0] / polygon.size(), c[1] += p[1] / polygon.size();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Point2 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    const double area = std::abs(cross2(c, a, b)) / 2;
    if (area == 0) continue;
    // The rule's triangle (0,0), (1,0), (0,1) of area 1/2 mapped onto (c, a, b).
    for (const auto& q : rule) {
      const double l0 = 1 - q.s - q.t;
      f({l0 * c[0] + q.s * a[0] + q.t * b[0], l0 * c[1] + q.s * a[1] + q.t * b[1]}, 2 * q.weight * area);
    }
  }
}

std::vector<Point2> clipPolygon(const std::vector<Point2>& subject, const std::vector<Point2>& clip) {
  // Points within round-off of an edge count as inside, so that a polygon
  // sharing an edge with the clip region keeps it.
  constexpr double kOn = 1e-13;
  std::vector<Point2> out = subject;
  for (size_t e = 0; e < clip.size() && !out.empty(); ++e) {
    const Point2 &a = clip[e], &b = clip[(e + 1) % clip.size()];
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    auto side = [&](const Point2& p) { return cross2(a, b, p) / length; };
    std::vector<Point2> in = std::move(out);
    out.clear();
    for (size_t i = 0; i < in.size(); ++i) {
      const Point2 &p = in[i], &q = in[(i + 1) % in.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= -kOn) out.push_back(p);
      if ((sp >= -kOn) != (sq >= -kOn)) {
        // Where the edge crosses the boundary, within the edge: two
        // vertices within kOn of the boundary on its outer side, one
        // counted in and one out, give a t far outside [0, 1], and without
        // the clamp a point far outside the facet (a master facet that
        // coincides with the slave facet up to round-off, as where two
        // meshes match on a part of the interface, got weights of +-19
        // instead of 1, and a gap from them).
        const double t = std::clamp(sp / (sp - sq), 0.0, 1.0);
        out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
  }
  return out;
}

}  // namespace Contact
}  // namespace Tribos
