#include "Tribos_Elasticity.hpp"

#include <cmath>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Fem {

std::array<double, 36> Material::D() const {
  const double l = lameLambda(), m = lameMu();
  std::array<double, 36> D{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) D[6 * i + j] = l;
    D[6 * i + i] = l + 2 * m;
    D[6 * (i + 3) + (i + 3)] = m;
  }
  return D;
}

namespace {

// Strain-displacement matrix B (6 x 3npc) from dN (npc x 3).
std::vector<double> strainDisplacement(const std::vector<double>& dN, int npc) {
  std::vector<double> B(6 * 3 * npc, 0.0);
  auto b = [&](int r, int c) -> double& { return B[r * 3 * npc + c]; };
  for (int a = 0; a < npc; ++a) {
    const double dx = dN[3 * a], dy = dN[3 * a + 1], dz = dN[3 * a + 2];
    b(0, 3 * a) = dx;
    b(1, 3 * a + 1) = dy;
    b(2, 3 * a + 2) = dz;
    b(3, 3 * a + 1) = dz;
    b(3, 3 * a + 2) = dy;
    b(4, 3 * a) = dz;
    b(4, 3 * a + 2) = dx;
    b(5, 3 * a) = dy;
    b(5, 3 * a + 1) = dx;
  }
  return B;
}

// Adds w B' D B to Ke.
void addBtDB(const std::vector<double>& B, const std::array<double, 36>& D, double w, int n, std::vector<double>& Ke) {
  std::vector<double> DB(6 * n, 0.0);
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k) {
      const double d = D[6 * i + k];
      if (d == 0.0) continue;
      for (int j = 0; j < n; ++j) DB[i * n + j] += d * B[k * n + j];
    }
  for (int k = 0; k < 6; ++k)
    for (int i = 0; i < n; ++i) {
      const double bki = w * B[k * n + i];
      if (bki == 0.0) continue;
      for (int j = 0; j < n; ++j) Ke[i * n + j] += bki * DB[k * n + j];
    }
}

// det J of J[i][j] = dx_j / dxi_i, and J^-1 in place when det J > 0.
double invert3(double J[3][3]) {
  const double det = determinant3(J);
  if (!(det > 0)) return det;
  double inv[3][3];
  inv[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
  inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
  inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
  inv[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
  inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
  inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
  inv[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
  inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
  inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) J[i][j] = inv[i][j];
  return det;
}

std::string pointText(const Point& xi) {
  std::ostringstream os;
  os << "(" << xi[0] << ", " << xi[1] << ", " << xi[2] << ")";
  return os.str();
}

void requireNodes(Mesh::CellType type, const std::vector<Point>& X) {
  TRIBOS_REQUIRE(static_cast<int>(X.size()) == Mesh::nodesPerCell(type),
                 Mesh::cellTypeName(type) << " cell given " << X.size() << " nodes");
}

// Voigt stress D B ue from the gradients dN (npc x 3) at one point.
std::array<double, 6> stressAt(const std::vector<double>& dN, int npc, const std::vector<double>& ue,
                               const std::array<double, 36>& D) {
  const auto B = strainDisplacement(dN, npc);
  std::array<double, 6> eps{}, sigma{};
  for (int r = 0; r < 6; ++r)
    for (int j = 0; j < 3 * npc; ++j) eps[r] += B[r * 3 * npc + j] * ue[j];
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) sigma[r] += D[6 * r + k] * eps[k];
  return sigma;
}

}  // namespace

void requirePositiveJacobianAtNodes(Mesh::CellType type, const std::vector<Point>& X) {
  if (!Mesh::isSecondOrder(type)) return;
  const int npc = Mesh::nodesPerCell(type);
  const std::vector<Point> nodes = referenceNodes(type);
  double N[kMaxNodesPerCell], dNdxi[kMaxNodesPerCell][3], J[3][3];
  for (int a = 0; a < npc; ++a) {
    referenceShape(type, nodes[a], N, dNdxi);
    isoparametricJacobian(dNdxi, X.data(), npc, J);
    const double det = determinant3(J);
    TRIBOS_REQUIRE(det > 0, "inverted or degenerate " << Mesh::cellTypeName(type) << " cell: det J = " << det
                                                      << " <= 0 at its node " << a << " " << pointText(X[a])
                                                      << "; its map from the reference cell folds there (a "
                                                         "mid-edge node too far from the middle of its edge?)");
  }
}

