// The consistent mass matrix (Tribos_Mass.hpp) on every cell type: its total
// mass, translational and rotational inertia on distorted cells against an
// independent quadrature of the cell's own map, symmetry and positive
// definiteness, the negative corner row sums that rule out row-sum lumping
// of Tet10 and Hex20, the subdomain assembly (K's pattern, per-body
// densities) and a bar's longitudinal vibration: the Rayleigh quotient of
// its first mode, and the first discrete eigenvalue, against (pi c / 2L)^2
// under refinement.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <string>

#include "Tribos_Assembly.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Mass.hpp"
#include "FemTestAlgebra.hpp"

namespace {

using Tribos::Fem::Test::gaussLegendre;
using Tribos::Fem::Test::symmetricEigenvalues;

using namespace Tribos;
using Fem::Point;
using Mesh::CellType;

const CellType kAllTypes[] = {CellType::Tet4, CellType::Hex8, CellType::Tet10, CellType::Hex20};

// ---------------------------------------------------------------------------
// Test cells, written out independently of the library: Gmsh's node orders
// (Tet10 mid-edge nodes 4 = 0-1, 5 = 1-2, 6 = 2-0, 7 = 3-0, 8 = 3-2, 9 = 3-1;
// Hex20's 8 = 0-1, 9 = 0-3, 10 = 0-4, 11 = 1-2, 12 = 1-5, 13 = 2-3, 14 = 2-6,
// 15 = 3-7, 16 = 4-5, 17 = 4-7, 18 = 5-6, 19 = 6-7).
const int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
const int kHexEdges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                              {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
const int kHexSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

bool isTet(CellType type) { return type == CellType::Tet4 || type == CellType::Tet10; }
int cornersOf(CellType type) { return isTet(type) ? 4 : 8; }

// A skewed tetrahedron, and a hexahedron with every corner moved off a
// parallelepiped (its map trilinear, not affine).
const std::vector<Point> kTetCorners = {{0.1, -0.2, 0.05}, {1.3, 0.2, -0.1}, {0.3, 1.1, 0.2}, {-0.2, 0.4, 0.9}};
std::vector<Point> distortedHexCorners() {
  const double A[3][3] = {{1.2, 0.3, -0.2}, {0.1, 0.9, 0.25}, {-0.15, 0.2, 1.1}};
  const double move[8][3] = {{0.1, -0.05, 0.08}, {-0.12, 0.07, 0.02}, {0.05, 0.1, -0.09}, {-0.04, -0.08, 0.11},
                             {0.09, 0.03, -0.1},  {-0.06, -0.1, 0.05}, {0.12, -0.02, 0.07}, {-0.1, 0.09, -0.03}};
  std::vector<Point> c;
  for (int a = 0; a < 8; ++a) {
    Point x{0.4 + move[a][0], -0.3 + move[a][1], 0.2 + move[a][2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) x[i] += A[i][j] * kHexSign[a][j];
    c.push_back(x);
  }
  return c;
}

// The cell of `type` on the given corners with straight edges (mid-edge
// nodes at the middles).
std::vector<Point> straightCell(CellType type, const std::vector<Point>& corners) {
  std::vector<Point> X = corners;
  auto addMid = [&](int p, int q) {
    X.push_back({(X[p][0] + X[q][0]) / 2, (X[p][1] + X[q][1]) / 2, (X[p][2] + X[q][2]) / 2});
  };
  if (type == CellType::Tet10)
    for (const auto& e : kTetEdges) addMid(e[0], e[1]);
  if (type == CellType::Hex20)
    for (const auto& e : kHexEdges) addMid(e[0], e[1]);
  return X;
}

std::vector<Point> distortedCell(CellType type) {
  return straightCell(type, isTet(type) ? kTetCorners : distortedHexCorners());
}

// ---------------------------------------------------------------------------
// The independent integral over a straight-edged cell: its map from the
// corners alone (affine for a tetrahedron, trilinear for a hexahedron),
// integrated by a Gauss-Legendre product rule of the test's own (Newton's
// method, FemTestAlgebra.hpp), collapsed (Duffy) on the tetrahedron. With 8
// points it is exact far beyond the degrees met here.
struct CellPoint {
  Point x;
  double weight;  // quadrature weight times det J
};

double det3(const double J[3][3]) {
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

std::vector<CellPoint> cellPoints(CellType type, const std::vector<Point>& X, int n = 8) {
  std::vector<double> g, gw;
  gaussLegendre(n, g, gw);
  std::vector<CellPoint> points;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double u = g[i], v = g[j], s = g[k], w = gw[i] * gw[j] * gw[k];
        CellPoint p{{0, 0, 0}, 0};
        double J[3][3] = {};  // J[d][r] = dx_d / d(reference r)
        if (isTet(type)) {
          // (u, v, s) in [0,1]^3 -> xi = (a, b (1 - a), c (1 - a)(1 - b)).
          const double a = (1 + u) / 2, b = (1 + v) / 2, c = (1 + s) / 2;
          const double xi[3] = {a, b * (1 - a), c * (1 - a) * (1 - b)};
          for (int d = 0; d < 3; ++d) {
            p.x[d] = X[0][d];
            for (int r = 0; r < 3; ++r) {
              p.x[d] += xi[r] * (X[r + 1][d] - X[0][d]);
              J[d][r] = X[r + 1][d] - X[0][d];
            }
          }
          p.weight = w / 8 * (1 - a) * (1 - a) * (1 - b) * det3(J);
        } else {
          const double xi[3] = {u, v, s};
          for (int a = 0; a < 8; ++a) {
            double f[3];
            for (int r = 0; r < 3; ++r) f[r] = (1 + kHexSign[a][r] * xi[r]) / 2;
            const double N = f[0] * f[1] * f[2];
            for (int d = 0; d < 3; ++d) {
              p.x[d] += N * X[a][d];
              for (int r = 0; r < 3; ++r) J[d][r] += X[a][d] * kHexSign[a][r] * 0.5 * (N / f[r]);
            }
          }
          p.weight = w * det3(J);
        }
        points.push_back(p);
      }
  return points;
}

// ---------------------------------------------------------------------------
// Dense helpers.

// a' M b of the element's 3 npc dofs.
double form(const std::vector<double>& M, const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = a.size();
  double s = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) s += a[i] * M[i * n + j] * b[j];
  return s;
}

// The nodal values of a vector field at the nodes X.
template <class Field>
std::vector<double> nodal(const std::vector<Point>& X, Field u) {
  std::vector<double> v;
  for (const Point& x : X) {
    const Point ux = u(x);
    v.insert(v.end(), ux.begin(), ux.end());
  }
  return v;
}

// Cholesky factorization in place (lower triangle); false when a pivot is
// not positive.
bool cholesky(std::vector<double>& A, int n) {
  for (int j = 0; j < n; ++j) {
    double d = A[j * n + j];
    for (int k = 0; k < j; ++k) d -= A[j * n + k] * A[j * n + k];
    if (!(d > 0)) return false;
    A[j * n + j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double s = A[i * n + j];
      for (int k = 0; k < j; ++k) s -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = s / A[j * n + j];
    }
  }
  return true;
}

// Solves L L' x = b with the factor of cholesky().
std::vector<double> choleskySolve(const std::vector<double>& L, int n, std::vector<double> b) {
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) b[i] -= L[i * n + k] * b[k];
    b[i] /= L[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) b[i] -= L[k * n + i] * b[k];
    b[i] /= L[i * n + i];
  }
  return b;
}


Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double inner(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

const double kRho = 2.7;

// ---------------------------------------------------------------------------
// Element level.

// The total mass in each component block, and the inertia of rigid
// translations, rigid rotations about the centroid and a general linear
// field: the nodal values of a linear field are its interpolant on a
// straight-edged isoparametric cell, so a' M a = rho int |u|^2 dV exactly.
TEUCHOS_UNIT_TEST(ElementMass, MassAndInertiaOnDistortedCells) {
  for (CellType type : kAllTypes) {
    const auto X = distortedCell(type);
    const auto M = Fem::elementMass(type, X, kRho);
    const int n = 3 * static_cast<int>(X.size());
    TEST_EQUALITY(static_cast<int>(M.size()), n * n);
    const auto points = cellPoints(type, X);
    double V = 0;
    Point centroid{0, 0, 0};
    for (const auto& p : points) {
      V += p.weight;
      for (int d = 0; d < 3; ++d) centroid[d] += p.weight * p.x[d];
    }
    for (double& c : centroid) c /= V;
    const double tol = 1e-12;
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) {
        double block = 0;
        for (int i = c; i < n; i += 3)
          for (int j = d; j < n; j += 3) block += M[i * n + j];
        if (c == d) TEST_FLOATING_EQUALITY(block, kRho * V, tol);
        if (c != d) TEST_ASSERT(block == 0.0);
      }
    const Point a{0.7, -1.3, 0.4};
    const auto translation = nodal(X, [&](const Point&) { return a; });
    TEST_FLOATING_EQUALITY(form(M, translation, translation), kRho * V * dot(a, a), tol);
    auto independent = [&](auto u) {
      double s = 0;
      for (const auto& p : points) s += p.weight * dot(u(p.x), u(p.x));
      return kRho * s;
    };
    const Point axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, -0.7, 0.5}};
    for (const Point& omega : axes) {
      auto rotation = [&](const Point& x) {
        return cross(omega, {x[0] - centroid[0], x[1] - centroid[1], x[2] - centroid[2]});
      };
      const auto r = nodal(X, rotation);
      const double inertia = independent(rotation);
      out << Mesh::cellTypeName(type) << " omega = (" << omega[0] << ", " << omega[1] << ", " << omega[2]
          << "): a'Ma = " << form(M, r, r) << ", independent " << inertia << "\n";
      TEST_FLOATING_EQUALITY(form(M, r, r), inertia, tol);
      // The translation carries no angular momentum about the centroid.
      TEST_COMPARE(std::abs(form(M, translation, r)), <, tol * kRho * V);
    }
    const double A[3][3] = {{0.3, -1.1, 0.4}, {0.8, 0.2, -0.5}, {-0.6, 0.9, 1.4}};
    auto linear = [&](const Point& x) {
      Point u{0.2, -0.1, 0.3};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) u[i] += A[i][j] * x[j];
      return u;
    };
    const auto l = nodal(X, linear);
    TEST_FLOATING_EQUALITY(form(M, l, l), independent(linear), tol);
  }
}

