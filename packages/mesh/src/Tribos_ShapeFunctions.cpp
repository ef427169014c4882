#include "Tribos_ShapeFunctions.hpp"

#include <cmath>
#include <string>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

namespace {

// The corners of [-1,1]^3 (Hex8, Hex20) and of [-1,1]^2 (4- and 8-node
// quadrilaterals), in node order.
const int kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const int kQuadSign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

// The corners joined by each mid-edge node, in node order.
const int kTet10Edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
const int kHex20Edges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
const int kTri6Edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
const int kQuad8Edges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};

// P1 and P2 Lagrange functions on a simplex of dimension dim (triangle or
// tetrahedron) from its barycentric coordinates L_0 = 1 - sum xi, L_k = xi_{k-1}:
// corners L_i (P1) or L_i (2 L_i - 1) (P2), mid-edge nodes 4 L_i L_j.
// grad[k][i] = dL_k / dxi_i.
template <int dim>
void simplexShape(const double* xi, int numEdges, const int (*edges)[2], double N[], double* dN) {
  double L[dim + 1], grad[dim + 1][dim] = {};
  L[0] = 1;
  for (int i = 0; i < dim; ++i) {
    L[0] -= xi[i];
    L[i + 1] = xi[i];
    grad[0][i] = -1;
    grad[i + 1][i] = 1;
  }
  const bool quadratic = numEdges > 0;
  for (int a = 0; a <= dim; ++a) {
    N[a] = quadratic ? L[a] * (2 * L[a] - 1) : L[a];
    for (int i = 0; i < dim; ++i) dN[dim * a + i] = quadratic ? (4 * L[a] - 1) * grad[a][i] : grad[a][i];
  }
  for (int e = 0; e < numEdges; ++e) {
    const int p = edges[e][0], q = edges[e][1], a = dim + 1 + e;
    N[a] = 4 * L[p] * L[q];
    for (int i = 0; i < dim; ++i) dN[dim * a + i] = 4 * (L[q] * grad[p][i] + L[p] * grad[q][i]);
  }
}

// Shape functions on [-1,1]^dim at the nodes p (each coordinate -1, 0 or 1),
// with s_j = 1 + p_j xi_j:
//   multilinear (Hex8, 4-node quadrilateral): N = 2^-dim prod_j s_j;
//   serendipity (Hex20, 8-node quadrilateral):
//     corner:             N = 2^-dim prod_j s_j (sum_j p_j xi_j - (dim - 1)),
//     mid-edge (p_k = 0): N = 2^(1-dim) (1 - xi_k^2) prod_{j != k} s_j.
template <int dim>
void cubeShape(const double* xi, int nodes, const std::array<int, dim>* p, bool serendipity, double N[], double* dN) {
  const double corner = 1.0 / (1 << dim), mid = 2.0 / (1 << dim);
  for (int a = 0; a < nodes; ++a) {
    double s[dim];
    int k = -1;  // the coordinate along the edge of a mid-edge node
    for (int j = 0; j < dim; ++j) {
      s[j] = 1 + p[a][j] * xi[j];
      if (p[a][j] == 0) k = j;
    }
    auto productWithout = [&](int skip1, int skip2) {
      double prod = 1;
      for (int j = 0; j < dim; ++j)
        if (j != skip1 && j != skip2) prod *= s[j];
      return prod;
    };
    if (!serendipity) {
      N[a] = corner * productWithout(-1, -1);
      for (int i = 0; i < dim; ++i) dN[dim * a + i] = corner * p[a][i] * productWithout(i, -1);
    } else if (k < 0) {
      double linear = -(dim - 1);
      for (int j = 0; j < dim; ++j) linear += p[a][j] * xi[j];
      N[a] = corner * productWithout(-1, -1) * linear;
      // d/dxi_i = 2^-dim p_i prod_{j != i} s_j (linear + s_i), by the product rule.
      for (int i = 0; i < dim; ++i) dN[dim * a + i] = corner * p[a][i] * productWithout(i, -1) * (linear + s[i]);
    } else {
      const double bubble = 1 - xi[k] * xi[k];
      N[a] = mid * bubble * productWithout(k, -1);
      for (int i = 0; i < dim; ++i)
        dN[dim * a + i] = i == k ? mid * (-2 * xi[k]) * productWithout(k, -1)
                                 : mid * bubble * p[a][i] * productWithout(k, i);
    }
  }
}

// The reference coordinates of the serendipity nodes: the corners, then the
// midpoints of the edges.
template <int dim, int corners, int edges>
std::array<std::array<int, dim>, corners + edges> serendipityNodes(const int (*sign)[dim], const int (*edge)[2]) {
  std::array<std::array<int, dim>, corners + edges> p{};
  for (int a = 0; a < corners; ++a)
    for (int j = 0; j < dim; ++j) p[a][j] = sign[a][j];
  for (int e = 0; e < edges; ++e)
    for (int j = 0; j < dim; ++j) p[corners + e][j] = (sign[edge[e][0]][j] + sign[edge[e][1]][j]) / 2;
  return p;
}

