// The second-order elements Tet10 and Hex20 at the element level: shape
// functions against an independent Lagrange basis (a Vandermonde system on
// Gmsh's nodes), gradients against finite differences, the quadrature rules'
// degrees, the stiffness against an independent formula and quadrature, the
// patch test on small distorted and curved meshes, the rigid-body kernel,
// the consistent surface and volume loads, the stress average and the
// refusal of inverted cells.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <string>

#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"
#include "FemTestAlgebra.hpp"

namespace {

using Tribos::Fem::Test::gaussLegendre;
using Tribos::Fem::Test::symmetricEigenvalues;

using namespace Tribos;
using Fem::Point;
using Mesh::CellType;

// ---------------------------------------------------------------------------
// Gmsh's node orderings, written out here independently of the library:
// Tet10 mid-edge nodes 4 = 0-1, 5 = 1-2, 6 = 2-0, 7 = 3-0, 8 = 3-2, 9 = 3-1;
// Hex20 mid-edge nodes 8 = 0-1, 9 = 0-3, 10 = 0-4, 11 = 1-2, 12 = 1-5,
// 13 = 2-3, 14 = 2-6, 15 = 3-7, 16 = 4-5, 17 = 4-7, 18 = 5-6, 19 = 6-7.
const int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
const int kHexEdges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                              {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
const std::vector<Point> kTet10Nodes = {{0, 0, 0},     {1, 0, 0},   {0, 1, 0},   {0, 0, 1},   {0.5, 0, 0},
                                        {0.5, 0.5, 0}, {0, 0.5, 0}, {0, 0, 0.5}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
const std::vector<Point> kHex20Nodes = {
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
    {-1, 1, 1},   {0, -1, -1}, {-1, 0, -1}, {-1, -1, 0}, {1, 0, -1},  {1, -1, 0}, {0, 1, -1},
    {1, 1, 0},    {-1, 1, 0},  {0, -1, 1},  {-1, 0, 1},  {1, 0, 1},   {0, 1, 1}};

const std::vector<Point>& gmshNodes(CellType type) { return type == CellType::Tet10 ? kTet10Nodes : kHex20Nodes; }

// ---------------------------------------------------------------------------
// Dense linear algebra of the test.

// Solves A X = B (A n x n, B n x m, row-major) by Gaussian elimination with
// partial pivoting; returns X.
std::vector<double> solveDense(std::vector<double> A, int n, std::vector<double> B, int m) {
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A[i * n + k]) > std::abs(A[p * n + k])) p = i;
    if (p != k) {
      for (int j = 0; j < n; ++j) std::swap(A[k * n + j], A[p * n + j]);
      for (int j = 0; j < m; ++j) std::swap(B[k * m + j], B[p * m + j]);
    }
    for (int i = k + 1; i < n; ++i) {
      const double f = A[i * n + k] / A[k * n + k];
      if (f == 0) continue;
      for (int j = k; j < n; ++j) A[i * n + j] -= f * A[k * n + j];
      for (int j = 0; j < m; ++j) B[i * m + j] -= f * B[k * m + j];
    }
  }
  for (int k = n - 1; k >= 0; --k)
    for (int j = 0; j < m; ++j) {
      double s = B[k * m + j];
      for (int i = k + 1; i < n; ++i) s -= A[k * n + i] * B[i * m + j];
      B[k * m + j] = s / A[k * n + k];
    }
  return B;
}


double maxAbs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double maxAbsDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

// ---------------------------------------------------------------------------
// An independent nodal basis: the Lagrange functions of a space of monomials
// x^p y^q z^r on given nodes, from the inverse of the Vandermonde matrix.
class LagrangeBasis {
 public:
  LagrangeBasis(std::vector<std::array<int, 3>> powers, const std::vector<Point>& nodes)
      : powers_(std::move(powers)), n_(static_cast<int>(nodes.size())) {
    std::vector<double> V(n_ * n_), I(n_ * n_, 0.0);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) V[i * n_ + j] = monomial(j, nodes[i]);
      I[i * n_ + i] = 1;
    }
    C_ = solveDense(V, n_, I, n_);  // C[j][a]: coefficient of monomial j in N_a
  }
  // The space of Tet10 (P2) and of Hex20 (serendipity: exponents <= 2, at most one of them 2).
  static LagrangeBasis of(CellType type) {
    std::vector<std::array<int, 3>> powers;
    for (int p = 0; p <= 2; ++p)
      for (int q = 0; q <= 2; ++q)
        for (int r = 0; r <= 2; ++r) {
          const bool keep = type == CellType::Tet10 ? p + q + r <= 2 : (p == 2) + (q == 2) + (r == 2) <= 1;
          if (keep) powers.push_back({p, q, r});
        }
    return LagrangeBasis(powers, gmshNodes(type));
  }
  int size() const { return n_; }
  // N[a] and dN[3 a + i] = dN_a / dx_i at x.
  void eval(const Point& x, double* N, double* dN) const {
    for (int a = 0; a < n_; ++a) {
      N[a] = 0;
      for (int i = 0; i < 3; ++i) dN[3 * a + i] = 0;
    }
    for (int j = 0; j < n_; ++j) {
      const double m = monomial(j, x);
      double g[3];
      for (int i = 0; i < 3; ++i) g[i] = derivative(j, i, x);
      for (int a = 0; a < n_; ++a) {
        N[a] += C_[j * n_ + a] * m;
        for (int i = 0; i < 3; ++i) dN[3 * a + i] += C_[j * n_ + a] * g[i];
      }
    }
  }

 private:
  double monomial(int j, const Point& x) const {
    return std::pow(x[0], powers_[j][0]) * std::pow(x[1], powers_[j][1]) * std::pow(x[2], powers_[j][2]);
  }
  double derivative(int j, int i, const Point& x) const {
    const int p = powers_[j][i];
    if (p == 0) return 0;
    double v = p * std::pow(x[i], p - 1);
    for (int k = 0; k < 3; ++k)
      if (k != i) v *= std::pow(x[k], powers_[j][k]);
    return v;
  }
  std::vector<std::array<int, 3>> powers_;
  int n_;
  std::vector<double> C_;
};

// ---------------------------------------------------------------------------
// Quadrature of the test: Gauss-Legendre by Newton's method
// (FemTestAlgebra.hpp), tensor products on [-1,1]^3, and collapsed (Duffy)
// products on the unit tetrahedron.

std::vector<Fem::QuadraturePoint> testHexRule(int n) {
  std::vector<double> x, w;
  gaussLegendre(n, x, w);
  std::vector<Fem::QuadraturePoint> q;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) q.push_back({{x[i], x[j], x[k]}, w[i] * w[j] * w[k]});
  return q;
}

// xi = u, eta = v (1 - u), zeta = w (1 - u)(1 - v) on [0,1]^3: exact for
// polynomials of degree 2n - 3 on the tetrahedron.
std::vector<Fem::QuadraturePoint> testTetRule(int n) {
  std::vector<double> x, w;
  gaussLegendre(n, x, w);
  std::vector<Fem::QuadraturePoint> q;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double u = (1 + x[i]) / 2, v = (1 + x[j]) / 2, s = (1 + x[k]) / 2;
        q.push_back({{u, v * (1 - u), s * (1 - u) * (1 - v)},
                     w[i] * w[j] * w[k] / 8 * (1 - u) * (1 - u) * (1 - v)});
      }
  return q;
}