// A box of sides 2 x 1 x 0.5 against the closed form of its moments of
// inertia, rho V (b^2 + c^2) / 12 about the x axis through the centre.
TEUCHOS_UNIT_TEST(ElementMass, BoxMomentsOfInertiaClosedForm) {
  const double side[3] = {2.0, 1.0, 0.5}, V = side[0] * side[1] * side[2];
  std::vector<Point> corners;
  for (const auto& s : kHexSign) corners.push_back({s[0] * side[0] / 2, s[1] * side[1] / 2, s[2] * side[2] / 2});
  for (CellType type : {CellType::Hex8, CellType::Hex20}) {
    const auto X = straightCell(type, corners);
    const auto M = Fem::elementMass(type, X, kRho);
    for (int k = 0; k < 3; ++k) {
      Point omega{0, 0, 0};
      omega[k] = 1;
      const auto r = nodal(X, [&](const Point& x) { return cross(omega, x); });
      const double b = side[(k + 1) % 3], c = side[(k + 2) % 3];
      TEST_FLOATING_EQUALITY(form(M, r, r), kRho * V * (b * b + c * c) / 12, 1e-13);
    }
  }
}

// Symmetric, and positive definite: the Cholesky factorization succeeds and
// the smallest eigenvalue is positive (a fair fraction of the largest).
TEUCHOS_UNIT_TEST(ElementMass, SymmetricPositiveDefinite) {
  for (CellType type : kAllTypes) {
    const auto X = distortedCell(type);
    auto M = Fem::elementMass(type, X, kRho);
    const int n = 3 * static_cast<int>(X.size());
    int asymmetric = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < i; ++j) asymmetric += M[i * n + j] != M[j * n + i];
    TEST_EQUALITY(asymmetric, 0);
    const auto ev = symmetricEigenvalues(M, n);
    out << Mesh::cellTypeName(type) << ": eigenvalues of M in [" << ev.front() << ", " << ev.back() << "]\n";
    TEST_COMPARE(ev.front(), >, 1e-3 * ev.back());
    TEST_ASSERT(cholesky(M, n));
  }
}

