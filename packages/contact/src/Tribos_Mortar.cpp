#include "Tribos_Mortar.hpp"

#include <Teuchos_SerialDenseMatrix.hpp>
#include <Teuchos_SerialDenseSolver.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Contact {

namespace {

constexpr int kMaxNodes = 9;

// A master facet takes part for slave facet e when it faces e, its sphere
// can reach e's along e's normal n0 (orthogonal projection does not
// expand), and one of its nodes lies within `reach` of e along n0.
bool mayOverlap(const SurfaceElement& e, const Vec3& n0, const SurfaceElement& m, double reach) {
  if (dot(m.centreNormal(), n0) >= 0) return false;
  const Vec3 r = minus(m.middle(), e.middle());
  const double along = dot(r, n0);
  const Vec3 across = {r[0] - along * n0[0], r[1] - along * n0[1], r[2] - along * n0[2]};
  const double size = e.radius() + m.radius();
  return norm(across) <= size * (1 + 1e-12) && std::abs(along) <= reach + size;
}

// The master facet's corners projected along n0 onto e, in e's reference
// coordinates; empty when a corner does not project or all lie beyond
// `reach`. A curved second-order master facet is so cut along the chords of
// its edges, which its neighbours share: the segments still tile e.
std::vector<Point2> projectedPolygon(const SurfaceElement& e, const Vec3& n0, const SurfaceElement& m,
                                     const Mesh::Mesh& mesh, double reach) {
  std::vector<Point2> poly;
  double nearest = std::numeric_limits<double>::infinity();
  const int corners = static_cast<int>(m.shape().corners().size());
  for (int a = 0; a < corners; ++a) {
    const int node = m.nodes()[a];
    Point2 xi;
    if (!e.project(mesh.coords[node], n0, xi)) return {};
    nearest = std::min(nearest, norm(minus(mesh.coords[node], e.position(xi))));
    poly.push_back(xi);
  }
  if (nearest > reach) return {};
  return poly;
}

// M_jk += int over the segment of psi_j N_k dA for the slave nodes j of e
// and the master nodes k of m, and normal_j += int N~_j n_m dA (n_m the
// master's outward normal, N~ the slave's transformed basis); the segment
// in e's reference coordinates.
void integrateSegment(const SurfaceElement& e, const std::vector<std::vector<double>>& A, const Vec3& n0,
                      const SurfaceElement& m, const std::vector<Point2>& segment,
                      std::vector<std::unordered_map<int, double>>& M, std::vector<Vec3>& normal) {
  const int ns = e.size(), nm = m.size();
  double Ns[kMaxNodes], Nm[kMaxNodes], d1[kMaxNodes], d2[kMaxNodes];
  const int degree = std::max(e.shape().productDegree(), m.shape().productDegree());
  integratePolygon(segment, [&](const Point2& xi, double w) {
    Point2 zeta;
    if (!m.project(e.position(xi), n0, zeta)) return;
    const double dA = w * e.jacobian(xi);
    transformedShape(e.shape(), xi, Ns);
    m.shape().evaluate(zeta, Nm, d1, d2);
    const Vec3 outward = m.normal(zeta);
    for (int j = 0; j < ns; ++j) {
      for (int d = 0; d < 3; ++d) normal[j][d] += Ns[j] * outward[d] * dA;
      double psi = 0;
      for (int k = 0; k < ns; ++k) psi += A[j][k] * Ns[k];
      for (int k = 0; k < nm; ++k) M[j][m.nodes()[k]] += psi * Nm[k] * dA;
    }
  }, degree);
}

}  // namespace

void transformedShape(const SurfaceShape& shape, const Point2& xi, double* N) {
  double d1[kMaxNodes], d2[kMaxNodes];
  shape.evaluate(xi, N, d1, d2);
  if (!shape.secondOrder()) return;
  const int corners = static_cast<int>(shape.corners().size());
  for (int c = 0; c < corners; ++c) N[c] += kMidEdgeShare * (N[corners + c] + N[corners + (c + corners - 1) % corners]);
  for (int m = corners; m < shape.numNodes(); ++m) N[m] *= 1 - 2 * kMidEdgeShare;
}