std::vector<Fem::QuadraturePoint> testRule(CellType type, int n) {
  return type == CellType::Tet10 ? testTetRule(n) : testHexRule(n);
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// ---------------------------------------------------------------------------
// The independent element: the map x = sum N_a X_a of the Lagrange basis, and
// the stiffness from the isotropic formula
//   K[3a+i][3b+j] = int lambda N_a,i N_b,j + mu N_a,j N_b,i + mu delta_ij grad N_a . grad N_b dV.
struct MapPoint {
  std::vector<double> N;
  std::vector<std::array<double, 3>> dNdx;
  double detJ;
  Point x;
};

MapPoint mapAt(const LagrangeBasis& basis, const std::vector<Point>& X, const Point& xi) {
  const int n = basis.size();
  MapPoint m;
  m.N.resize(n);
  std::vector<double> dNdxi(3 * n);
  basis.eval(xi, m.N.data(), dNdxi.data());
  double J[3][3] = {};  // J[j][i] = dx_j / dxi_i
  m.x = {0, 0, 0};
  for (int a = 0; a < n; ++a)
    for (int j = 0; j < 3; ++j) {
      m.x[j] += m.N[a] * X[a][j];
      for (int i = 0; i < 3; ++i) J[j][i] += X[a][j] * dNdxi[3 * a + i];
    }
  // dN/dx solves J^T g = dN/dxi; Cramer's rule column by column.
  auto det3 = [](const double M[3][3]) {
    return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
           M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  };
  m.detJ = det3(J);
  m.dNdx.resize(n);
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < 3; ++k) {
      double M[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) M[i][j] = k == j ? dNdxi[3 * a + i] : J[j][i];  // rows: equations i
      m.dNdx[a][k] = det3(M) / m.detJ;
    }
  return m;
}

std::vector<double> independentStiffness(CellType type, const std::vector<Point>& X, const Fem::Material& mat,
                                         const std::vector<Fem::QuadraturePoint>& rule) {
  const LagrangeBasis basis = LagrangeBasis::of(type);
  const int n = basis.size(), m = 3 * n;
  const double lambda = mat.lameLambda(), mu = mat.lameMu();
  std::vector<double> K(m * m, 0.0);
  for (const auto& q : rule) {
    const MapPoint p = mapAt(basis, X, q.xi);
    const double w = q.weight * p.detJ;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const auto &ga = p.dNdx[a], &gb = p.dNdx[b];
        const double dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            K[(3 * a + i) * m + 3 * b + j] += w * (lambda * ga[i] * gb[j] + mu * ga[j] * gb[i] + (i == j ? mu * dot : 0));
      }
  }
  return K;
}

double independentVolume(CellType type, const std::vector<Point>& X) {
  const LagrangeBasis basis = LagrangeBasis::of(type);
  double V = 0;
  for (const auto& q : testRule(type, 10)) V += q.weight * mapAt(basis, X, q.xi).detJ;
  return V;
}

// ---------------------------------------------------------------------------
// Test cells.

// The cell whose corners are `corners` (straight edges: mid-edge nodes at
// the middles), in the node order of `type`.
std::vector<Point> straightCell(CellType type, const std::vector<Point>& corners) {
  std::vector<Point> X = corners;
  const auto addMid = [&](int p, int q) {
    X.push_back({(X[p][0] + X[q][0]) / 2, (X[p][1] + X[q][1]) / 2, (X[p][2] + X[q][2]) / 2});
  };
  if (type == CellType::Tet10)
    for (const auto& e : kTetEdges) addMid(e[0], e[1]);
  else
    for (const auto& e : kHexEdges) addMid(e[0], e[1]);
  return X;
}

// Moves every mid-edge node by up to `amount` in each coordinate (fixed seed).
std::vector<Point> curved(std::vector<Point> X, int corners, double amount, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> r(-amount, amount);
  for (size_t a = corners; a < X.size(); ++a)
    for (double& c : X[a]) c += r(gen);
  return X;
}

const std::vector<Point> kTetCorners = {{0.1, -0.2, 0.05}, {1.3, 0.2, -0.1}, {0.3, 1.1, 0.2}, {-0.2, 0.4, 0.9}};

// A sheared, scaled and shifted cube: a parallelepiped (affine map).
std::vector<Point> parallelepipedCorners() {
  const double A[3][3] = {{1.2, 0.3, -0.2}, {0.1, 0.9, 0.25}, {-0.15, 0.2, 1.1}};
  std::vector<Point> c;
  for (const Point& r : std::vector<Point>(kHex20Nodes.begin(), kHex20Nodes.begin() + 8)) {
    Point x{0.4, -0.3, 0.2};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) x[i] += A[i][j] * r[j];
    c.push_back(x);
  }
  return c;
}

// A hexahedron with every corner moved (trilinear, not affine).
std::vector<Point> distortedHexCorners() {
  std::vector<Point> c = parallelepipedCorners();
  const double move[8][3] = {{0.1, -0.05, 0.08}, {-0.12, 0.07, 0.02}, {0.05, 0.1, -0.09}, {-0.04, -0.08, 0.11},
                             {0.09, 0.03, -0.1},  {-0.06, -0.1, 0.05}, {0.12, -0.02, 0.07}, {-0.1, 0.09, -0.03}};
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) c[a][d] += move[a][d];
  return c;
}

double relDiff(const std::vector<double>& a, const std::vector<double>& b) { return maxAbsDiff(a, b) / maxAbs(b); }

bool messageHas(const std::string& message, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (message.find(w) == std::string::npos) return false;
  return true;
}

// ---------------------------------------------------------------------------
// Small meshes of distorted and curved quadratic cells on [0,1]^3: the nodes
// sit on a grid of half cells (index g, coordinates g / (2 n)); a node off
// the boundary moves by up to `amount` half cells in every direction, a node
// on the boundary within the boundary's plane(s) only, so the boundary stays
// flat while the cells' edges curve.
struct TestMesh {
  CellType type;
  std::array<int, 3> cells;
  std::vector<Point> x;
  std::vector<std::array<int, 3>> grid;  // per node
  std::vector<std::vector<int>> connectivity;
  bool onBoundary(int node) const {
    for (int d = 0; d < 3; ++d)
      if (grid[node][d] == 0 || grid[node][d] == 2 * cells[d]) return true;
    return false;
  }
};