const auto kHex20Nodes = serendipityNodes<3, 8, 12>(kHexSign, kHex20Edges);
const auto kQuad8Nodes = serendipityNodes<2, 4, 4>(kQuadSign, kQuad8Edges);

// Gauss-Legendre points and weights on [-1,1].
struct GaussRule {
  std::vector<double> x, w;
};
GaussRule gaussLegendre(int n) {
  switch (n) {
    case 2: {
      const double g = 1.0 / std::sqrt(3.0);
      return {{-g, g}, {1.0, 1.0}};
    }
    case 3: return {{-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, {5.0 / 9, 8.0 / 9, 5.0 / 9}};
    case 4: {
      const double r = 2 * std::sqrt(6.0 / 5) / 7;
      const double a = std::sqrt(3.0 / 7 - r), b = std::sqrt(3.0 / 7 + r);
      const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
      return {{-b, -a, a, b}, {wb, wa, wa, wb}};
    }
    case 5: {
      const double r = 2 * std::sqrt(10.0 / 7);
      const double a = std::sqrt(5 - r) / 3, b = std::sqrt(5 + r) / 3;
      const double wa = (322 + 13 * std::sqrt(70.0)) / 900, wb = (322 - 13 * std::sqrt(70.0)) / 900;
      return {{-b, -a, 0.0, a, b}, {wb, wa, 128.0 / 225, wa, wb}};
    }
  }
  throw Error("gaussLegendre: no " + std::to_string(n) + "-point rule");
}

// The tensor product of n-point Gauss rules on [-1,1]^3, x fastest.
std::vector<QuadraturePoint> gaussHex(int n) {
  const GaussRule g = gaussLegendre(n);
  std::vector<QuadraturePoint> q;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) q.push_back({{g.x[i], g.x[j], g.x[k]}, g.w[i] * g.w[j] * g.w[k]});
  return q;
}

// Keast's 5-point rule (degree 3) on the unit tetrahedron of volume 1/6.
std::vector<QuadraturePoint> keast5() {
  const double a = 0.5, b = 1.0 / 6.0;
  return {{{0.25, 0.25, 0.25}, -2.0 / 15.0},
          {{a, b, b}, 3.0 / 40.0},
          {{b, a, b}, 3.0 / 40.0},
          {{b, b, a}, 3.0 / 40.0},
          {{b, b, b}, 3.0 / 40.0}};
}

// The 14-point rule of degree 5 on the unit tetrahedron (Walkington 2000;
// Grundmann and Moeller 1978, (4.5)): two orbits of 4 points with
// barycentric coordinates (1 - 3a, a, a, a) and one of 6 points
// (1/2 - c, 1/2 - c, c, c), weights for the volume 1/6.
std::vector<QuadraturePoint> tet14() {
  const double a1 = 0.31088591926330060980, w1 = 0.018781320953002641800;
  const double a2 = 0.092735250310891226402, w2 = 0.012248840519393658257;
  const double c = 0.045503704125649649492, w3 = 0.0070910034628469110730;
  std::vector<QuadraturePoint> q;
  for (const auto& [a, w] : {std::pair<double, double>{a1, w1}, {a2, w2}}) {
    // Barycentric (L0, L1, L2, L3) = (a, a, a, a) with one of them 1 - 3a; xi = (L1, L2, L3).
    for (int big = 0; big < 4; ++big) {
      double L[4] = {a, a, a, a};
      L[big] = 1 - 3 * a;
      q.push_back({{L[1], L[2], L[3]}, w});
    }
  }
  const double b = 0.5 - c;
  for (const auto& e : kTet10Edges) {  // the two barycentric coordinates b sit on an edge's ends
    double L[4] = {c, c, c, c};
    L[e[0]] = b;
    L[e[1]] = b;
    q.push_back({{L[1], L[2], L[3]}, w3});
  }
  return q;
}

}  // namespace

void referenceShape(Mesh::CellType type, const Point& xi, double N[], double dNdxi[][3]) {
  switch (type) {
    case Mesh::CellType::Tet4:
      simplexShape<3>(xi.data(), 0, kTet10Edges, N, &dNdxi[0][0]);
      return;
    case Mesh::CellType::Tet10:
      simplexShape<3>(xi.data(), 6, kTet10Edges, N, &dNdxi[0][0]);
      return;
    case Mesh::CellType::Hex8:
    case Mesh::CellType::Hex20:
      cubeShape<3>(xi.data(), Mesh::nodesPerCell(type), kHex20Nodes.data(), type == Mesh::CellType::Hex20, N,
                   &dNdxi[0][0]);
      return;
  }
  throw Error("referenceShape: cell type " + std::to_string(static_cast<int>(type)) + " unknown");
}