double shapeGradients(Mesh::CellType type, const std::vector<Point>& X, const Point& xi, std::vector<double>& dN) {
  requireNodes(type, X);
  const int npc = Mesh::nodesPerCell(type);
  dN.assign(3 * npc, 0.0);
  double N[kMaxNodesPerCell], dNdxi[kMaxNodesPerCell][3], J[3][3];
  referenceShape(type, xi, N, dNdxi);
  isoparametricJacobian(dNdxi, X.data(), npc, J);
  const double det = invert3(J);  // J now holds d xi / d x (transposed layout)
  TRIBOS_REQUIRE(det > 0, "inverted or degenerate " << Mesh::cellTypeName(type) << " cell: det J = " << det
                                                    << " <= 0 at the reference point " << pointText(xi));
  for (int a = 0; a < npc; ++a)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) dN[3 * a + j] += J[j][i] * dNdxi[a][i];
  return det;
}

std::vector<double> shapeFunctions(Mesh::CellType type, const Point& xi) {
  double N[kMaxNodesPerCell], dNdxi[kMaxNodesPerCell][3];
  referenceShape(type, xi, N, dNdxi);
  return std::vector<double>(N, N + Mesh::nodesPerCell(type));
}

std::vector<double> elementStiffness(Mesh::CellType type, const std::vector<Point>& X, const Material& mat) {
  const int npc = Mesh::nodesPerCell(type), n = 3 * npc;
  std::vector<double> Ke(n * n, 0.0), dN;
  const auto D = mat.D();
  if (type == Mesh::CellType::Tet4) {
    const double det = shapeGradients(type, X, {0, 0, 0}, dN);
    addBtDB(strainDisplacement(dN, npc), D, det / 6.0, n, Ke);
    return Ke;
  }
  requireNodes(type, X);
  requirePositiveJacobianAtNodes(type, X);
  for (const QuadraturePoint& q : cellQuadrature(type)) {
    const double det = shapeGradients(type, X, q.xi, dN);
    addBtDB(strainDisplacement(dN, npc), D, q.weight * det, n, Ke);
  }
  return Ke;
}

std::array<double, 6> cellStress(Mesh::CellType type, const std::vector<Point>& X, const std::vector<double>& ue,
                                 const Material& mat) {
  const int npc = Mesh::nodesPerCell(type);
  const auto D = mat.D();
  std::vector<double> dN;
  if (!Mesh::isSecondOrder(type)) {
    shapeGradients(type, X, {0, 0, 0}, dN);
    return stressAt(dN, npc, ue, D);
  }
  std::array<double, 6> integral{};
  double volume = 0;
  for (const QuadraturePoint& q : cellQuadrature(type)) {
    const double w = q.weight * shapeGradients(type, X, q.xi, dN);
    const auto sigma = stressAt(dN, npc, ue, D);
    for (int r = 0; r < 6; ++r) integral[r] += w * sigma[r];
    volume += w;
  }
  for (double& v : integral) v /= volume;
  return integral;
}

