#include "Tribos_Elasticity.hpp"

#include <cmath>

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

const double kGauss = 1.0 / std::sqrt(3.0);
const int kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

void hexShape(const Point& xi, double N[8], double dNdxi[8][3]) {
  for (int a = 0; a < 8; ++a) {
    const double s[3] = {1 + kHexSign[a][0] * xi[0], 1 + kHexSign[a][1] * xi[1], 1 + kHexSign[a][2] * xi[2]};
    N[a] = s[0] * s[1] * s[2] / 8;
    dNdxi[a][0] = kHexSign[a][0] * s[1] * s[2] / 8;
    dNdxi[a][1] = kHexSign[a][1] * s[0] * s[2] / 8;
    dNdxi[a][2] = kHexSign[a][2] * s[0] * s[1] / 8;
  }
}

// Inverts the 3x3 matrix J in place; returns det J.
double invert3(double J[3][3]) {
  const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                     J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                     J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  TRIBOS_REQUIRE(det > 0, "degenerate or inverted cell (det J = " << det << ")");
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

std::vector<Point> hexGaussPoints() {
  std::vector<Point> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) pts.push_back({(2 * i - 1) * kGauss, (2 * j - 1) * kGauss, (2 * k - 1) * kGauss});
  return pts;
}

}  // namespace

double shapeGradients(Mesh::CellType type, const std::vector<Point>& X, const Point& xi, std::vector<double>& dN) {
  const int npc = Mesh::nodesPerCell(type);
  dN.assign(3 * npc, 0.0);
  double dNdxi[8][3], N[8];
  if (type == Mesh::CellType::Tet4) {
    const double ref[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) dNdxi[a][d] = ref[a][d];
  } else {
    hexShape(xi, N, dNdxi);
  }
  double J[3][3] = {};  // J[i][j] = d x_j / d xi_i
  for (int a = 0; a < npc; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) J[i][j] += dNdxi[a][i] * X[a][j];
  const double det = invert3(J);  // J now holds d xi / d x (transposed layout)
  for (int a = 0; a < npc; ++a)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) dN[3 * a + j] += J[j][i] * dNdxi[a][i];
  return det;
}

std::vector<double> shapeFunctions(Mesh::CellType type, const Point& xi) {
  if (type == Mesh::CellType::Tet4) return {1 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  double N[8], dNdxi[8][3];
  hexShape(xi, N, dNdxi);
  return std::vector<double>(N, N + 8);
}

std::vector<QuadraturePoint> accurateQuadrature(Mesh::CellType type) {
  if (type == Mesh::CellType::Tet4) {
    // Keast's 5-point rule (degree 3) on the unit tetrahedron of volume 1/6.
    const double a = 0.5, b = 1.0 / 6.0;
    return {{{0.25, 0.25, 0.25}, -2.0 / 15.0},
            {{a, b, b}, 3.0 / 40.0},
            {{b, a, b}, 3.0 / 40.0},
            {{b, b, a}, 3.0 / 40.0},
            {{b, b, b}, 3.0 / 40.0}};
  }
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  std::vector<QuadraturePoint> q;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) q.push_back({{g[i], g[j], g[k]}, w[i] * w[j] * w[k]});
  return q;
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
  for (const Point& xi : hexGaussPoints()) {
    const double det = shapeGradients(type, X, xi, dN);
    addBtDB(strainDisplacement(dN, npc), D, det, n, Ke);
  }
  return Ke;
}

std::array<double, 6> cellStress(Mesh::CellType type, const std::vector<Point>& X, const std::vector<double>& ue,
                                 const Material& mat) {
  const int npc = Mesh::nodesPerCell(type);
  std::vector<double> dN;
  shapeGradients(type, X, {0, 0, 0}, dN);
  const auto B = strainDisplacement(dN, npc);
  const auto D = mat.D();
  std::array<double, 6> eps{}, sigma{};
  for (int r = 0; r < 6; ++r)
    for (int j = 0; j < 3 * npc; ++j) eps[r] += B[r * 3 * npc + j] * ue[j];
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) sigma[r] += D[6 * r + k] * eps[k];
  return sigma;
}

double vonMises(const std::array<double, 6>& s) {
  const double d1 = s[0] - s[1], d2 = s[1] - s[2], d3 = s[2] - s[0];
  return std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

std::vector<double> facetNodalAreas(const std::vector<Point>& X) {
  if (X.size() == 3) {
    const double area = 0.5 * norm(cross(minus(X[1], X[0]), minus(X[2], X[0])));
    return {area / 3, area / 3, area / 3};
  }
  TRIBOS_REQUIRE(X.size() == 4, "facet with " << X.size() << " nodes");
  // Bilinear quadrilateral, 2x2 Gauss: weight of node a = sum_q N_a(q) |dX/ds x dX/dt|.
  std::vector<double> w(4, 0.0);
  const int sgn[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int q = 0; q < 4; ++q) {
    const double s = sgn[q][0] * kGauss, t = sgn[q][1] * kGauss;
    Point xs{}, xt{};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        xs[d] += sgn[a][0] * (1 + sgn[a][1] * t) / 4 * X[a][d];
        xt[d] += sgn[a][1] * (1 + sgn[a][0] * s) / 4 * X[a][d];
      }
    const double J = norm(cross(xs, xt));
    for (int a = 0; a < 4; ++a) w[a] += (1 + sgn[a][0] * s) * (1 + sgn[a][1] * t) / 4 * J;
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
  double N[8], dNdxi[8][3];
  for (const Point& xi : hexGaussPoints()) {
    const double det = shapeGradients(type, X, xi, dN);
    hexShape(xi, N, dNdxi);
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) f[3 * a + d] += det * N[a] * b[d];
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