std::map<int, std::vector<std::pair<int, double>>> transformedNodes(const Mesh::Mesh& mesh, const std::string& face) {
  std::map<int, std::vector<std::pair<int, double>>> out;
  const double alpha = kMidEdgeShare, keep = 1 - 2 * kMidEdgeShare;
  for (const auto& f : mesh.face(face)) {
    const int corners = static_cast<int>(surfaceShape(static_cast<int>(f.nodes.size())).corners().size());
    for (int k = corners; k < static_cast<int>(f.nodes.size()); ++k) {
      const int a = f.nodes[k - corners], b = f.nodes[(k - corners + 1) % corners];
      out[f.nodes[k]] = {{f.nodes[k], 1 / keep}, {a, -alpha / keep}, {b, -alpha / keep}};
    }
  }
  return out;
}

std::vector<double> transformedAreas(const Mesh::Mesh& mesh, const std::string& face) {
  std::vector<double> area(mesh.numNodes(), 0.0);
  double N[kMaxNodes];
  for (const auto& f : mesh.face(face)) {
    const SurfaceElement e(f, mesh);
    integratePolygon(e.shape().corners(), [&](const Point2& xi, double w) {
      transformedShape(e.shape(), xi, N);
      const double dA = w * e.jacobian(xi);
      for (int j = 0; j < e.size(); ++j) area[e.nodes()[j]] += N[j] * dA;
    }, e.shape().productDegree());
  }
  return area;
}

double MortarNode::covered() const {
  double sum = 0;
  for (const auto& [node, value] : M) sum += value;
  return sum;
}

DualBasis dualBasis(const SurfaceElement& e) {
  const int n = e.size();
  Teuchos::SerialDenseMatrix<int, double> mass(n, n);
  double N[kMaxNodes];
  integratePolygon(e.shape().corners(), [&](const Point2& xi, double w) {
    transformedShape(e.shape(), xi, N);
    const double dA = w * e.jacobian(xi);
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) mass(j, k) += N[j] * N[k] * dA;
  }, e.shape().productDegree());
  std::vector<double> D(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) D[j] += mass(j, k);
  Teuchos::SerialDenseSolver<int, double> solver;
  solver.setMatrix(Teuchos::rcpFromRef(mass));
  TRIBOS_REQUIRE(solver.invert() == 0, "mortar contact: the mass matrix of a slave facet (nodes "
                                           << e.nodes()[0] << ", " << e.nodes()[1] << ", ...) is singular");
  // A = D M^-1, M symmetric.
  std::vector<std::vector<double>> A(n, std::vector<double>(n));
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) A[j][k] = D[j] * mass(j, k);
  return {A, D};
}

std::vector<MortarNode> mortarCoupling(const Mesh::Mesh& mesh, const std::string& slave, const std::string& master,
                                       double reach) {
  static const auto timer = Teuchos::TimeMonitor::getNewCounter("Tribos::contact search: mortar integrals");
  Teuchos::TimeMonitor timing(*timer);
  std::vector<SurfaceElement> slaves, masters;
  for (const auto& f : mesh.face(slave)) slaves.emplace_back(f, mesh);
  for (const auto& f : mesh.face(master)) masters.emplace_back(f, mesh);
  const std::vector<int> nodes = mesh.faceNodes(slave);
  std::unordered_map<int, size_t> index;
  for (size_t i = 0; i < nodes.size(); ++i) index[nodes[i]] = i;
  std::vector<MortarNode> out(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) out[i].node = nodes[i];

  std::vector<std::unordered_map<int, double>> M;
  std::vector<Vec3> normal;
  for (const SurfaceElement& e : slaves) {
    const DualBasis basis = dualBasis(e);
    const Vec3& n0 = e.centreNormal();
    for (int j = 0; j < e.size(); ++j) out[index.at(e.nodes()[j])].area += basis.D[j];
    M.assign(e.size(), {});
    normal.assign(e.size(), Vec3{0, 0, 0});
    for (const SurfaceElement& m : masters) {
      if (!mayOverlap(e, n0, m, reach)) continue;
      const std::vector<Point2> segment = clipPolygon(projectedPolygon(e, n0, m, mesh, reach), e.shape().corners());
      if (std::abs(signedArea(segment)) <= 1e-12 * std::abs(signedArea(e.shape().corners()))) continue;
      integrateSegment(e, basis.A, n0, m, segment, M, normal);
    }
    for (int j = 0; j < e.size(); ++j) {
      MortarNode& node = out[index.at(e.nodes()[j])];
      for (const auto& [master, value] : M[j]) node.M[master] += value;
      for (int d = 0; d < 3; ++d) node.normal[d] -= normal[j][d];
    }
  }
  for (MortarNode& node : out)
    if (norm(node.normal) > 0) node.normal = normalized(node.normal);
  return out;
}

}  // namespace Contact
}  // namespace Tribos