// The row sums of M are the consistent masses of the nodes, int rho N_a dV:
// negative at the corners of Tet10 (-1/20 of the cell's) and of Hex20 (-1/8
// on a parallelepiped), which is why Tribos offers no row-sum lumped mass.
TEUCHOS_UNIT_TEST(ElementMass, RowSumsNegativeAtQuadraticCorners) {
  struct Case {
    CellType type;
    std::vector<Point> corners;
    double corner, midEdge;  // fractions of the cell's mass
  };
  std::vector<Point> brick;
  for (const auto& s : kHexSign) brick.push_back({1.0 + s[0] * 0.6, s[1] * 0.4, -2.0 + s[2] * 0.3});
  const std::vector<Case> cases = {{CellType::Tet4, kTetCorners, 0.25, 0},
                                   {CellType::Hex8, brick, 0.125, 0},
                                   {CellType::Tet10, kTetCorners, -1.0 / 20, 1.0 / 5},
                                   {CellType::Hex20, brick, -1.0 / 8, 1.0 / 6}};
  for (const Case& c : cases) {
    const auto X = straightCell(c.type, c.corners);
    const auto M = Fem::elementMass(c.type, X, kRho);
    const int n = 3 * static_cast<int>(X.size());
    double V = 0;
    for (const auto& p : cellPoints(c.type, X)) V += p.weight;
    for (int a = 0; a < static_cast<int>(X.size()); ++a) {
      double rowSum = 0;
      for (int j = 0; j < n; ++j) rowSum += M[3 * a * n + j];
      const double expected = (a < cornersOf(c.type) ? c.corner : c.midEdge) * kRho * V;
      TEST_COMPARE(std::abs(rowSum - expected), <, 1e-13 * kRho * V);
    }
  }
}