TestMesh buildMesh(CellType type, std::array<int, 3> cells, double amount, unsigned seed) {
  TestMesh mesh{type, cells, {}, {}, {}};
  std::map<std::array<int, 3>, int> id;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> r(-amount, amount);
  auto node = [&](const std::array<int, 3>& g) {
    auto it = id.find(g);
    if (it != id.end()) return it->second;
    Point x;
    for (int d = 0; d < 3; ++d) {
      const double h = 1.0 / (2 * cells[d]);
      const bool boundary = g[d] == 0 || g[d] == 2 * cells[d];
      x[d] = g[d] * h + (boundary ? 0.0 : r(gen) * h);
    }
    mesh.x.push_back(x);
    mesh.grid.push_back(g);
    return id[g] = static_cast<int>(mesh.x.size()) - 1;
  };
  auto mid = [](const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::array<int, 3>{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
  };
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) {
        std::vector<std::array<int, 3>> corner;
        if (type == CellType::Hex20) {
          for (int a = 0; a < 8; ++a)
            corner.push_back({2 * i + 1 + int(kHex20Nodes[a][0]), 2 * j + 1 + int(kHex20Nodes[a][1]),
                              2 * k + 1 + int(kHex20Nodes[a][2])});
          for (const auto& e : kHexEdges) corner.push_back(mid(corner[e[0]], corner[e[1]]));
          std::vector<int> c;
          for (const auto& g : corner) c.push_back(node(g));
          mesh.connectivity.push_back(c);
          continue;
        }
        for (const auto& p : perms) {  // Kuhn tetrahedra, positively oriented
          std::array<int, 3> g{2 * i, 2 * j, 2 * k};
          corner = {g};
          for (int s = 0; s < 3; ++s) {
            g[p[s]] += 2;
            corner.push_back(g);
          }
          Point e[3];
          for (int s = 0; s < 3; ++s)
            for (int d = 0; d < 3; ++d) e[s][d] = corner[s + 1][d] - corner[0][d];
          const double vol = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          if (vol < 0) std::swap(corner[2], corner[3]);
          for (const auto& ed : kTetEdges) corner.push_back(mid(corner[ed[0]], corner[ed[1]]));
          std::vector<int> c;
          for (const auto& gg : corner) c.push_back(node(gg));
          mesh.connectivity.push_back(c);
        }
      }
  return mesh;
}

std::vector<Point> cellNodes(const TestMesh& mesh, int c) {
  std::vector<Point> X;
  for (int n : mesh.connectivity[c]) X.push_back(mesh.x[n]);
  return X;
}

// The assembled stiffness (dense).
std::vector<double> assemble(const TestMesh& mesh, const Fem::Material& mat) {
  const int m = 3 * static_cast<int>(mesh.x.size());
  std::vector<double> K(static_cast<size_t>(m) * m, 0.0);
  for (size_t c = 0; c < mesh.connectivity.size(); ++c) {
    const auto& nodes = mesh.connectivity[c];
    const int ne = 3 * static_cast<int>(nodes.size());
    const auto Ke = Fem::elementStiffness(mesh.type, cellNodes(mesh, static_cast<int>(c)), mat);
    for (int i = 0; i < ne; ++i)
      for (int j = 0; j < ne; ++j)
        K[static_cast<size_t>(3 * nodes[i / 3] + i % 3) * m + 3 * nodes[j / 3] + j % 3] += Ke[i * ne + j];
  }
  return K;
}

// The linear field of the patch test and its constant stress.
const double kA[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, 5e-4, 2.5e-4}, {4e-4, -2e-4, -6e-4}};
const Point kC = {1e-3, -2e-3, 5e-4};
Point linearField(const Point& x) {
  Point u = kC;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) u[i] += kA[i][j] * x[j];
  return u;
}
// sigma = lambda tr(eps) I + 2 mu eps, eps = sym(A).
std::array<std::array<double, 3>, 3> linearStress(const Fem::Material& mat) {
  std::array<std::array<double, 3>, 3> s{};
  const double tr = kA[0][0] + kA[1][1] + kA[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s[i][j] = mat.lameMu() * (kA[i][j] + kA[j][i]) + (i == j ? mat.lameLambda() * tr : 0);
  return s;
}

// Interior nodes free, boundary nodes prescribed to the linear field: the
// solution must be the linear field; and K u must equal the consistent
// boundary forces of its constant stress, node by node.
void patchTest(CellType type, std::array<int, 3> cells, Teuchos::FancyOStream& out, bool& success) {
  const TestMesh mesh = buildMesh(type, cells, 0.15, 11);
  const Fem::Material mat{2.1e11, 0.3};
  const int nn = static_cast<int>(mesh.x.size()), m = 3 * nn;
  const auto K = assemble(mesh, mat);
  std::vector<double> uExact(m);
  for (int a = 0; a < nn; ++a) {
    const Point u = linearField(mesh.x[a]);
    for (int d = 0; d < 3; ++d) uExact[3 * a + d] = u[d];
  }
  std::vector<int> freeDofs;
  for (int a = 0; a < nn; ++a)
    if (!mesh.onBoundary(a))
      for (int d = 0; d < 3; ++d) freeDofs.push_back(3 * a + d);
  const int nf = static_cast<int>(freeDofs.size());
  std::vector<double> Kff(static_cast<size_t>(nf) * nf), rhs(nf, 0.0);
  std::vector<char> isFree(m, 0);
  for (int f : freeDofs) isFree[f] = 1;
  for (int i = 0; i < nf; ++i) {
    for (int j = 0; j < nf; ++j) Kff[i * nf + j] = K[static_cast<size_t>(freeDofs[i]) * m + freeDofs[j]];
    for (int j = 0; j < m; ++j)
      if (!isFree[j]) rhs[i] -= K[static_cast<size_t>(freeDofs[i]) * m + j] * uExact[j];
  }
  const auto uFree = solveDense(Kff, nf, rhs, 1);
  double err = 0;
  for (int i = 0; i < nf; ++i) err = std::max(err, std::abs(uFree[i] - uExact[freeDofs[i]]));
  const double relErr = err / maxAbs(uExact);
  out << Mesh::cellTypeName(type) << " patch test: " << mesh.connectivity.size() << " cells, " << nn << " nodes, "
      << nf / 3 << " free: max |u - u_exact| / max |u_exact| = " << relErr << "\n";
  TEST_ASSERT(nf > 0);
  TEST_COMPARE(relErr, <, 1e-12);

  // K u_exact = f: the traction sigma n on every boundary facet (the box's
  // faces stay flat), integrated with the facets' consistent loads.
  const auto sigma = linearStress(mat);
  std::vector<double> f(m, 0.0);
  int boundaryFacets = 0;
  for (size_t c = 0; c < mesh.connectivity.size(); ++c)
    for (const auto& local : Mesh::detail::cellFaces(type)) {
      const int corners = type == CellType::Tet10 ? 3 : 4;
      for (int d = 0; d < 3; ++d)
        for (int side : {0, 2 * cells[d]}) {
          bool on = true;
          for (int k = 0; k < corners; ++k) on = on && mesh.grid[mesh.connectivity[c][local[k]]][d] == side;
          if (!on) continue;
          ++boundaryFacets;
          Point t;
          for (int i = 0; i < 3; ++i) t[i] = sigma[i][d] * (side == 0 ? -1 : 1);
          std::vector<Point> X;
          for (int ln : local) X.push_back(mesh.x[mesh.connectivity[c][ln]]);
          const auto fe = Fem::facetTractionForces(X, t);
          for (size_t a = 0; a < local.size(); ++a)
            for (int i = 0; i < 3; ++i) f[3 * mesh.connectivity[c][local[a]] + i] += fe[3 * a + i];
        }
    }
  std::vector<double> Ku(m, 0.0);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) Ku[i] += K[static_cast<size_t>(i) * m + j] * uExact[j];
  const double relRes = relDiff(Ku, f);
  out << "  " << boundaryFacets << " boundary facets: max |K u - f| / max |f| = " << relRes << "\n";
  TEST_COMPARE(relRes, <, 1e-12);
}

