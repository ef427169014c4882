// Mortar integration: clipping of known polygons, the dual basis, and the
// integrals of two non-matching faces of stacked boxes (sum_m M_sm = D_s,
// total D = slave area, the master's consistent nodal areas, linear fields
// carried over exactly), and the rows the search builds from them.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <map>
#include <string>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_MeshFile.hpp"
#include "Tribos_Mortar.hpp"

namespace {

using namespace Tribos;
using Contact::Point2;

double area(const std::vector<Point2>& p) { return std::abs(Contact::signedArea(p)); }

// Two boxes stacked along z, as separate bodies: "lower" (0,1)^2 x (0,1)
// with nl^3 cells, "upper" (0,1)^2 x (1,2) with nu^3 cells, the upper one
// lifted by `lift`; faces lower_top and upper_bottom.
Mesh::Mesh stackedBoxes(Mesh::CellType type, int nl, int nu, double lift = 0) {
  Mesh::BoxSpec a, b;
  a.type = b.type = type;
  a.cells = {nl, nl, nl};
  b.cells = {nu, nu, nu};
  b.z = {1 + lift, 2 + lift};
  const Mesh::Mesh lower = Mesh::generateBox(a), upper = Mesh::generateBox(b);
  Mesh::Mesh m;
  m.type = type;
  m.coords = lower.coords;
  m.coords.insert(m.coords.end(), upper.coords.begin(), upper.coords.end());
  m.connectivity = lower.connectivity;
  const int offset = lower.numNodes();
  for (int n : upper.connectivity) m.connectivity.push_back(n + offset);
  m.faces["lower_top"] = lower.faces.at("zmax");
  for (Mesh::Facet f : upper.faces.at("zmin")) {
    for (int& n : f.nodes) n += offset;
    f.cell += lower.numCells();
    m.faces["upper_bottom"].push_back(f);
  }
  m.cellBody.assign(lower.numCells(), 0);
  m.cellBody.resize(m.numCells(), 1);
  m.bodyNames = {"lower", "upper"};
  return m;
}

TEUCHOS_UNIT_TEST(Mortar, ClipsKnownPolygons) {
  const std::vector<Point2> square = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  // A shifted square: the overlap [0, 1]^2.
  const auto quarter = Contact::clipPolygon({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, square);
  TEST_FLOATING_EQUALITY(area(quarter), 1.0, 1e-14);
  // A triangle cut by two edges of the square: [0,1]^2 minus the corner x + y > 1.5.
  const auto cut = Contact::clipPolygon({{0, 0}, {1.5, 0}, {0, 1.5}}, square);
  TEST_FLOATING_EQUALITY(area(cut), 1 - 0.125, 1e-14);
  // Clockwise subjects (a master facet seen from the slave) clip alike.
  const auto cw = Contact::clipPolygon({{0, 0}, {0, 2}, {2, 2}, {2, 0}}, square);
  TEST_FLOATING_EQUALITY(area(cw), 1.0, 1e-14);
  TEST_COMPARE(Contact::signedArea(cw), <, 0);
  // A rotated square inside the reference triangle's corner; a disjoint one;
  // one sharing an edge only.
  const std::vector<Point2> triangle = {{0, 0}, {1, 0}, {0, 1}};
  TEST_FLOATING_EQUALITY(area(Contact::clipPolygon({{0.2, 0.1}, {0.3, 0.2}, {0.2, 0.3}, {0.1, 0.2}}, triangle)), 0.02,
                         1e-13);
  TEST_ASSERT(Contact::clipPolygon({{2, 2}, {3, 2}, {3, 3}}, triangle).empty());
  TEST_COMPARE(area(Contact::clipPolygon({{1, -1}, {2, -1}, {2, 1}, {1, 1}}, square)), <, 1e-14);
  // The whole triangle inside the square stays itself.
  TEST_FLOATING_EQUALITY(area(Contact::clipPolygon(triangle, square)), 0.5, 1e-14);
}

// A master facet that coincides with the slave facet, seen through the
// round-off of two projections: its vertices lie within 1e-13 of the
// reference triangle's edges, on either side. The clipped polygon is the
// triangle: every vertex within round-off of it, area 1/2. (Cutting each
// edge at 0 instead of at the tolerance put a vertex at (10.5, -9.5) for a
// facet of a Gmsh mesh, with mortar weights of +-19 instead of 1.)
TEUCHOS_UNIT_TEST(Mortar, ClipsCoincidentPolygonsWithinRoundOff) {
  const std::vector<Point2> triangle = {{0, 0}, {1, 0}, {0, 1}};
  const double e[] = {-1.1e-13, -0.9e-13, -3e-14, 0.0, 4e-14, 0.9e-13, 1.1e-13};
  double worstOutside = 0, worstArea = 0;
  for (double a : e)
    for (double b : e)
      for (double c : e)
        for (bool clockwise : {false, true}) {
          std::vector<Point2> subject = {{a, b}, {1 + b, c}, {c, 1 - a}};
          if (clockwise) std::swap(subject[1], subject[2]);
          const auto clipped = Contact::clipPolygon(subject, triangle);
          worstArea = std::max(worstArea, std::abs(area(clipped) - 0.5));
          for (const Point2& p : clipped)
            worstOutside = std::max({worstOutside, -p[0], -p[1], p[0] + p[1] - 1});
        }
  out << "largest distance outside " << worstOutside << ", largest area error " << worstArea << "\n";
  TEST_COMPARE(worstOutside, <, 1e-12);
  TEST_COMPARE(worstArea, <, 1e-12);
}

// The quadrature of polygons: exact for degree 5 on a fan of triangles.
TEUCHOS_UNIT_TEST(Mortar, IntegratesPolynomials) {
  const std::vector<Point2> pentagon = {{0, 0}, {2, 0}, {2.5, 1}, {1, 2}, {-0.5, 1}};
  double a = 0, m = 0;
  Contact::integratePolygon(pentagon, [&](const Point2& p, double w) {
    a += w;
    m += w * std::pow(p[0], 3) * std::pow(p[1], 2);
  });
  TEST_FLOATING_EQUALITY(a, std::abs(Contact::signedArea(pentagon)), 1e-14);
  // int x^3 y^2 over the pentagon by the divergence theorem: sum over edges
  // of int x^4 y^2 / 4 dy, done with 4-point Gauss-Legendre per edge (exact).
  const double g[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double exact = 0;
  for (size_t i = 0; i < pentagon.size(); ++i) {
    const Point2 &p = pentagon[i], &q = pentagon[(i + 1) % pentagon.size()];
    for (int k = 0; k < 4; ++k) {
      const double t = (1 + g[k]) / 2, x = p[0] + t * (q[0] - p[0]), y = p[1] + t * (q[1] - p[1]);
      exact += gw[k] / 2 * std::pow(x, 4) * y * y / 4 * (q[1] - p[1]);
    }
  }
  TEST_FLOATING_EQUALITY(m, exact, 1e-13);
}

// Biorthogonality on a triangle and a distorted, warped quadrilateral:
// int psi_j N_k dA = delta_jk int N_k dA, and the psi_j sum to one.
TEUCHOS_UNIT_TEST(Mortar, DualBasisIsBiorthogonal) {
  Mesh::Mesh mesh;
  mesh.coords = {{0, 0, 0}, {1.3, 0.1, 0}, {1.1, 0.9, 0.2}, {-0.2, 1.4, 0.05}};
  for (const std::vector<int>& nodes : {std::vector<int>{0, 1, 2}, std::vector<int>{0, 1, 2, 3}}) {
    const Contact::SurfaceElement e(Mesh::Facet{nodes, 0}, mesh);
    const auto basis = Contact::dualBasis(e);
    const auto& A = basis.A;
    const int n = e.size();
    std::vector<std::vector<double>> psiN(n, std::vector<double>(n, 0.0));
    std::vector<double> areaN(n, 0.0);
    double N[4], d1[4], d2[4], sumPsiErr = 0;
    Contact::integratePolygon(e.shape().corners(), [&](const Point2& xi, double w) {
      e.shape().evaluate(xi, N, d1, d2);
      const double dA = w * e.jacobian(xi);
      double sumPsi = 0;
      for (int j = 0; j < n; ++j) {
        double psi = 0;
        for (int k = 0; k < n; ++k) psi += A[j][k] * N[k];
        sumPsi += psi;
        areaN[j] += N[j] * dA;
        for (int k = 0; k < n; ++k) psiN[j][k] += psi * N[k] * dA;
      }
      sumPsiErr = std::max(sumPsiErr, std::abs(sumPsi - 1));
    });
    TEST_COMPARE(sumPsiErr, <, 1e-13);
    for (int j = 0; j < n; ++j) {
      TEST_COMPARE(std::abs(basis.D[j] - areaN[j]), <, 1e-14);
      for (int k = 0; k < n; ++k) TEST_COMPARE(std::abs(psiN[j][k] - (j == k ? areaN[k] : 0.0)), <, 1e-13);
    }
  }
}

// Non-matching flat faces (slave 4^3 or 7^3 on master 3^3, and the coarse
// side as slave; second-order boxes 4^3 on 3^3): every slave node fully
// covered has sum_m M_sm = D_s = int N~_s dA (N~ = N on first-order
// facets, the transformed basis on second-order ones, all positive); D sums
// to the slave area; sum_s M_sm is the master node's int N_m dA (a uniform
// traction reaches the master as its consistent nodal forces, zero or
// negative at a second-order facet's corners); linear fields are carried
// over exactly (a mid-edge node's transformed position is the node on a
// straight edge).
TEUCHOS_UNIT_TEST(Mortar, FlatNonMatchingFaces) {
  using Cells = std::vector<std::pair<int, int>>;
  const std::vector<std::pair<Mesh::CellType, Cells>> cases = {
      {Mesh::CellType::Hex8, {{3, 4}, {3, 7}, {4, 3}}},
      {Mesh::CellType::Tet4, {{3, 4}, {3, 7}, {4, 3}}},
      {Mesh::CellType::Tet10, {{3, 4}}},
      {Mesh::CellType::Hex20, {{3, 4}}}};
  for (const auto& [type, cells] : cases)
    for (auto [nl, nu] : cells) {
      const Mesh::Mesh mesh = stackedBoxes(type, nl, nu);
      const auto coupling = Contact::mortarCoupling(mesh, "upper_bottom", "lower_top");
      const auto slaveArea = Contact::transformedAreas(mesh, "upper_bottom");
      const auto masterArea = Fem::faceNodalAreas(mesh, "lower_top");
      double total = 0, worst = 0, worstLinear = 0, worstNormal = 0, smallest = 1;
      std::map<int, double> toMaster;
      for (const auto& node : coupling) {
        total += node.covered();
        smallest = std::min(smallest, node.area);
        worst = std::max({worst, std::abs(node.covered() - node.area), std::abs(node.area - slaveArea[node.node])});
        worstNormal = std::max(worstNormal, std::abs(node.normal[2] + 1) + std::abs(node.normal[0]));
        double linear = 0;
        for (const auto& [m, value] : node.M) {
          toMaster[m] += value;
          const auto& x = mesh.coords[m];
          linear += value * (1 + 2 * x[0] - 3 * x[1]);
        }
        const auto& xs = mesh.coords[node.node];
        worstLinear = std::max(worstLinear, std::abs(linear / node.covered() - (1 + 2 * xs[0] - 3 * xs[1])));
      }
      out << Mesh::cellTypeName(type) << ", cells " << nl << " under " << nu << ": total D " << total
          << ", smallest D_s " << smallest << ", max |D_s - area| " << worst << ", linear " << worstLinear << "\n";
      TEST_FLOATING_EQUALITY(total, 1.0, 1e-13);
      TEST_COMPARE(smallest, >, 0.0);
      TEST_COMPARE(worst, <, 1e-14);
      TEST_COMPARE(worstLinear, <, 1e-12);
      TEST_COMPARE(worstNormal, <, 1e-14);
      double worstMaster = 0;
      for (int m : mesh.faceNodes("lower_top")) worstMaster = std::max(worstMaster, std::abs(toMaster[m] - masterArea[m]));
      TEST_COMPARE(worstMaster, <, 1e-14);
    }
}

// A Gmsh mesh whose two plates match on parts of their interface (the
// shipped lap joint: both plates are cut by the same washer and hole
// curves, so many slave facets coincide with master facets up to
// round-off). Every slave node whose facets lie inside the overlap, away
// from the faceted hole and the master's edge, is fully covered: sum_m
// M_sm = D_s, and its row carries linear fields over exactly.
TEUCHOS_UNIT_TEST(Mortar, MatchingFacetsOfAGmshMesh) {
  const Mesh::Mesh mesh = Mesh::readMeshFile(std::string(TRIBOS_INPUT_DIR) + "/lap_joint.msh");
  const auto coupling = Contact::mortarCoupling(mesh, "upper_bottom", "lower_top");
  int inside = 0;
  double worstCovered = 0, worstLinear = 0;
  for (const auto& node : coupling) {
    const auto& xs = mesh.coords[node.node];
    // The overlap is 20 < x < 40 outside the hole r < 3 around (30, 0);
    // the facets are at most 1.7 mm.
    if (xs[0] > 40 - 3.5 || std::hypot(xs[0] - 30, xs[1]) < 3 + 1.8) continue;
    ++inside;
    worstCovered = std::max(worstCovered, std::abs(node.covered() - node.area) / node.area);
    double linear = 0;
    for (const auto& [m, value] : node.M) linear += value * (1 + 0.2 * mesh.coords[m][0] - 0.3 * mesh.coords[m][1]);
    worstLinear = std::max(worstLinear, std::abs(linear / node.covered() - (1 + 0.2 * xs[0] - 0.3 * xs[1])));
  }
  out << inside << " slave nodes inside: largest |sum_m M_sm - D_s| / D_s " << worstCovered
      << ", largest error of a linear field " << worstLinear << "\n";
  TEST_COMPARE(inside, >, 100);
  TEST_COMPARE(worstCovered, <, 1e-10);
  TEST_COMPARE(worstLinear, <, 1e-10);
}

// The rule of second-order facets: every monomial s^a t^b of degree at
// most 8 over the unit triangle, cut into a fan, against a! b! / (a+b+2)!.
TEUCHOS_UNIT_TEST(Mortar, IntegratesPolynomialsOfDegreeEight) {
  const std::vector<Point2> triangle = {{0, 0}, {1, 0}, {0, 1}};
  auto factorial = [](int n) { return std::tgamma(n + 1.0); };
  double worst = 0;
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; a + b <= 8; ++b) {
      double m = 0;
      Contact::integratePolygon(triangle, [&](const Point2& p, double w) { m += w * std::pow(p[0], a) * std::pow(p[1], b); },
                                8);
      worst = std::max(worst, std::abs(m / (factorial(a) * factorial(b) / factorial(a + b + 2)) - 1));
    }
  out << "largest relative error of a monomial of degree <= 8: " << worst << "\n";
  TEST_COMPARE(worst, <, 1e-13);
}

// The transformed basis of second-order facets (a flat 6-node triangle and
// an 8-node parallelogram, tilted in space, mid-edge nodes at the middle
// of their edges): it sums to one; int N~ dA is 2A/15 at a triangle's
// corners and A/5 at its mid-edge nodes, A/20 and A/5 on the quadrilateral
// (alpha = 1/5, all positive where int N_c dA is 0 and -A/12); and the
// dual basis built on it is biorthogonal to it.
TEUCHOS_UNIT_TEST(Mortar, TransformedBasisOfSecondOrderFacets) {
  const Vec3 o{0.2, -0.1, 0.3}, e1{1.3, 0.2, 0.4}, e2{-0.3, 0.9, 0.5};
  auto at = [&](double s, double t) {
    return Vec3{o[0] + s * e1[0] + t * e2[0], o[1] + s * e1[1] + t * e2[1], o[2] + s * e1[2] + t * e2[2]};
  };
  const double A = norm(cross(e1, e2));
  struct Case {
    std::vector<Point2> points;  // in (s, t) of the parallelogram o + s e1 + t e2
    double corner, mid;          // int N~ dA / area
  };
  const std::vector<Case> cases = {
      {{{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}, 2.0 / 15, 1.0 / 5},
      {{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0}, {1, 0.5}, {0.5, 1}, {0, 0.5}}, 1.0 / 20, 1.0 / 5}};
  for (const Case& c : cases) {
    Mesh::Mesh mesh;
    std::vector<int> nodes;
    for (const Point2& p : c.points) nodes.push_back(mesh.numNodes()), mesh.coords.push_back(at(p[0], p[1]));
    const Contact::SurfaceElement e(Mesh::Facet{nodes, 0}, mesh);
    const int n = e.size(), corners = n / 2;
    const double area = c.points.size() == 6 ? A / 2 : A;
    const auto basis = Contact::dualBasis(e);
    std::vector<std::vector<double>> psiN(n, std::vector<double>(n, 0.0));
    std::vector<double> integral(n, 0.0);
    double N[8], sumErr = 0;
    Contact::integratePolygon(e.shape().corners(), [&](const Point2& xi, double w) {
      Contact::transformedShape(e.shape(), xi, N);
      const double dA = w * e.jacobian(xi);
      double sum = 0;
      for (int j = 0; j < n; ++j) {
        sum += N[j];
        integral[j] += N[j] * dA;
        double psi = 0;
        for (int k = 0; k < n; ++k) psi += basis.A[j][k] * N[k];
        for (int k = 0; k < n; ++k) psiN[j][k] += psi * N[k] * dA;
      }
      sumErr = std::max(sumErr, std::abs(sum - 1));
    }, 8);
    TEST_COMPARE(sumErr, <, 1e-14);
    for (int j = 0; j < n; ++j) {
      const double expected = (j < corners ? c.corner : c.mid) * area;
      TEST_FLOATING_EQUALITY(integral[j], expected, 1e-13);
      TEST_FLOATING_EQUALITY(basis.D[j], expected, 1e-13);
      for (int k = 0; k < n; ++k) TEST_COMPARE(std::abs(psiN[j][k] - (j == k ? expected : 0.0)), <, 1e-13 * area);
    }
  }
}

// The search's rows: Mortar gives each slave node weights summing to one,
// the nodal normal, area D_s, and the gap of the lifted block; a name that
// is no discretization is refused by the validator.
TEUCHOS_UNIT_TEST(Mortar, SearchRows) {
  for (auto type : {Mesh::CellType::Hex8, Mesh::CellType::Tet4}) {
    const Mesh::Mesh mesh = stackedBoxes(type, 3, 4, 0.125);
    Contact::ContactPair pair;
    pair.name = "interface";
    pair.slave = "upper_bottom";
    pair.master = "lower_top";
    pair.discretization = Contact::ContactDiscretization::Mortar;
    std::vector<std::string> notes;
    const auto rows = Contact::contactConstraints(mesh, {pair}, &notes);
    TEST_EQUALITY(rows.size(), mesh.faceNodes("upper_bottom").size());
    TEST_ASSERT(notes.empty());
    const auto area = Fem::faceNodalAreas(mesh, "upper_bottom");
    for (const auto& c : rows) {
      double sum = 0;
      for (const auto& [m, w] : c.master) sum += w;
      TEST_COMPARE(std::abs(sum - 1), <, 1e-13);
      TEST_COMPARE(std::abs(c.gap - 0.125), <, 1e-13);
      TEST_COMPARE(std::abs(c.area - area[c.node]), <, 1e-14);
      TEST_COMPARE(std::abs(c.normal[2] + 1), <, 1e-14);
      TEST_COMPARE(std::abs(c.t1[2]) + std::abs(c.t2[2]), <, 1e-14);
    }
  }
  const auto v = Contact::discretizationValidator();
  TEST_ASSERT(v->getIntegralValue("Mortar") == Contact::ContactDiscretization::Mortar);
  TEST_ASSERT(v->getIntegralValue("Node To Segment") == Contact::ContactDiscretization::NodeToSegment);
  TEST_THROW(v->getIntegralValue("mortar"), std::exception);
}

// A slave surface wider than its master (x, y of the lower block scaled to
// [0, 0.76]): slave nodes beyond the master's edge take no part; a node
// whose segments cover less than half its area keeps a node-to-segment row
// where its closest point lies on the master; the search says both.
TEUCHOS_UNIT_TEST(Mortar, SlaveBeyondMaster) {
  Mesh::Mesh mesh = stackedBoxes(Mesh::CellType::Hex8, 3, 4);
  std::vector<char> lower(mesh.numNodes(), 0);
  for (int c = 0; c < mesh.numCells(); ++c)
    if (mesh.cellBody[c] == 0)
      for (int a = 0; a < mesh.nodesPerCell(); ++a) lower[mesh.cell(c)[a]] = 1;
  for (int n = 0; n < mesh.numNodes(); ++n)
    if (lower[n]) mesh.coords[n][0] *= 0.76, mesh.coords[n][1] *= 0.76;
  Contact::ContactPair pair;
  pair.name = "interface";
  pair.slave = "upper_bottom";
  pair.master = "lower_top";
  pair.discretization = Contact::ContactDiscretization::Mortar;
  std::vector<std::string> notes;
  const auto rows = Contact::contactConstraints(mesh, {pair}, &notes);
  for (const auto& n : notes) out << n << "\n";
  // Slave nodes x, y in {0, 0.25, 0.5, 0.75} have rows; along one axis the
  // node at 0.75 keeps 0.5776 of its int psi_s (its outer facet covered up
  // to 0.04 of its width), so the corner (0.75, 0.75) keeps 0.334 < 0.5:
  // node-to-segment. Nodes at 1 are beyond the master.
  TEST_EQUALITY(rows.size(), 16u);
  int nodeToSegment = 0;
  for (const auto& c : rows) {
    TEST_COMPARE(std::max(mesh.coords[c.node][0], mesh.coords[c.node][1]), <, 0.76);
    const bool corner = mesh.coords[c.node][0] == 0.75 && mesh.coords[c.node][1] == 0.75;
    nodeToSegment += corner;
    if (corner) TEST_COMPARE(c.master.size(), <=, 4u);
  }
  TEST_EQUALITY(nodeToSegment, 1);
  TEST_EQUALITY(notes.size(), 2u);
}

}  // namespace