TEUCHOS_UNIT_TEST(ElementMass, DensityRefused) {
  const auto X = distortedCell(CellType::Tet4);
  for (double rho : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    TEST_THROW(Fem::elementMass(CellType::Tet4, X, rho), Error);
    TEST_THROW(Fem::BodyDensities{rho}, Error);
  }
  TEST_THROW(Fem::BodyDensities(std::vector<double>{1.0, 0.0}), Error);
  TEST_THROW(Fem::BodyDensities(std::vector<double>{}), Error);
}

// ---------------------------------------------------------------------------
// Meshes of a prismatic bar [0, L] x [0, b] x [0, b]: `cells` cells along x,
// one across. Nodes are found by their position on a grid of half cells.
Mesh::Mesh barMesh(CellType type, int cells, double L, double b) {
  const std::vector<Point> ref = straightCell(CellType::Hex20, [] {
    std::vector<Point> c;
    for (const auto& s : kHexSign) c.push_back({double(s[0]), double(s[1]), double(s[2])});
    return c;
  }());
  Mesh::Mesh mesh;
  mesh.type = type;
  std::map<std::array<int, 3>, int> id;
  for (int i = 0; i < cells; ++i)
    for (int a = 0; a < Mesh::nodesPerCell(type); ++a) {
      const std::array<int, 3> g{2 * i + 1 + int(ref[a][0]), 1 + int(ref[a][1]), 1 + int(ref[a][2])};
      auto it = id.find(g);
      if (it == id.end()) {
        it = id.emplace(g, mesh.numNodes()).first;
        mesh.coords.push_back({g[0] * L / (2 * cells), g[1] * b / 2, g[2] * b / 2});
      }
      mesh.connectivity.push_back(it->second);
    }
  return mesh;
}

// The whole mesh as one subdomain, local nodes the mesh's.
Mesh::Subdomain wholeMesh(const Mesh::Mesh& mesh) {
  Mesh::Subdomain sub;
  sub.id = 0;
  for (int c = 0; c < mesh.numCells(); ++c) sub.cells.push_back(c);
  for (int n = 0; n < mesh.numNodes(); ++n) sub.nodes.push_back(n);
  sub.connectivity = mesh.connectivity;
  return sub;
}