// The six rigid-body motions of the cell's nodes.
std::vector<std::vector<double>> rigidModes(const std::vector<Point>& X) {
  std::vector<std::vector<double>> modes;
  for (int k = 0; k < 6; ++k) {
    std::vector<double> r;
    for (const Point& x : X) {
      const Point v = Fem::rigidBodyMode(k, x);
      r.insert(r.end(), v.begin(), v.end());
    }
    modes.push_back(r);
  }
  return modes;
}

void kernelTest(CellType type, const std::vector<Point>& X, const std::string& what, Teuchos::FancyOStream& out,
                bool& success) {
  const Fem::Material mat{2.1e11, 0.3};
  const auto K = Fem::elementStiffness(type, X, mat);
  const int m = 3 * static_cast<int>(X.size());
  const double kmax = maxAbs(K);
  double worst = 0, asym = 0;
  for (const auto& r : rigidModes(X)) {
    std::vector<double> Kr(m, 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) Kr[i] += K[i * m + j] * r[j];
    worst = std::max(worst, maxAbs(Kr) / (kmax * maxAbs(r)));
  }
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) asym = std::max(asym, std::abs(K[i * m + j] - K[j * m + i]));
  const auto lambda = symmetricEigenvalues(K, m);
  const double top = lambda.back();
  int zero = 0;
  for (double l : lambda) zero += std::abs(l) < 1e-10 * top;
  out << Mesh::cellTypeName(type) << " " << what << ": max |K r| / (max |K| max |r|) = " << worst
      << ", |K - K'| / max |K| = " << asym / kmax << ", eigenvalues: " << zero << " below 1e-10 lambda_max, "
      << "lambda_6 / lambda_max = " << lambda[5] / top << ", lambda_7 / lambda_max = " << lambda[6] / top << "\n";
  TEST_COMPARE(worst, <, 1e-12);
  TEST_COMPARE(asym, <=, 1e-14 * kmax);
  TEST_EQUALITY(zero, 6);
  TEST_COMPARE(lambda[6], >, 1e-6 * top);  // rank 3n - 6: no spurious zero-energy mode
}

}  // namespace

// ---------------------------------------------------------------------------

TEUCHOS_UNIT_TEST(QuadraticMesh, CellTypes) {
  TEST_EQUALITY(Mesh::nodesPerCell(CellType::Tet10), 10);
  TEST_EQUALITY(Mesh::nodesPerCell(CellType::Hex20), 20);
  for (CellType t : {CellType::Tet4, CellType::Hex8, CellType::Tet10, CellType::Hex20})
    TEST_ASSERT(Mesh::cellTypeFromName(Mesh::cellTypeName(t)) == t);
  TEST_EQUALITY(Mesh::cellTypeName(CellType::Tet10), std::string("Tet10"));
  TEST_EQUALITY(Mesh::cellTypeName(CellType::Hex20), std::string("Hex20"));
  TEST_ASSERT(Mesh::isSecondOrder(CellType::Tet10) && Mesh::isSecondOrder(CellType::Hex20));
  TEST_ASSERT(!Mesh::isSecondOrder(CellType::Tet4) && !Mesh::isSecondOrder(CellType::Hex8));
  try {
    Mesh::cellTypeFromName("Tet20");
    TEST_ASSERT(false);
  } catch (const Error& e) {
    out << e.what() << "\n";
    TEST_ASSERT(messageHas(e.what(), {"Tet20", "Tet4, Hex8, Tet10, Hex20"}));
  }
}

// The faces of the reference cells: the corners of the first-order faces,
// then each edge's middle, in Gmsh's 6-node triangle / 8-node quadrilateral order.
TEUCHOS_UNIT_TEST(QuadraticMesh, CellFaces) {
  for (CellType t : {CellType::Tet10, CellType::Hex20}) {
    const CellType linear = t == CellType::Tet10 ? CellType::Tet4 : CellType::Hex8;
    const auto& faces = Mesh::detail::cellFaces(t);
    const auto& linearFaces = Mesh::detail::cellFaces(linear);
    const auto& X = gmshNodes(t);
    TEST_EQUALITY(faces.size(), linearFaces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
      const size_t corners = linearFaces[f].size();
      TEST_EQUALITY(faces[f].size(), 2 * corners);
      for (size_t k = 0; k < corners; ++k) {
        TEST_EQUALITY(faces[f][k], linearFaces[f][k]);
        const Point& p = X[faces[f][k]];
        const Point& q = X[faces[f][(k + 1) % corners]];
        const Point& mid = X[faces[f][corners + k]];
        for (int d = 0; d < 3; ++d) TEST_EQUALITY(mid[d], (p[d] + q[d]) / 2);
      }
    }
  }
}

TEUCHOS_UNIT_TEST(QuadraticShape, KroneckerPartitionOfUnityAndIndependentBasis) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> r(0, 1);
  for (CellType t : {CellType::Tet10, CellType::Hex20}) {
    const int n = Mesh::nodesPerCell(t);
    const auto& nodes = gmshNodes(t);
    const auto ref = Fem::referenceNodes(t);
    TEST_EQUALITY(static_cast<int>(ref.size()), n);
    for (int a = 0; a < n; ++a)
      for (int d = 0; d < 3; ++d) TEST_EQUALITY(ref[a][d], nodes[a][d]);
    double kron = 0;
    for (int b = 0; b < n; ++b) {
      const auto N = Fem::shapeFunctions(t, nodes[b]);
      for (int a = 0; a < n; ++a) kron = std::max(kron, std::abs(N[a] - (a == b ? 1.0 : 0.0)));
    }
    const LagrangeBasis basis = LagrangeBasis::of(t);
    double unity = 0, gradSum = 0, linear = 0, vsBasis = 0, gradVsBasis = 0;
    for (int k = 0; k < 50; ++k) {
      Point xi{r(gen), r(gen), r(gen)};
      if (t == CellType::Tet10) {
        const double s = xi[0] + xi[1] + xi[2];
        if (s > 1)
          for (double& c : xi) c /= 1.5 * s;
      } else {
        for (double& c : xi) c = 2 * c - 1;
      }
      double N[Fem::kMaxNodesPerCell], dN[Fem::kMaxNodesPerCell][3], Nb[Fem::kMaxNodesPerCell],
          dNb[Fem::kMaxNodesPerCell][3];
      Fem::referenceShape(t, xi, N, dN);
      basis.eval(xi, Nb, &dNb[0][0]);
      double sum = 0, g[3] = {0, 0, 0};
      Point x{0, 0, 0};
      for (int a = 0; a < n; ++a) {
        sum += N[a];
        for (int d = 0; d < 3; ++d) {
          g[d] += dN[a][d];
          x[d] += N[a] * nodes[a][d];
          gradVsBasis = std::max(gradVsBasis, std::abs(dN[a][d] - dNb[a][d]));
        }
        vsBasis = std::max(vsBasis, std::abs(N[a] - Nb[a]));
      }
      unity = std::max(unity, std::abs(sum - 1));
      for (int d = 0; d < 3; ++d) {
        gradSum = std::max(gradSum, std::abs(g[d]));
        linear = std::max(linear, std::abs(x[d] - xi[d]));
      }
    }
    out << Mesh::cellTypeName(t) << ": |N_a(x_b) - delta_ab| " << kron << ", |sum N - 1| " << unity
        << ", |sum grad N| " << gradSum << ", |sum N_a x_a - x| " << linear << ", vs the Vandermonde basis: N "
        << vsBasis << ", grad N " << gradVsBasis << "\n";
    TEST_COMPARE(kron, <, 1e-15);
    TEST_COMPARE(unity, <, 1e-14);
    TEST_COMPARE(gradSum, <, 1e-13);
    TEST_COMPARE(linear, <, 1e-14);
    TEST_COMPARE(vsBasis, <, 1e-12);
    TEST_COMPARE(gradVsBasis, <, 1e-12);
  }
}

