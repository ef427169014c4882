#include "Tribos_MortarElement.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Contact {

namespace {

class Tri3 : public SurfaceShape {
 public:
  int numNodes() const override { return 3; }
  void evaluate(const Point2& xi, double* N, double* dN1, double* dN2) const override {
    N[0] = 1 - xi[0] - xi[1], N[1] = xi[0], N[2] = xi[1];
    dN1[0] = -1, dN1[1] = 1, dN1[2] = 0;
    dN2[0] = -1, dN2[1] = 0, dN2[2] = 1;
  }
  const std::vector<Point2>& corners() const override {
    static const std::vector<Point2> c = {{0, 0}, {1, 0}, {0, 1}};
    return c;
  }
};

class Quad4 : public SurfaceShape {
 public:
  int numNodes() const override { return 4; }
  void evaluate(const Point2& xi, double* N, double* dN1, double* dN2) const override {
    const auto& c = corners();
    for (int a = 0; a < 4; ++a) {
      N[a] = (1 + c[a][0] * xi[0]) * (1 + c[a][1] * xi[1]) / 4;
      dN1[a] = c[a][0] * (1 + c[a][1] * xi[1]) / 4;
      dN2[a] = c[a][1] * (1 + c[a][0] * xi[0]) / 4;
    }
  }
  const std::vector<Point2>& corners() const override {
    static const std::vector<Point2> c = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    return c;
  }
};

constexpr int kMaxNodes = 9;

double cross2(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Dunavant's 7-point rule on a triangle: barycentric points and weights
// summing to 1, exact for polynomials of degree 5.
struct TriangleRule {
  std::array<std::array<double, 3>, 7> point;
  std::array<double, 7> weight;
  TriangleRule() {
    const double r = std::sqrt(15.0);
    const double a1 = (9 - 2 * r) / 21, b1 = (6 + r) / 21, w1 = (155 + r) / 1200;
    const double a2 = (9 + 2 * r) / 21, b2 = (6 - r) / 21, w2 = (155 - r) / 1200;
    point = {{{1.0 / 3, 1.0 / 3, 1.0 / 3}, {a1, b1, b1}, {b1, a1, b1}, {b1, b1, a1}, {a2, b2, b2}, {b2, a2, b2},
              {b2, b2, a2}}};
    weight = {9.0 / 40, w1, w1, w1, w2, w2, w2};
  }
};

}  // namespace

const SurfaceShape& surfaceShape(int numNodes) {
  static const Tri3 tri;
  static const Quad4 quad;
  TRIBOS_REQUIRE(numNodes == 3 || numNodes == 4, "mortar contact: a facet with " << numNodes << " nodes (3 or 4 expected)");
  return numNodes == 3 ? static_cast<const SurfaceShape&>(tri) : quad;
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

void integratePolygon(const std::vector<Point2>& polygon, const std::function<void(const Point2&, double)>& f) {
  static const TriangleRule rule;
  if (polygon.size() < 3) return;
  Point2 c{0, 0};
  for (const Point2& p : polygon) c[0] += p[0] / polygon.size(), c[1] += p[1] / polygon.size();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Point2 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    const double area = std::abs(cross2(c, a, b)) / 2;
    if (area == 0) continue;
    for (size_t q = 0; q < rule.weight.size(); ++q) {
      const auto& l = rule.point[q];
      f({l[0] * c[0] + l[1] * a[0] + l[2] * b[0], l[0] * c[1] + l[1] * a[1] + l[2] * b[1]}, rule.weight[q] * area);
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