double sumOfBlock(const LocalCsr& A, int component) {
  double s = 0;
  for (int i = component; i < A.rows; i += 3)
    for (int k = A.rowptr[i]; k < A.rowptr[i + 1]; ++k)
      if (A.col[k] % 3 == component) s += A.val[k];
  return s;
}

// Two bodies of different densities in two subdomains: each subdomain's M
// has its K's pattern, and the masses add up body by body.
TEUCHOS_UNIT_TEST(SubdomainMass, PatternOfStiffnessAndBodyDensities) {
  for (CellType type : {CellType::Hex8, CellType::Hex20}) {
    const double L = 3.0, b = 0.5;
    Mesh::Mesh mesh = barMesh(type, 6, L, b);
    mesh.cellBody = {0, 0, 0, 0, 1, 1};
    mesh.bodyNames = {"light", "heavy"};
    const Fem::BodyDensities rho(std::vector<double>{1.5, 4.0});
    const auto subs = Mesh::extractSubdomains(mesh, {0, 0, 0, 1, 1, 1}, 2);
    const double cellVolume = L / 6 * b * b;
    // Subdomain 0 holds three light cells, subdomain 1 one light and two heavy.
    const double subdomainMass[2] = {3 * 1.5 * cellVolume, (1.5 + 2 * 4.0) * cellVolume};
    for (const auto& sub : subs) {
      const auto sys = Fem::assembleSubdomain(mesh, sub, Fem::Material{}, Fem::LoadCase{});
      const LocalCsr M = Fem::assembleSubdomainMass(mesh, sub, rho);
      TEST_EQUALITY(M.rows, sys.K.rows);
      TEST_ASSERT(M.rowptr == sys.K.rowptr);
      TEST_ASSERT(M.col == sys.K.col);
      for (int c = 0; c < 3; ++c) TEST_FLOATING_EQUALITY(sumOfBlock(M, c), subdomainMass[sub.id], 1e-13);
    }
  }
}

// The assembled K is the sum of the element stiffness matrices, entry by
// entry, to the last bit (the assembly K and M share).
TEUCHOS_UNIT_TEST(SubdomainMass, StiffnessAssemblyUnchanged) {
  const Mesh::Mesh mesh = barMesh(CellType::Hex20, 3, 1.0, 0.3);
  const auto sub = wholeMesh(mesh);
  const Fem::Material mat{2.0, 0.25};
  const auto K = Fem::assembleSubdomain(mesh, sub, mat, Fem::LoadCase{}).K;
  const int n = K.rows;
  std::vector<double> dense(static_cast<size_t>(n) * n, 0.0);
  for (int c = 0; c < mesh.numCells(); ++c) {
    const auto Ke = Fem::elementStiffness(mesh.type, Fem::cellCoordinates(mesh, c), mat);
    const int npc = mesh.nodesPerCell(), ne = 3 * npc;
    for (int i = 0; i < ne; ++i)
      for (int j = 0; j < ne; ++j)
        dense[static_cast<size_t>(3 * mesh.cell(c)[i / 3] + i % 3) * n + 3 * mesh.cell(c)[j / 3] + j % 3] +=
            Ke[i * ne + j];
  }
  int differ = 0;
  for (int i = 0; i < n; ++i)
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k)
      differ += K.val[k] != dense[static_cast<size_t>(i) * n + K.col[k]];
  TEST_EQUALITY(differ, 0);
}

// ---------------------------------------------------------------------------
// A bar's longitudinal vibration: nu = 0, fixed at x = 0 in x, rollers on
// every other face (y and z held everywhere: one cell across, every node is
// on a lateral face), so that it vibrates as the 1D bar, whose first mode
// u = sin(pi x / 2L) has omega^2 = (pi c / 2L)^2, c = sqrt(E / rho).

struct BarFrequencies {
  double rayleigh;  // u'Ku / u'Mu of the exact mode interpolated at the nodes
  double discrete;  // the first eigenvalue of K x = lambda M x on the free dofs
};