// dN/dx and det J of curved cells against central differences of N(xi) and
// x(xi): dN_a/dxi_i = sum_j dN_a/dx_j dx_j/dxi_i.
TEUCHOS_UNIT_TEST(QuadraticShape, GradientsAgainstFiniteDifferences) {
  const std::vector<std::pair<CellType, std::vector<Point>>> cells = {
      {CellType::Tet10, curved(straightCell(CellType::Tet10, kTetCorners), 4, 0.08, 1)},
      {CellType::Hex20, curved(straightCell(CellType::Hex20, distortedHexCorners()), 8, 0.1, 2)}};
  const double h = 1e-5;
  for (const auto& [t, X] : cells) {
    const int n = Mesh::nodesPerCell(t);
    const Point xi = t == CellType::Tet10 ? Point{0.2, 0.3, 0.15} : Point{0.3, -0.45, 0.6};
    std::vector<double> dN;
    const double det = Fem::shapeGradients(t, X, xi, dN);
    double dxdxi[3][3], worst = 0, scale = 0;  // dxdxi[j][i] = dx_j / dxi_i
    std::vector<std::array<double, 3>> dNdxi(n);
    for (int i = 0; i < 3; ++i) {
      Point p = xi, m = xi;
      p[i] += h;
      m[i] -= h;
      const auto Np = Fem::shapeFunctions(t, p), Nm = Fem::shapeFunctions(t, m);
      for (int j = 0; j < 3; ++j) {
        dxdxi[j][i] = 0;
        for (int a = 0; a < n; ++a) dxdxi[j][i] += (Np[a] - Nm[a]) / (2 * h) * X[a][j];
      }
      for (int a = 0; a < n; ++a) dNdxi[a][i] = (Np[a] - Nm[a]) / (2 * h);
    }
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) {
        double chain = 0;
        for (int j = 0; j < 3; ++j) chain += dN[3 * a + j] * dxdxi[j][i];
        worst = std::max(worst, std::abs(chain - dNdxi[a][i]));
        scale = std::max(scale, std::abs(dNdxi[a][i]));
      }
    const double detFd = dxdxi[0][0] * (dxdxi[1][1] * dxdxi[2][2] - dxdxi[1][2] * dxdxi[2][1]) -
                         dxdxi[0][1] * (dxdxi[1][0] * dxdxi[2][2] - dxdxi[1][2] * dxdxi[2][0]) +
                         dxdxi[0][2] * (dxdxi[1][0] * dxdxi[2][1] - dxdxi[1][1] * dxdxi[2][0]);
    out << Mesh::cellTypeName(t) << ": max |grad N . dx/dxi - dN/dxi (FD)| / max |dN/dxi| = " << worst / scale
        << ", det J " << det << " vs FD " << detFd << "\n";
    TEST_COMPARE(worst / scale, <, 1e-8);
    TEST_COMPARE(std::abs(det - detFd) / det, <, 1e-8);
  }
}

// Each rule integrates the monomials of its degree exactly: on the unit
// tetrahedron int x^p y^q z^r = p! q! r! / (p + q + r + 3)!, on [-1,1]^3 a
// product of int x^p = 2 / (p + 1) (p even); and fails the next degree.
TEUCHOS_UNIT_TEST(Quadrature, Degrees) {
  auto tetError = [](const std::vector<Fem::QuadraturePoint>& rule, int degree) {
    double worst = 0;
    for (int p = 0; p <= degree; ++p)
      for (int q = 0; p + q <= degree; ++q) {
        const int r = degree - p - q;
        double sum = 0;
        for (const auto& x : rule) sum += x.weight * std::pow(x.xi[0], p) * std::pow(x.xi[1], q) * std::pow(x.xi[2], r);
        const double exact = factorial(p) * factorial(q) * factorial(r) / factorial(p + q + r + 3);
        worst = std::max(worst, std::abs(sum - exact) / exact);
      }
    return worst;
  };
  auto cubeError = [](const std::vector<Fem::QuadraturePoint>& rule, int degree) {  // every exponent <= degree
    double worst = 0;
    for (int p = 0; p <= degree; ++p)
      for (int q = 0; q <= degree; ++q)
        for (int r = 0; r <= degree; ++r) {
          double sum = 0;
          for (const auto& x : rule)
            sum += x.weight * std::pow(x.xi[0], p) * std::pow(x.xi[1], q) * std::pow(x.xi[2], r);
          const double exact = (p % 2 || q % 2 || r % 2) ? 0.0 : 8.0 / ((p + 1) * (q + 1) * (r + 1));
          worst = std::max(worst, std::abs(sum - exact));
        }
    return worst;
  };
  double tet = 0;
  for (int d = 0; d <= 5; ++d) tet = std::max(tet, tetError(Fem::cellQuadrature(CellType::Tet10), d));
  const double tet6 = tetError(Fem::cellQuadrature(CellType::Tet10), 6);
  out << "Tet10 rule (" << Fem::cellQuadrature(CellType::Tet10).size() << " points): degree <= 5 error " << tet
      << ", degree 6 error " << tet6 << "\n";
  TEST_COMPARE(tet, <, 1e-14);
  TEST_COMPARE(tet6, >, 1e-6);
  double weights = 0, negative = 0;
  for (const auto& q : Fem::cellQuadrature(CellType::Tet10)) weights += q.weight, negative += q.weight <= 0;
  TEST_FLOATING_EQUALITY(weights, 1.0 / 6, 1e-15);
  TEST_EQUALITY(negative, 0.0);
  double tetAcc = 0;
  for (int d = 0; d <= 3; ++d) tetAcc = std::max(tetAcc, tetError(Fem::accurateQuadrature(CellType::Tet10), d));
  TEST_COMPARE(tetAcc, <, 1e-14);
  const double hex = cubeError(Fem::cellQuadrature(CellType::Hex20), 5), hex6 = cubeError(Fem::cellQuadrature(CellType::Hex20), 6);
  const double hexAcc = cubeError(Fem::accurateQuadrature(CellType::Hex20), 7);
  out << "Hex20 rule: exponents <= 5 error " << hex << ", <= 6 " << hex6 << "; accurate rule exponents <= 7 "
      << hexAcc << "\n";
  TEST_COMPARE(hex, <, 1e-14);
  TEST_COMPARE(hex6, >, 1e-3);
  TEST_COMPARE(hexAcc, <, 1e-14);
  // Facets: the 6-node triangle's rule (degree 5), int s^p t^q = p! q! / (p + q + 2)!;
  // the 8-node quadrilateral's 3x3 Gauss (exponents <= 5).
  double tri = 0, quad = 0;
  for (int p = 0; p <= 5; ++p)
    for (int q = 0; q <= 5; ++q) {
      if (p + q <= 5) {
        double sum = 0;
        for (const auto& x : Fem::facetQuadrature(6)) sum += x.weight * std::pow(x.s, p) * std::pow(x.t, q);
        const double exact = factorial(p) * factorial(q) / factorial(p + q + 2);
        tri = std::max(tri, std::abs(sum - exact) / exact);
      }
      double sum = 0;
      for (const auto& x : Fem::facetQuadrature(8)) sum += x.weight * std::pow(x.s, p) * std::pow(x.t, q);
      const double exact = (p % 2 || q % 2) ? 0.0 : 4.0 / ((p + 1) * (q + 1));
      quad = std::max(quad, std::abs(sum - exact));
    }
  out << "facet rules: 6-node triangle degree <= 5 error " << tri << ", 8-node quadrilateral " << quad << "\n";
  TEST_COMPARE(tri, <, 1e-14);
  TEST_COMPARE(quad, <, 1e-14);
}