std::vector<Point> referenceNodes(Mesh::CellType type) {
  std::vector<Point> X;
  switch (type) {
    case Mesh::CellType::Tet4:
    case Mesh::CellType::Tet10:
      X = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      if (type == Mesh::CellType::Tet10)
        for (const auto& e : kTet10Edges)
          X.push_back({(X[e[0]][0] + X[e[1]][0]) / 2, (X[e[0]][1] + X[e[1]][1]) / 2, (X[e[0]][2] + X[e[1]][2]) / 2});
      return X;
    case Mesh::CellType::Hex8:
    case Mesh::CellType::Hex20:
      for (int a = 0; a < Mesh::nodesPerCell(type); ++a)
        X.push_back({double(kHex20Nodes[a][0]), double(kHex20Nodes[a][1]), double(kHex20Nodes[a][2])});
      return X;
  }
  throw Error("referenceNodes: cell type " + std::to_string(static_cast<int>(type)) + " unknown");
}

std::vector<QuadraturePoint> cellQuadrature(Mesh::CellType type) {
  switch (type) {
    case Mesh::CellType::Hex8: return gaussHex(2);
    case Mesh::CellType::Tet10: return tet14();
    case Mesh::CellType::Hex20: return gaussHex(3);
    case Mesh::CellType::Tet4: break;
  }
  throw Error("cellQuadrature: no rule for " + Mesh::cellTypeName(type) + " cells (their strain is constant)");
}

std::vector<QuadraturePoint> accurateQuadrature(Mesh::CellType type) {
  switch (type) {
    case Mesh::CellType::Tet4: return keast5();
    case Mesh::CellType::Hex8: return gaussHex(3);
    case Mesh::CellType::Tet10: return tet14();
    case Mesh::CellType::Hex20: return gaussHex(4);
  }
  throw Error("accurateQuadrature: cell type " + std::to_string(static_cast<int>(type)) + " unknown");
}

void facetShape(int nodes, double s, double t, double N[], double dNds[][2]) {
  const double st[2] = {s, t};
  switch (nodes) {
    case 3: simplexShape<2>(st, 0, kTri6Edges, N, &dNds[0][0]); return;
    case 6: simplexShape<2>(st, 3, kTri6Edges, N, &dNds[0][0]); return;
    case 4:
    case 8: cubeShape<2>(st, nodes, kQuad8Nodes.data(), nodes == 8, N, &dNds[0][0]); return;
  }
  throw Error("a facet with " + std::to_string(nodes) + " nodes (3, 4, 6 or 8 expected)");
}

std::vector<FacetQuadraturePoint> facetQuadrature(int nodes) {
  switch (nodes) {
    case 3: return {{1.0 / 3, 1.0 / 3, 0.5}};
    case 6: {
      // Radon's 7-point rule (degree 5) on the triangle of area 1/2: the
      // centroid and two orbits (a, a, 1 - 2a) of barycentric coordinates.
      const double r15 = std::sqrt(15.0);
      const double a1 = (6 - r15) / 21, w1 = (155 - r15) / 2400;
      const double a2 = (6 + r15) / 21, w2 = (155 + r15) / 2400;
      return {{1.0 / 3, 1.0 / 3, 9.0 / 80}, {a1, a1, w1}, {1 - 2 * a1, a1, w1}, {a1, 1 - 2 * a1, w1},
              {a2, a2, w2},                 {1 - 2 * a2, a2, w2},               {a2, 1 - 2 * a2, w2}};
    }
    case 4: {
      const double g = 1.0 / std::sqrt(3.0);
      std::vector<FacetQuadraturePoint> q;
      for (const auto& c : kQuadSign) q.push_back({c[0] * g, c[1] * g, 1.0});  // at the corners' sides
      return q;
    }
    case 8: {
      const GaussRule g = gaussLegendre(3);
      std::vector<FacetQuadraturePoint> q;
      for (size_t j = 0; j < g.x.size(); ++j)
        for (size_t i = 0; i < g.x.size(); ++i) q.push_back({g.x[i], g.x[j], g.w[i] * g.w[j]});
      return q;
    }
  }
  throw Error("a facet with " + std::to_string(nodes) + " nodes (3, 4, 6 or 8 expected)");
}

std::vector<FacetQuadraturePoint> triangleQuadrature(int degree) {
  TRIBOS_REQUIRE(degree >= 0 && degree <= 8, "triangleQuadrature: no rule of degree " << degree);
  if (degree <= 5) return facetQuadrature(6);
  // The square [0,1]^2 collapsed onto the triangle, (u, v) -> (u, v (1 - u)),
  // with the Jacobian 1 - u: a polynomial of degree p on the triangle is one
  // of degree p + 1 in u and p in v, which 5 Gauss points integrate exactly
  // for p <= 8.
  const GaussRule g = gaussLegendre(5);
  std::vector<FacetQuadraturePoint> q;
  for (size_t i = 0; i < g.x.size(); ++i) {
    const double u = (1 + g.x[i]) / 2;
    for (size_t j = 0; j < g.x.size(); ++j) {
      const double v = (1 + g.x[j]) / 2;
      q.push_back({u, v * (1 - u), g.w[i] * g.w[j] * (1 - u) / 4});
    }
  }
  return q;
}

void isoparametricJacobian(const double dNdxi[][3], const Point* X, int npc, double J[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) J[i][j] = 0;
  for (int a = 0; a < npc; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) J[i][j] += dNdxi[a][i] * X[a][j];
}

double determinant3(const double J[3][3]) {
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

}  // namespace Fem
}  // namespace Tribos