BarFrequencies barFrequencies(CellType type, int cells, double L, double E, double rho) {
  const Mesh::Mesh mesh = barMesh(type, cells, L, 0.4);
  const auto sub = wholeMesh(mesh);
  const LocalCsr K = Fem::assembleSubdomain(mesh, sub, Fem::Material{E, 0.0}, Fem::LoadCase{}).K;
  const LocalCsr M = Fem::assembleSubdomainMass(mesh, sub, Fem::BodyDensities(rho));
  std::vector<double> u(K.rows, 0.0), Ku, Mu;
  for (int a = 0; a < mesh.numNodes(); ++a) u[3 * a] = std::sin(std::acos(-1.0) * mesh.coords[a][0] / (2 * L));
  K.multiply(u, Ku);
  M.multiply(u, Mu);
  BarFrequencies f;
  f.rayleigh = inner(u, Ku) / inner(u, Mu);
  // Inverse iteration from the mode on the x dofs of the nodes off x = 0.
  std::vector<int> free;
  for (int a = 0; a < mesh.numNodes(); ++a)
    if (mesh.coords[a][0] > 0) free.push_back(3 * a);
  const LocalCsr Kf = K.principalSubmatrix(free), Mf = M.principalSubmatrix(free);
  const int n = Kf.rows;
  std::vector<double> factor(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = Kf.rowptr[i]; k < Kf.rowptr[i + 1]; ++k) factor[static_cast<size_t>(i) * n + Kf.col[k]] = Kf.val[k];
  if (!cholesky(factor, n)) throw Error("the bar's K is not positive definite on its free dofs");
  std::vector<double> x(n), Mx, Kx;
  for (int i = 0; i < n; ++i) x[i] = u[free[i]];
  for (int it = 0; it < 50; ++it) {
    Mf.multiply(x, Mx);
    x = choleskySolve(factor, n, Mx);
    const double scale = std::sqrt(inner(x, x));
    for (double& v : x) v /= scale;
  }
  Kf.multiply(x, Kx);
  Mf.multiply(x, Mx);
  f.discrete = inner(x, Kx) / inner(x, Mx);
  return f;
}

// The errors of both against (pi c / 2L)^2 are positive (the Rayleigh
// quotient is at least the discrete eigenvalue, which is at least the exact
// one) and fall as h^2 (Hex8) and h^4 (Hex20): halving h divides them by
// about 4 and 16.
void barConvergence(CellType type, int coarseCells, double expectedRatio, double finestBound,
                    Teuchos::FancyOStream& out, bool& success) {
  const double L = 2.0, E = 3.0, rho = 0.75, c = std::sqrt(E / rho);
  const double omega2 = std::pow(std::acos(-1.0) * c / (2 * L), 2);
  std::vector<BarFrequencies> errors;
  for (int cells = coarseCells; cells <= 4 * coarseCells; cells *= 2) {
    const BarFrequencies f = barFrequencies(type, cells, L, E, rho);
    errors.push_back({f.rayleigh / omega2 - 1, f.discrete / omega2 - 1});
    out << std::setprecision(6) << Mesh::cellTypeName(type) << " bar, " << cells
        << " cells: relative error of omega^2, Rayleigh quotient "
        << errors.back().rayleigh << ", first eigenvalue " << errors.back().discrete << "\n";
    TEST_COMPARE(errors.back().discrete, >, 0.0);
    TEST_COMPARE(errors.back().rayleigh, >=, errors.back().discrete * (1 - 1e-9));
  }
  for (size_t k = 1; k < errors.size(); ++k) {
    const double rayleighRatio = errors[k - 1].rayleigh / errors[k].rayleigh;
    const double discreteRatio = errors[k - 1].discrete / errors[k].discrete;
    out << "  ratio of errors on halving h: Rayleigh quotient " << rayleighRatio << ", first eigenvalue "
        << discreteRatio << "\n";
    TEST_COMPARE(std::abs(rayleighRatio / expectedRatio - 1), <, 0.1);
    TEST_COMPARE(std::abs(discreteRatio / expectedRatio - 1), <, 0.1);
  }
  TEST_COMPARE(errors.back().rayleigh, <, finestBound);
}

TEUCHOS_UNIT_TEST(BarVibration, Hex8) { barConvergence(CellType::Hex8, 4, 4.0, 2e-3, out, success); }
TEUCHOS_UNIT_TEST(BarVibration, Hex20) { barConvergence(CellType::Hex20, 2, 16.0, 1e-5, out, success); }

}  // namespace