// K against the isotropic formula with the independent basis: with a
// high-order rule on cells where the integrand is a polynomial (a
// straight-sided Tet10, a parallelepiped Hex20), with the element's own
// points on curved cells (where no rule is exact), and then how far the
// element's rule is from a high-order one there.
TEUCHOS_UNIT_TEST(QuadraticStiffness, AgainstIndependentQuadrature) {
  const Fem::Material mat{2.1e11, 0.3};
  struct Case {
    CellType type;
    std::string what;
    std::vector<Point> X;
    bool polynomial;
  };
  const std::vector<Case> cases = {
      {CellType::Tet10, "distorted straight-sided", straightCell(CellType::Tet10, kTetCorners), true},
      {CellType::Tet10, "curved", curved(straightCell(CellType::Tet10, kTetCorners), 4, 0.08, 5), false},
      {CellType::Hex20, "parallelepiped", straightCell(CellType::Hex20, parallelepipedCorners()), true},
      {CellType::Hex20, "distorted straight-edged", straightCell(CellType::Hex20, distortedHexCorners()), false},
      {CellType::Hex20, "curved", curved(straightCell(CellType::Hex20, distortedHexCorners()), 8, 0.1, 6), false}};
  for (const Case& c : cases) {
    const auto K = Fem::elementStiffness(c.type, c.X, mat);
    const auto Khigh = independentStiffness(c.type, c.X, mat, testRule(c.type, 8));
    const double dHigh = relDiff(K, Khigh);
    out << Mesh::cellTypeName(c.type) << " " << c.what << ": max |K - K_independent(high order)| / max |K| = " << dHigh;
    if (c.polynomial) {
      out << "\n";
      TEST_COMPARE(dHigh, <, 1e-12);
      continue;
    }
    const double dSame = relDiff(K, independentStiffness(c.type, c.X, mat, Fem::cellQuadrature(c.type)));
    out << "; with the element's own points " << dSame << "\n";
    TEST_COMPARE(dSame, <, 1e-12);
    TEST_COMPARE(dHigh, <, 1e-2);  // quadrature error of a rational integrand, small for mild curvature
  }
}

TEUCHOS_UNIT_TEST(QuadraticStiffness, RigidBodyKernelAndRank) {
  kernelTest(CellType::Tet10, straightCell(CellType::Tet10, kTetCorners), "straight-sided", out, success);
  kernelTest(CellType::Tet10, curved(straightCell(CellType::Tet10, kTetCorners), 4, 0.08, 7), "curved", out, success);
  kernelTest(CellType::Hex20, straightCell(CellType::Hex20, distortedHexCorners()), "distorted", out, success);
  kernelTest(CellType::Hex20, curved(straightCell(CellType::Hex20, distortedHexCorners()), 8, 0.1, 8), "curved", out,
             success);
}

TEUCHOS_UNIT_TEST(QuadraticPatchTest, Tet10) { patchTest(CellType::Tet10, {2, 2, 2}, out, success); }
TEUCHOS_UNIT_TEST(QuadraticPatchTest, Hex20) { patchTest(CellType::Hex20, {3, 2, 2}, out, success); }