double vonMises(const std::array<double, 6>& s) {
  const double d1 = s[0] - s[1], d2 = s[1] - s[2], d3 = s[2] - s[0];
  return std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

std::vector<double> facetNodalAreas(const std::vector<Point>& X) {
  const int nodes = static_cast<int>(X.size());
  if (nodes == 3) {
    const double area = 0.5 * norm(cross(minus(X[1], X[0]), minus(X[2], X[0])));
    return {area / 3, area / 3, area / 3};
  }
  TRIBOS_REQUIRE(nodes == 4 || nodes == 6 || nodes == 8, "facet with " << nodes << " nodes (3, 4, 6 or 8 expected)");
  // Weight of node a = sum_q w_q N_a(q) |dX/ds x dX/dt|(q).
  std::vector<double> w(nodes, 0.0);
  double N[kMaxNodesPerFacet], dNds[kMaxNodesPerFacet][2];
  for (const FacetQuadraturePoint& q : facetQuadrature(nodes)) {
    facetShape(nodes, q.s, q.t, N, dNds);
    Point xs{}, xt{};
    for (int a = 0; a < nodes; ++a)
      for (int d = 0; d < 3; ++d) {
        xs[d] += dNds[a][0] * X[a][d];
        xt[d] += dNds[a][1] * X[a][d];
      }
    const double J = norm(cross(xs, xt));
    for (int a = 0; a < nodes; ++a) w[a] += N[a] * J * q.weight;
  }
  return w;
}

std::vector<double> facetTractionForces(const std::vector<Point>& X, const Point& t) {
  const auto w = facetNodalAreas(X);
  std::vector<double> f(3 * X.size());
  for (size_t a = 0; a < X.size(); ++a)
    for (int d = 0; d < 3; ++d) f[3 * a + d] = w[a] * t[d];
  return f;
}

std::vector<double> cellVolumeForces(Mesh::CellType type, const std::vector<Point>& X, const Point& b) {
  const int npc = Mesh::nodesPerCell(type);
  std::vector<double> f(3 * npc, 0.0), dN;
  if (type == Mesh::CellType::Tet4) {
    const double vol = shapeGradients(type, X, {0, 0, 0}, dN) / 6.0;
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) f[3 * a + d] = vol / 4 * b[d];
    return f;
  }
  double N[kMaxNodesPerCell], dNdxi[kMaxNodesPerCell][3];
  for (const QuadraturePoint& q : cellQuadrature(type)) {
    const double w = q.weight * shapeGradients(type, X, q.xi, dN);
    referenceShape(type, q.xi, N, dNdxi);
    for (int a = 0; a < npc; ++a)
      for (int d = 0; d < 3; ++d) f[3 * a + d] += w * N[a] * b[d];
  }
  return f;
}

void orthonormalizeColumns(std::vector<double>& R, size_t m, int k, const std::string& degenerate) {
  // Two passes of modified Gram-Schmidt make the columns orthonormal to round-off.
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < k; ++j) {
      double* rj = &R[j * m];
      for (int i = 0; i < j; ++i) {
        const double* ri = &R[i * m];
        double dot = 0;
        for (size_t a = 0; a < m; ++a) dot += ri[a] * rj[a];
        for (size_t a = 0; a < m; ++a) rj[a] -= dot * ri[a];
      }
      double nrm = 0;
      for (size_t a = 0; a < m; ++a) nrm += rj[a] * rj[a];
      nrm = std::sqrt(nrm);
      TRIBOS_REQUIRE(nrm > 1e-12, degenerate);
      for (size_t a = 0; a < m; ++a) rj[a] /= nrm;
    }
}

std::vector<double> rigidBodyModes(const std::vector<Point>& X) {
  const size_t n = X.size(), m = 3 * n;
  Point c{};
  for (const Point& p : X)
    for (int d = 0; d < 3; ++d) c[d] += p[d] / n;
  std::vector<double> R(m * 6, 0.0);
  for (size_t a = 0; a < n; ++a) {
    const Point r{X[a][0] - c[0], X[a][1] - c[1], X[a][2] - c[2]};
    for (int k = 0; k < 6; ++k) {
      const Point mode = rigidBodyMode(k, r);
      for (int d = 0; d < 3; ++d) R[k * m + 3 * a + d] = mode[d];
    }
  }
  orthonormalizeColumns(R, m, 6, "rigid-body modes are degenerate (fewer than 3 non-collinear points)");
  return R;
}

}  // namespace Fem
}  // namespace Tribos