// Consistent loads of a uniform traction: the total is t x area, on flat
// facets with straight and with curved edges (area: the straight polygon and
// the parabolic segments, 2/3 chord x rise each); flat straight 6-node
// triangles put 0 on the corners and 1/3 on the mid-edge nodes, flat 8-node
// quadrilaterals -1/12 and 1/3.
TEUCHOS_UNIT_TEST(QuadraticLoads, FacetTractions) {
  const Point t = {0.3, -1.2, 2.5};
  // The facet's plane in space: origin o, orthonormal directions e1, e2.
  const Point o = {0.2, -0.1, 0.4}, e1 = {2.0 / 3, 2.0 / 3, 1.0 / 3}, e2 = {-2.0 / 3, 1.0 / 3, 2.0 / 3};
  auto place = [&](double u, double v) {
    return Point{o[0] + u * e1[0] + v * e2[0], o[1] + u * e1[1] + v * e2[1], o[2] + u * e1[2] + v * e2[2]};
  };
  // In-plane corners and, per edge, the rise of its mid-edge node off the chord (outward).
  struct Facet {
    std::vector<std::array<double, 2>> corners;
    std::vector<double> rise;
  };
  auto build = [&](const Facet& f, double& area) {
    const size_t nc = f.corners.size();
    std::vector<Point> X;
    area = 0;
    for (size_t k = 0; k < nc; ++k) {
      const auto &p = f.corners[k], &q = f.corners[(k + 1) % nc];
      area += (p[0] * q[1] - q[0] * p[1]) / 2;  // counter-clockwise polygon
    }
    for (const auto& c : f.corners) X.push_back(place(c[0], c[1]));
    for (size_t k = 0; k < nc; ++k) {
      const auto &p = f.corners[k], &q = f.corners[(k + 1) % nc];
      const double dx = q[0] - p[0], dy = q[1] - p[1], L = std::hypot(dx, dy);
      const double nx = dy / L, ny = -dx / L;  // outward for a counter-clockwise polygon
      X.push_back(place((p[0] + q[0]) / 2 + f.rise[k] * nx, (p[1] + q[1]) / 2 + f.rise[k] * ny));
      area += 2.0 / 3 * L * f.rise[k];
    }
    return X;
  };
  const std::vector<std::pair<Facet, std::string>> facets = {
      {{{{0, 0}, {1.3, 0.1}, {0.4, 0.9}}, {0, 0, 0}}, "straight triangle"},
      {{{{0, 0}, {1.3, 0.1}, {0.4, 0.9}}, {0.08, -0.05, 0.1}}, "curved triangle"},
      {{{{0, 0}, {2, 0}, {2, 2}, {0, 2}}, {0, 0, 0, 0}}, "square"},
      {{{{0, 0}, {1.5, 0.2}, {1.9, 1.4}, {0.4, 1.2}}, {0, 0, 0, 0}}, "parallelogram"},
      {{{{0, 0}, {1.5, 0.1}, {1.7, 1.3}, {0.2, 1.1}}, {0.1, -0.08, 0.05, 0.12}}, "curved quadrilateral"}};
  for (const auto& [f, what] : facets) {
    double area;
    const auto X = build(f, area);
    const auto w = Fem::facetNodalAreas(X);
    const auto force = Fem::facetTractionForces(X, t);
    double total[3] = {0, 0, 0}, sumW = 0;
    for (size_t a = 0; a < X.size(); ++a) {
      sumW += w[a];
      for (int d = 0; d < 3; ++d) total[d] += force[3 * a + d];
    }
    double err = std::abs(sumW - area) / area;
    for (int d = 0; d < 3; ++d) err = std::max(err, std::abs(total[d] - t[d] * area) / (std::abs(t[d]) * area));
    out << X.size() << "-node " << what << ": area " << area << ", |total - t area| / |t area| = " << err << "\n";
    TEST_COMPARE(err, <, 1e-13);
    const size_t nc = f.corners.size();
    const bool flatStraight = std::all_of(f.rise.begin(), f.rise.end(), [](double r) { return r == 0; });
    if (flatStraight) {
      const double corner = nc == 3 ? 0.0 : -1.0 / 12, mid = 1.0 / 3;
      double dev = 0;
      for (size_t a = 0; a < X.size(); ++a) dev = std::max(dev, std::abs(w[a] / area - (a < nc ? corner : mid)));
      out << "  corners " << w[0] / area << " and mid-edge nodes " << w[nc] / area << " of the area (max deviation "
          << dev << ")\n";
      TEST_COMPARE(dev, <, 1e-14);
      for (int d = 0; d < 3; ++d) TEST_FLOATING_EQUALITY(force[3 * nc + d], t[d] * area / 3, 1e-13);
    }
  }
  // A facet bent out of its plane (on a sphere of radius 2): the surface
  // element is no polynomial; the rule's total against a 20 x 20 product rule.
  for (int nodes : {6, 8}) {
    const std::vector<std::array<double, 2>> ref =
        nodes == 6 ? std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}
                   : std::vector<std::array<double, 2>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1},
                                                        {0, -1},  {1, 0},  {0, 1}, {-1, 0}};
    std::vector<Point> X;
    for (const auto& r : ref) {
      const double u = nodes == 6 ? r[0] : 0.5 * r[0], v = nodes == 6 ? r[1] : 0.5 * r[1];
      const double R = 2, n = std::sqrt(R * R + u * u + v * v);
      X.push_back({R * u / n, R * v / n, R * R / n});  // the radial projection onto the sphere
    }
    std::vector<Point> refPoints;
    for (const auto& r : ref) refPoints.push_back({r[0], r[1], 0});
    std::vector<std::array<int, 3>> powers;
    for (int p = 0; p <= 2; ++p)
      for (int q = 0; q <= 2; ++q)
        if (nodes == 6 ? p + q <= 2 : p + q <= 3) powers.push_back({p, q, 0});
    const LagrangeBasis basis(powers, refPoints);
    std::vector<double> gx, gw;
    gaussLegendre(20, gx, gw);
    double area = 0;
    for (int i = 0; i < 20; ++i)
      for (int j = 0; j < 20; ++j) {
        double s = gx[i], tt = gx[j], weight = gw[i] * gw[j];
        if (nodes == 6) {  // collapsed square onto the triangle
          const double u = (1 + s) / 2, v = (1 + tt) / 2;
          s = u, tt = v * (1 - u), weight *= (1 - u) / 4;
        }
        double N[8], dN[8][3];
        basis.eval({s, tt, 0}, N, &dN[0][0]);
        Point xs{0, 0, 0}, xt{0, 0, 0};
        for (int a = 0; a < nodes; ++a)
          for (int d = 0; d < 3; ++d) xs[d] += dN[a][0] * X[a][d], xt[d] += dN[a][1] * X[a][d];
        const Point c = {xs[1] * xt[2] - xs[2] * xt[1], xs[2] * xt[0] - xs[0] * xt[2], xs[0] * xt[1] - xs[1] * xt[0]};
        area += weight * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      }
    const auto w = Fem::facetNodalAreas(X);
    double sum = 0;
    for (double v : w) sum += v;
    out << nodes << "-node facet on a sphere: area " << sum << " vs " << area << " (20 x 20 points), relative "
        << std::abs(sum - area) / area << "\n";
    TEST_COMPARE(std::abs(sum - area) / area, <, 5e-6);
  }
}

// Consistent loads of a uniform volume force: the total is b x volume (also
// on curved cells, where the rules integrate det J exactly); a straight-sided
// Tet10 puts -1/20 of it on each corner and 1/5 on each mid-edge node, a
// parallelepiped Hex20 -1/8 and 1/6.
TEUCHOS_UNIT_TEST(QuadraticLoads, VolumeForces) {
  const Point b = {1.5, -2.0, 0.7};
  struct Case {
    CellType type;
    std::string what;
    std::vector<Point> X;
    double corner, mid;  // fractions of the total, or NaN when not checked
  };
  const double nan = std::nan("");
  const std::vector<Case> cases = {
      {CellType::Tet10, "straight-sided", straightCell(CellType::Tet10, kTetCorners), -1.0 / 20, 1.0 / 5},
      {CellType::Tet10, "curved", curved(straightCell(CellType::Tet10, kTetCorners), 4, 0.08, 9), nan, nan},
      {CellType::Hex20, "parallelepiped", straightCell(CellType::Hex20, parallelepipedCorners()), -1.0 / 8, 1.0 / 6},
      {CellType::Hex20, "curved", curved(straightCell(CellType::Hex20, distortedHexCorners()), 8, 0.1, 10), nan, nan}};
  for (const Case& c : cases) {
    const double V = independentVolume(c.type, c.X);
    const auto f = Fem::cellVolumeForces(c.type, c.X, b);
    const int corners = c.type == CellType::Tet10 ? 4 : 8;
    double total[3] = {0, 0, 0};
    for (size_t a = 0; a < c.X.size(); ++a)
      for (int d = 0; d < 3; ++d) total[d] += f[3 * a + d];
    double err = 0;
    for (int d = 0; d < 3; ++d) err = std::max(err, std::abs(total[d] - b[d] * V) / std::abs(b[d] * V));
    out << Mesh::cellTypeName(c.type) << " " << c.what << ": volume " << V << ", |total - b V| / |b V| = " << err
        << "\n";
    TEST_COMPARE(err, <, 1e-13);
    if (!std::isnan(c.corner)) {
      double dev = 0;
      for (size_t a = 0; a < c.X.size(); ++a)
        for (int d = 0; d < 3; ++d)
          dev = std::max(dev, std::abs(f[3 * a + d] / (b[d] * V) - (int(a) < corners ? c.corner : c.mid)));
      out << "  corners " << f[0] / (b[0] * V) << ", mid-edge nodes " << f[3 * corners] / (b[0] * V)
          << " of the total (max deviation " << dev << ")\n";
      TEST_COMPARE(dev, <, 1e-13);
    }
  }
}

// The stress of a cell: a linear displacement gives its constant stress on
// curved cells; a quadratic one on a straight-sided Tet10 or a parallelepiped
// Hex20 gives a linear stress, whose volume average is its value at the centroid.
TEUCHOS_UNIT_TEST(QuadraticStress, VolumeAverage) {
  const Fem::Material mat{2.0e5, 0.27};
  const auto D = mat.D();
  auto voigt = [&](const double eps[6]) {
    std::array<double, 6> s{};
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 6; ++k) s[r] += D[6 * r + k] * eps[k];
    return s;
  };
  const double epsLinear[6] = {kA[0][0],           kA[1][1],           kA[2][2],
                               kA[1][2] + kA[2][1], kA[0][2] + kA[2][0], kA[0][1] + kA[1][0]};
  const auto sigmaLinear = voigt(epsLinear);
  const std::vector<std::pair<CellType, std::vector<Point>>> curvedCells = {
      {CellType::Tet10, curved(straightCell(CellType::Tet10, kTetCorners), 4, 0.08, 12)},
      {CellType::Hex20, curved(straightCell(CellType::Hex20, distortedHexCorners()), 8, 0.1, 13)}};
  for (const auto& [t, X] : curvedCells) {
    std::vector<double> ue;
    for (const Point& x : X) {
      const Point u = linearField(x);
      ue.insert(ue.end(), u.begin(), u.end());
    }
    const auto s = Fem::cellStress(t, X, ue, mat);
    const double err = relDiff(std::vector<double>(s.begin(), s.end()),
                               std::vector<double>(sigmaLinear.begin(), sigmaLinear.end()));
    out << Mesh::cellTypeName(t) << " curved, linear field: |sigma - D eps| / |D eps| = " << err << "\n";
    TEST_COMPARE(err, <, 1e-12);
  }
  // u = (x^2, y z, x z): eps = (2x, z, x, y, z, 0) (engineering shears yz, xz, xy).
  const std::vector<std::pair<CellType, std::vector<Point>>> straightCells = {
      {CellType::Tet10, straightCell(CellType::Tet10, kTetCorners)},
      {CellType::Hex20, straightCell(CellType::Hex20, parallelepipedCorners())}};
  for (const auto& [t, X] : straightCells) {
    std::vector<double> ue;
    Point c{0, 0, 0};
    const int corners = t == CellType::Tet10 ? 4 : 8;
    for (int a = 0; a < corners; ++a)
      for (int d = 0; d < 3; ++d) c[d] += X[a][d] / corners;
    for (const Point& x : X) ue.insert(ue.end(), {x[0] * x[0], x[1] * x[2], x[0] * x[2]});
    const double eps[6] = {2 * c[0], c[2], c[0], c[1], c[2], 0};
    const auto expected = voigt(eps);
    const auto s = Fem::cellStress(t, X, ue, mat);
    const double err =
        relDiff(std::vector<double>(s.begin(), s.end()), std::vector<double>(expected.begin(), expected.end()));
    out << Mesh::cellTypeName(t) << " straight, quadratic field: |sigma_mean - sigma(centroid)| / |sigma| = " << err
        << "\n";
    TEST_COMPARE(err, <, 1e-12);
  }
}

// Inverted cells are refused with the reason: an inverted corner order
// (det J < 0 everywhere), and a mid-edge node moved along its edge by more
// than a quarter of the edge from the middle, which folds the map at the
// corner it approaches while every quadrature point still sees det J > 0.
TEUCHOS_UNIT_TEST(QuadraticElements, InvertedCellRefused) {
  const Fem::Material mat{1.0, 0.3};
  auto refused = [&](CellType t, const std::vector<Point>& X, std::initializer_list<const char*> words) {
    try {
      Fem::elementStiffness(t, X, mat);
    } catch (const Error& e) {
      out << Mesh::cellTypeName(t) << ": " << e.what() << "\n";
      return messageHas(e.what(), words);
    }
    out << Mesh::cellTypeName(t) << ": not refused\n";
    return false;
  };
  std::vector<Point> swapped = kTetCorners;
  std::swap(swapped[2], swapped[3]);
  TEST_ASSERT(refused(CellType::Tet10, straightCell(CellType::Tet10, swapped), {"inverted", "Tet10", "det J"}));
  std::vector<Point> hexSwapped = parallelepipedCorners();
  for (int a = 0; a < 4; ++a) std::swap(hexSwapped[a], hexSwapped[a + 4]);
  TEST_ASSERT(refused(CellType::Hex20, straightCell(CellType::Hex20, hexSwapped), {"inverted", "Hex20", "det J"}));
  TEST_THROW(Fem::cellVolumeForces(CellType::Tet10, straightCell(CellType::Tet10, swapped), {0, 0, 1}), Error);

  // The unit tetrahedron with node 4 (edge 0-1) at x = 0.8: dx/dxi = 3 - 4 (0.8) < 0 at corner 1.
  std::vector<Point> folded = straightCell(CellType::Tet10, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  folded[4] = {0.8, 0, 0};
  std::vector<Point> hexFolded = straightCell(CellType::Hex20, std::vector<Point>(kHex20Nodes.begin(), kHex20Nodes.begin() + 8));
  hexFolded[8] = {0.6, -1, -1};  // edge 0-1 from x = -1 to 1: past the quarter point 0.5
  for (const auto& [t, X] : {std::pair<CellType, std::vector<Point>>{CellType::Tet10, folded}, {CellType::Hex20, hexFolded}}) {
    bool quadraturePointsPositive = true;
    for (const auto& q : Fem::cellQuadrature(t)) {
      std::vector<double> dN;
      try {
        Fem::shapeGradients(t, X, q.xi, dN);
      } catch (const Error&) {
        quadraturePointsPositive = false;
      }
    }
    TEST_ASSERT(quadraturePointsPositive);
    TEST_ASSERT(refused(t, X, {"inverted", Mesh::cellTypeName(t).c_str(), "det J", "node 1"}));
  }
}
