#include "Tribos_ContactSearch.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_AllGather.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mortar.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_RigidMotions.hpp"
#include "Tribos_ShapeFunctions.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Contact {

using Feti::ContactConstraint;

namespace {

// A point is on a facet when its parametric coordinates are inside up to
// this (relative) tolerance: a slave node on the edge of a node-matching
// interface must find the master node it sits on.
constexpr double kInside = 1e-8;

// The closest point of x on one master facet, when it lies on the facet.
struct Projection {
  bool onFacet = false;
  double distance = 0;
  Vec3 point{}, outwardNormal{};
  std::vector<std::pair<int, double>> weights;  // facet node, shape function value
  Point2 xi{};  // the reference coordinates of the point (Fem::facetShape's)
};

// Triangle: the plane's closest point in barycentric coordinates.
Projection projectOnTriangle(const Vec3& x, const std::vector<int>& v, const std::vector<Vec3>& X) {
  const Vec3 &a = X[v[0]], e1 = minus(X[v[1]], a), e2 = minus(X[v[2]], a), r = minus(x, a);
  const double m11 = dot(e1, e1), m12 = dot(e1, e2), m22 = dot(e2, e2), det = m11 * m22 - m12 * m12;
  const double s = (dot(r, e1) * m22 - dot(r, e2) * m12) / det, t = (dot(r, e2) * m11 - dot(r, e1) * m12) / det;
  Projection p;
  p.onFacet = s >= -kInside && t >= -kInside && s + t <= 1 + kInside;
  const double sc = std::clamp(s, 0.0, 1.0), tc = std::clamp(t, 0.0, 1.0 - sc);
  p.weights = {{v[0], 1 - sc - tc}, {v[1], sc}, {v[2], tc}};
  p.xi = {sc, tc};
  for (int d = 0; d < 3; ++d) p.point[d] = a[d] + sc * e1[d] + tc * e2[d];
  p.outwardNormal = normalized(cross(e1, e2));
  return p;
}

// Bilinear quadrilateral a, b, c, d at (xi, eta) in [-1, 1]^2: Gauss-Newton
// on the distance (exact in a few steps for the flat faces of hexahedra).
Projection projectOnQuad(const Vec3& x, const std::vector<int>& v, const std::vector<Vec3>& X) {
  static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  double xi = 0, eta = 0;
  Vec3 p{}, dxi{}, deta{};
  auto evaluate = [&] {
    p = dxi = deta = Vec3{0, 0, 0};
    for (int i = 0; i < 4; ++i) {
      const double N = (1 + sx[i] * xi) * (1 + sy[i] * eta) / 4;
      for (int d = 0; d < 3; ++d) {
        p[d] += N * X[v[i]][d];
        dxi[d] += sx[i] * (1 + sy[i] * eta) / 4 * X[v[i]][d];
        deta[d] += sy[i] * (1 + sx[i] * xi) / 4 * X[v[i]][d];
      }
    }
  };
  for (int it = 0; it < 30; ++it) {
    evaluate();
    const Vec3 r = minus(p, x);
    const double m11 = dot(dxi, dxi), m12 = dot(dxi, deta), m22 = dot(deta, deta), det = m11 * m22 - m12 * m12;
    const double g1 = dot(r, dxi), g2 = dot(r, deta);
    const double dx = -(g1 * m22 - g2 * m12) / det, de = -(g2 * m11 - g1 * m12) / det;
    xi += dx, eta += de;
    if (std::abs(dx) + std::abs(de) < 1e-14) break;
  }
  Projection out;
  out.onFacet = std::abs(xi) <= 1 + kInside && std::abs(eta) <= 1 + kInside;
  xi = std::clamp(xi, -1.0, 1.0), eta = std::clamp(eta, -1.0, 1.0);
  evaluate();
  out.point = p;
  out.outwardNormal = normalized(cross(dxi, deta));
  for (int i = 0; i < 4; ++i) out.weights.push_back({v[i], (1 + sx[i] * xi) * (1 + sy[i] * eta) / 4});
  out.xi = {xi, eta};
  return out;
}

// A facet of 3 or 4 nodes, or a second-order one: projected on the flat
// facet of its corners, its weights and point then those of the facet's
// own shape functions at the same reference coordinates (the closest point
// itself on a flat facet, whose mid-edge nodes lie on its plane).
Projection projectOnFacet(const Vec3& x, const Mesh::Facet& facet, const Mesh::Mesh& mesh) {
  const auto& v = facet.nodes;
  const int corners = v.size() == 3 || v.size() == 6 ? 3 : 4;
  const std::vector<int> c(v.begin(), v.begin() + corners);
  Projection p = corners == 3 ? projectOnTriangle(x, c, mesh.coords) : projectOnQuad(x, c, mesh.coords);
  if (static_cast<int>(v.size()) == corners) return p;
  const SurfaceElement e(facet, mesh);
  double N[Fem::kMaxNodesPerFacet], d1[Fem::kMaxNodesPerFacet], d2[Fem::kMaxNodesPerFacet];
  e.shape().evaluate(p.xi, N, d1, d2);
  p.weights.clear();
  for (size_t a = 0; a < v.size(); ++a) p.weights.push_back({v[a], N[a]});
  p.point = e.position(p.xi);
  p.outwardNormal = e.normal(p.xi);
  return p;
}

// Weights below round-off are dropped (a node-matching slave node gets the
// one master node it sits on) and the rest rescaled to sum 1 (those of a
// second-order facet may be negative).
std::vector<std::pair<int, double>> significant(const std::vector<std::pair<int, double>>& w) {
  std::vector<std::pair<int, double>> out;
  double sum = 0;
  for (const auto& [node, value] : w)
    if (std::abs(value) > 1e-10) out.push_back({node, value}), sum += value;
  for (auto& e : out) e.second /= sum;
  return out;
}

struct Box {
  Vec3 lo, hi;
  double distance(const Vec3& x) const {
    double s = 0;
    for (int d = 0; d < 3; ++d) {
      const double e = std::max({lo[d] - x[d], 0.0, x[d] - hi[d]});
      s += e * e;
    }
    return std::sqrt(s);
  }
};

std::string firstIds(const std::vector<int>& ids) {
  std::ostringstream os;
  for (size_t i = 0; i < ids.size() && i < 8; ++i) os << (i ? ", " : "") << ids[i];
  if (ids.size() > 8) os << ", ...";
  return os.str();
}

// The constraint of slave node s of pair `index` along the unit normal n
// (pointing from the node into its partner) with the gap, master weights
// and the node's area.
ContactConstraint constraint(int s, int index, const ContactPair& pair, const Vec3& n, double gap,
                             std::vector<std::pair<int, double>> master, double area) {
  ContactConstraint c;
  c.node = s;
  c.pair = index;
  c.glued = pair.glued;
  c.master = std::move(master);
  c.normal = n;
  c.gap = gap;
  c.area = area;
  Feti::tangents(c.normal, c.t1, c.t2);
  return c;
}

// The master surface of a pair: its facets with their bounding boxes.
struct MasterSurface {
  const std::vector<Mesh::Facet>& facets;
  std::vector<Box> boxes;
  std::vector<char> isMasterNode;
  MasterSurface(const Mesh::Mesh& mesh, const std::string& face)
      : facets(mesh.face(face)), isMasterNode(mesh.numNodes(), 0) {
    for (const auto& f : facets) {
      Box b{mesh.coords[f.nodes[0]], mesh.coords[f.nodes[0]]};
      for (int n : f.nodes) {
        isMasterNode[n] = 1;
        for (int d = 0; d < 3; ++d)
          b.lo[d] = std::min(b.lo[d], mesh.coords[n][d]), b.hi[d] = std::max(b.hi[d], mesh.coords[n][d]);
      }
      boxes.push_back(b);
    }
  }
};

bool secondOrderFace(const Mesh::Mesh& mesh, const std::string& face) {
  for (const auto& f : mesh.face(face))
    if (surfaceShape(static_cast<int>(f.nodes.size())).secondOrder()) return true;
  return false;
}

void requireNotOnMaster(const MasterSurface& surface, const ContactPair& pair, int s) {
  TRIBOS_REQUIRE(!surface.isMasterNode[s], "contact pair '" << pair.name << "': slave node " << s << " of '" << pair.slave
                                                            << "' is also a node of the master surface '" << pair.master
                                                            << "' (bodies that share their interface nodes are bonded); "
                                                               "mesh the two bodies separately for contact");
}

// The closest point of slave node s on the master surface within the search
// distance, if its projection lands on a facet.
bool closestPoint(const Mesh::Mesh& mesh, const MasterSurface& surface, const ContactPair& pair, int s,
                  Projection& best) {
  const Vec3& x = mesh.coords[s];
  best = Projection();
  best.distance = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < surface.facets.size(); ++f) {
    if (surface.boxes[f].distance(x) > best.distance) continue;
    Projection p = projectOnFacet(x, surface.facets[f], mesh);
    if (!p.onFacet) continue;
    p.distance = norm(minus(p.point, x));
    if (p.distance < best.distance) best = std::move(p);
  }
  return best.onFacet && best.distance <= pair.searchDistance;
}

// Node-to-segment constraints of the slave nodes of one pair.
void slaveOnMaster(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& slaveNodes,
                   std::vector<ContactConstraint>& out, std::vector<int>& leftOut) {
  const MasterSurface surface(mesh, pair.master);
  const std::vector<double> area = Fem::faceNodalAreas(mesh, pair.slave);
  for (int s : slaveNodes) {
    requireNotOnMaster(surface, pair, s);
    Projection best;
    if (!closestPoint(mesh, surface, pair, s, best)) {
      leftOut.push_back(s);
      continue;
    }
    const Vec3 n = {-best.outwardNormal[0], -best.outwardNormal[1], -best.outwardNormal[2]};
    out.push_back(
        constraint(s, index, pair, n, dot(minus(best.point, mesh.coords[s]), n), significant(best.weights), area[s]));
  }
}

// A slave node keeps its mortar row when its segments cover at least this
// share of its area: the dual shape functions are negative away from their
// node, so a partly covered node's int psi_s dA may be small or negative.
constexpr double kMortarCovered = 0.5;

// The slave side of the rows of a pair: the transformed value of each
// mid-edge node of a second-order slave surface (transformedNodes; empty
// for first-order ones), and the reference position the row sees there.
struct SlaveSide {
  std::map<int, std::vector<std::pair<int, double>>> transformed;
  SlaveSide(const Mesh::Mesh& mesh, const std::string& face) : transformed(transformedNodes(mesh, face)) {}
  std::vector<std::pair<int, double>> of(int s) const {
    const auto it = transformed.find(s);
    return it == transformed.end() ? std::vector<std::pair<int, double>>{} : it->second;
  }
  Vec3 position(const Mesh::Mesh& mesh, int s) const {
    const auto it = transformed.find(s);
    if (it == transformed.end()) return mesh.coords[s];
    Vec3 x{0, 0, 0};
    for (const auto& [b, weight] : it->second)
      for (int d = 0; d < 3; ++d) x[d] += weight * mesh.coords[b][d];
    return x;
  }
};

// The mortar row of one slave node divided by D_s: weights M_sm / D_s (those
// below round-off dropped, the rest summing to 1), the gap of the row
// applied to the reference positions, the area D_s.
ContactConstraint mortarConstraint(const Mesh::Mesh& mesh, const MortarNode& node, int index, const ContactPair& pair,
                                   const SlaveSide& side) {
  const double D = node.covered();
  std::vector<std::pair<int, double>> weights;
  double sum = 0;
  for (const auto& [m, value] : node.M)
    if (std::abs(value) > 1e-12 * D) weights.push_back({m, value / D}), sum += value / D;
  Vec3 xp{0, 0, 0};
  for (auto& [m, w] : weights) {
    w /= sum;
    for (int d = 0; d < 3; ++d) xp[d] += w * mesh.coords[m][d];
  }
  const double gap = dot(minus(xp, side.position(mesh, node.node)), node.normal);
  ContactConstraint c = constraint(node.node, index, pair, node.normal, gap, std::move(weights), D);
  c.slave = side.of(node.node);
  return c;
}

// Mortar constraints of the slave nodes of one pair; nodes covered too
// little take node-to-segment rows (`fallback`), on the same slave side.
void slaveOnMasterMortar(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& slaveNodes,
                         std::vector<ContactConstraint>& out, std::vector<int>& leftOut, std::vector<int>& fallback) {
  const MasterSurface surface(mesh, pair.master);
  for (int s : slaveNodes) requireNotOnMaster(surface, pair, s);
  const SlaveSide side(mesh, pair.slave);
  const std::vector<MortarNode> coupling = mortarCoupling(mesh, pair.slave, pair.master, pair.searchDistance);
  for (const MortarNode& node : coupling) {
    if (node.covered() >= kMortarCovered * node.area) {
      out.push_back(mortarConstraint(mesh, node, index, pair, side));
      continue;
    }
    Projection best;
    if (!closestPoint(mesh, surface, pair, node.node, best)) {
      leftOut.push_back(node.node);
      continue;
    }
    fallback.push_back(node.node);
    const Vec3 n = {-best.outwardNormal[0], -best.outwardNormal[1], -best.outwardNormal[2]};
    out.push_back(constraint(node.node, index, pair, n, dot(minus(best.point, side.position(mesh, node.node)), n),
                             significant(best.weights), node.area));
    out.back().slave = side.of(node.node);
  }
}

// The distance of slave node s from the pair's rigid plane (negative
// behind it).
double planeGap(const Mesh::Mesh& mesh, const ContactPair& pair, int s) {
  return dot(minus(mesh.coords[s], pair.planePoint), pair.planeNormal);
}

// A rigid plane: node rows with the node's area int N~_s dA, for both
// discretizations (the plane's gap is linear in x, so the weighted gap of
// mortar, int psi_s g dA, is D_s g(x~_s), and D_s = int N~_s dA; x~_s = x_s
// but at the mid-edge nodes of second-order facets, Tribos_Mortar.hpp).
void slaveOnPlane(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& slaveNodes,
                  std::vector<ContactConstraint>& out, std::vector<int>& leftOut) {
  const Vec3& m = pair.planeNormal;
  const std::vector<double> area = transformedAreas(mesh, pair.slave);
  const SlaveSide side(mesh, pair.slave);
  for (int s : slaveNodes) {
    const double gap = dot(minus(side.position(mesh, s), pair.planePoint), m);
    if (std::abs(gap) > pair.searchDistance) {
      leftOut.push_back(s);
      continue;
    }
    out.push_back(constraint(s, index, pair, {-m[0], -m[1], -m[2]}, gap, {}, area[s]));
    out.back().slave = side.of(s);
  }
}

void noteLeftOut(const ContactPair& pair, const std::vector<int>& leftOut, size_t slaveNodes,
                 std::vector<std::string>& notes) {
  if (leftOut.empty()) return;
  std::ostringstream os;
  os << "contact pair '" << pair.name << "': " << leftOut.size() << " of " << slaveNodes << " slave nodes of '"
     << pair.slave << "' have no partner ("
     << (pair.master.empty() ? "farther from the plane than" : "no master facet under them within")
     << " the search distance) and take no part in the contact: nodes " << firstIds(leftOut);
  notes.push_back(os.str());
}

void noteFallback(const ContactPair& pair, const std::vector<int>& fallback, size_t slaveNodes,
                  std::vector<std::string>& notes) {
  if (fallback.empty()) return;
  std::ostringstream os;
  os << "contact pair '" << pair.name << "': " << fallback.size() << " of " << slaveNodes << " slave nodes of '"
     << pair.slave << "' lie where '" << pair.master
     << "' covers less than half of their area and take node-to-segment rows instead of mortar ones: nodes "
     << firstIds(fallback);
  notes.push_back(os.str());
}

// The left-out nodes of a pair with their reference gaps: the distance to
// the closest point on a master facet (nodes whose projection lands on no
// facet cannot take a row, in any search, and are not listed), or to the
// plane.
void listLeftOut(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& leftOut,
                 std::vector<LeftOutNode>& list) {
  if (pair.master.empty()) {
    for (int s : leftOut) list.push_back({s, index, planeGap(mesh, pair, s)});
    return;
  }
  const MasterSurface surface(mesh, pair.master);
  ContactPair unlimited = pair;
  unlimited.searchDistance = std::numeric_limits<double>::infinity();
  for (int s : leftOut) {
    Projection best;
    if (closestPoint(mesh, surface, unlimited, s, best)) list.push_back({s, index, best.distance});
  }
}

}  // namespace

std::vector<ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                  std::vector<std::string>* notes) {
  ContactSearch found;
  auto out = contactConstraints(mesh, pairs, found);
  if (notes) notes->insert(notes->end(), found.notes.begin(), found.notes.end());
  return out;
}

double automaticSearchDistance(const Mesh::Mesh& mesh, const std::string& slave, double largestPrescribedDisplacement) {
  const std::vector<int> nodes = mesh.faceNodes(slave);
  if (nodes.empty()) return kAutoSearchDisplacements * largestPrescribedDisplacement;
  Vec3 lo = mesh.coords[nodes[0]], hi = lo;
  for (int n : nodes)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], mesh.coords[n][d]), hi[d] = std::max(hi[d], mesh.coords[n][d]);
  return std::max(kAutoSearchShare * norm(minus(hi, lo)), kAutoSearchDisplacements * largestPrescribedDisplacement);
}

double leftOutMargin(const LeftOutNode& node, const Vec3& u, bool plane, const Vec3& planeNormal, double masterMotion) {
  return plane ? node.gap + dot(u, planeNormal) : node.gap - norm(u) - masterMotion;
}

std::vector<ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                  ContactSearch& found) {
  static const auto timer = Teuchos::TimeMonitor::getNewCounter("Tribos::contact search");
  Teuchos::TimeMonitor timing(*timer);
  std::vector<ContactConstraint> out;
  std::map<int, int> pairOfNode;  // slave node -> pair
  for (size_t k = 0; k < pairs.size(); ++k) {
    const ContactPair& pair = pairs[k];
    const std::string name = "contact pair '" + pair.name + "'";
    mesh.face(pair.slave);  // throws naming the faces the mesh has
    TRIBOS_REQUIRE(pair.master != pair.slave, name << ": slave and master are the same surface '" << pair.slave << "'");
    TRIBOS_REQUIRE(pair.searchDistance > 0, name << ": search distance " << pair.searchDistance << " must be positive");
    if (pair.master.empty()) {
      const Vec3& m = pair.planeNormal;
      TRIBOS_REQUIRE(std::abs(norm(m) - 1) <= 1e-12 && std::isfinite(dot(pair.planePoint, pair.planePoint)),
                     name << ": the rigid plane's normal (" << m[0] << ", " << m[1] << ", " << m[2]
                          << ") must be a unit vector and its point finite");
    } else {
      mesh.face(pair.master);
      TRIBOS_REQUIRE(pair.discretization == ContactDiscretization::Mortar || !secondOrderFace(mesh, pair.slave),
                     name << ": the slave surface '" << pair.slave << "' has second-order facets, whose corner "
                          << "nodes carry no share (6-node triangles) or a negative one (8-node quadrilaterals) of a "
                             "uniform pressure: one node-to-segment row per node cannot transmit it; use "
                             "Discretization = Mortar (its transformed basis, docs/contact.md)");
    }
    const std::vector<int> slaveNodes = mesh.faceNodes(pair.slave);
    for (int s : slaveNodes) {
      const auto [it, fresh] = pairOfNode.emplace(s, static_cast<int>(k));
      TRIBOS_REQUIRE(fresh, "node " << s << " is a slave node of contact pairs '" << pairs[it->second].name << "' and '"
                                    << pair.name << "': a node takes part in one pair only");
    }
    const size_t first = out.size();
    std::vector<int> leftOut, fallback;
    auto search = [&](const ContactPair& p) {
      if (p.master.empty())
        slaveOnPlane(mesh, p, static_cast<int>(k), slaveNodes, out, leftOut);
      else if (p.discretization == ContactDiscretization::Mortar)
        slaveOnMasterMortar(mesh, p, static_cast<int>(k), slaveNodes, out, leftOut, fallback);
      else
        slaveOnMaster(mesh, p, static_cast<int>(k), slaveNodes, out, leftOut);
    };
    search(pair);
    // An automatic distance that leaves every node out says nothing of the
    // pair: search without a limit, so that the pair is what the input
    // made it (a pair within one body, say, is refused as such).
    ContactPair searched = pair;  // the pair as searched
    if (pair.automaticSearch && out.size() == first) {
      searched.searchDistance = std::numeric_limits<double>::infinity();
      searched.automaticSearch = false;
      leftOut.clear(), fallback.clear();
      search(searched);
    }
    // An automatic distance leaves nodes out by rule, and the rim nodes a
    // mortar pair gives node-to-segment rows are counted, not warned of:
    // the result check proves the left-out nodes stayed out.
    if (searched.automaticSearch) listLeftOut(mesh, searched, static_cast<int>(k), leftOut, found.leftOut);
    else {
      noteLeftOut(searched, leftOut, slaveNodes.size(), found.notes);
      noteFallback(searched, fallback, slaveNodes.size(), found.notes);
    }
    found.pairs.push_back({pair.name, pair.master, pair.planeNormal, searched.searchDistance, searched.automaticSearch,
                           static_cast<long long>(slaveNodes.size()),
                           static_cast<long long>(out.size() - first), static_cast<long long>(leftOut.size()),
                           static_cast<long long>(fallback.size())});
    TRIBOS_REQUIRE(out.size() > first, name << ": none of the " << slaveNodes.size() << " nodes of '" << pair.slave
                                            << "' finds a partner on "
                                            << (pair.master.empty() ? std::string("the rigid plane")
                                                                    : "'" + pair.master + "'")
                                            << " within the search distance");
  }
  return out;
}

namespace {

// Bodies joined by shared nodes: unit[b] the smallest body of b's unit, and
// the unit of every node (-1: no cell uses it).
struct BondedUnits {
  std::vector<int> unit, nodeUnit;
  explicit BondedUnits(const Mesh::Mesh& mesh) : unit(mesh.numBodies()), nodeUnit(mesh.numNodes(), -1) {
    for (size_t b = 0; b < unit.size(); ++b) unit[b] = static_cast<int>(b);
    std::vector<int> nodeBody(mesh.numNodes(), -1);
    for (int c = 0; c < mesh.numCells(); ++c)
      for (int a = 0; a < mesh.cellSize(c); ++a) {
        int& b = nodeBody[mesh.cell(c)[a]];
        if (b < 0) b = mesh.bodyOf(c);
        else join(b, mesh.bodyOf(c));
      }
    for (int n = 0; n < mesh.numNodes(); ++n)
      if (nodeBody[n] >= 0) nodeUnit[n] = root(nodeBody[n]);
  }
  int root(int b) { return unit[b] == b ? b : unit[b] = root(unit[b]); }
  void join(int a, int b) {
    a = root(a), b = root(b);
    unit[std::max(a, b)] = std::min(a, b);
  }
};

// Whether a pair's master surface faces its slave surface somewhere: at some
// slave node its contact normal (the master's inward normal) lies within 60
// degrees of the slave face's outward normal there.
bool masterFacesSlave(const Mesh::Mesh& mesh, const std::vector<ContactConstraint>& constraints, int pair,
                      const std::string& slave) {
  std::vector<Vec3> outward(mesh.numNodes(), Vec3{0, 0, 0});
  for (const Mesh::Facet& f : mesh.face(slave)) {
    const auto& x = mesh.coords;
    const Vec3 a = cross(minus(x[f.nodes[1]], x[f.nodes[0]]), minus(x[f.nodes.back()], x[f.nodes[0]]));
    for (int n : f.nodes)
      for (int d = 0; d < 3; ++d) outward[n][d] += a[d];
  }
  for (const auto& c : constraints)
    if (c.pair == pair && norm(outward[c.node]) > 0 && dot(c.normal, normalized(outward[c.node])) >= 0.5) return true;
  return false;
}

}  // namespace

void requireEveryBodyHeldAlone(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                               const std::vector<ContactPair>& pairs, const std::vector<char>& holdsTangentially,
                               const std::vector<ContactConstraint>& constraints) {
  BondedUnits units(mesh);
  for (int u = 0; u < mesh.numBodies(); ++u) {
    if (units.root(u) != u) continue;
    // The unit's nodes, numbered locally, then the points where a row's
    // master side in the unit acts (the weighted mean of its master nodes:
    // a rigid motion moves sum w_i x_i as it moves that point).
    std::vector<Vec3> coords;
    std::vector<int> local(mesh.numNodes(), -1);
    for (int n = 0; n < mesh.numNodes(); ++n)
      if (units.nodeUnit[n] == u) local[n] = static_cast<int>(coords.size()), coords.push_back(mesh.coords[n]);
    std::vector<Fem::HeldDirection> held;
    for (const auto& [dof, value] : dirichlet)
      if (local[dof / 3] >= 0) {
        Fem::HeldDirection h{local[dof / 3], {0, 0, 0}};
        h.direction[dof % 3] = 1;
        held.push_back(h);
      }
    std::vector<char> touches(pairs.size(), 0);  // pairs with rows between the unit and something else
    for (const auto& c : constraints) {
      bool master = false;  // a master node of the row in the unit
      double inUnit = 0;     // their weight (mortar weights may be negative)
      Vec3 xp{0, 0, 0};
      for (const auto& [m, w] : c.master) {
        if (units.nodeUnit[m] != u) continue;
        master = true, inUnit += w;
        for (int d = 0; d < 3; ++d) xp[d] += w * mesh.coords[m][d];
      }
      const bool slave = local[c.node] >= 0;
      int at = -1;  // the local point where the row acts on the unit alone
      if (slave && !master) {
        at = local[c.node];
      } else if (!slave && master && std::abs(inUnit) > 1e-12) {
        at = static_cast<int>(coords.size());
        coords.push_back({xp[0] / inUnit, xp[1] / inUnit, xp[2] / inUnit});
      }
      if (at < 0) continue;  // a row within the unit: internal forces only
      touches[c.pair] = 1;
      for (const auto& d : {c.normal, c.t1, c.t2}) {
        held.push_back({at, d});
        if (!holdsTangentially[c.pair]) break;
      }
    }
    if (coords.empty()) continue;
    const auto free = Fem::freeRigidMotions(coords, held);
    if (free.empty()) continue;
    std::string names, motions, on, why;
    int count = 0;
    for (int b = 0; b < mesh.numBodies(); ++b)
      if (units.root(b) == u) names += (count++ ? ", '" : "'") + mesh.bodyName(b) + "'";
    for (const auto& m : free) motions += (motions.empty() ? "" : ", ") + m;
    for (size_t p = 0; p < pairs.size(); ++p) {
      if (!touches[p]) continue;
      on += (on.empty() ? "'" : ", '") + pairs[p].name + "'";
      if (!pairs[p].master.empty() && !masterFacesSlave(mesh, constraints, static_cast<int>(p), pairs[p].slave))
        why += "; the master surface '" + pairs[p].master + "' of contact pair '" + pairs[p].name +
               "' does not face its slave surface '" + pairs[p].slave +
               "' (its normal lies more than 60 degrees from the slave's at every slave node), so the pair holds "
               "nothing along the slave's normal";
    }
    std::ostringstream os;
    os << (count == 1 ? "body " + names + " is" : "bodies " + names + " (bonded) are") << " free to move rigidly ("
       << motions << ") while the other bodies stay: no Dirichlet condition holds "
       << (count == 1 ? "it" : "them") << " and "
       << (on.empty() ? std::string("no contact pair acts on ") + (count == 1 ? "it" : "them")
                      : "contact pair(s) " + on + " hold only other motions")
       << why << "; add a Dirichlet condition that holds the motion, or correct the pairs";
    throw Error(os.str());
  }
}

ContactPair planeBeyondFace(const Mesh::Mesh& mesh, const std::string& face, double gap) {
  const Vec3 n = faceNormal(mesh, face);
  const Vec3& x0 = mesh.coords[mesh.faceNodes(face).front()];
  ContactPair pair;
  pair.name = face;
  pair.slave = face;
  pair.planeNormal = {-n[0], -n[1], -n[2]};
  for (int d = 0; d < 3; ++d) pair.planePoint[d] = x0[d] + gap * n[d];
  return pair;
}

std::vector<ContactConstraint> faceContactConstraints(const Mesh::Discretization& disc, const ContactSpec& contact,
                                                      const RCP<const Comm>& comm) {
  if (!contact.enabled) return {};
  const Mesh::Mesh& part = disc.part;
  std::vector<double> plane(7, 0.0);  // has facets, normal, point
  checkOnEveryRank(*comm, [&] {
    if (part.face(contact.face).empty()) return;
    const ContactPair p = planeBeyondFace(part, contact.face, contact.gap);
    plane = {1.0, p.planeNormal[0], p.planeNormal[1], p.planeNormal[2], p.planePoint[0], p.planePoint[1], p.planePoint[2]};
  });
  const std::vector<double> planes = allGatherv(plane, *comm);
  ContactPair pair;
  pair.name = pair.slave = contact.face;
  bool found = false;
  for (size_t r = 0; r < planes.size(); r += 7) {
    if (planes[r] == 0.0) continue;
    const std::array<double, 3> n{planes[r + 1], planes[r + 2], planes[r + 3]}, x{planes[r + 4], planes[r + 5], planes[r + 6]};
    if (!found) pair.planeNormal = n, pair.planePoint = x, found = true;
    double along = 0, offset = 0, size = 1;
    for (int d = 0; d < 3; ++d) {
      along += n[d] * pair.planeNormal[d];
      offset += (x[d] - pair.planePoint[d]) * pair.planeNormal[d];
      size = std::max({size, std::abs(x[d]), std::abs(pair.planePoint[d])});
    }
    TRIBOS_REQUIRE(along >= 1 - 1e-10 && std::abs(offset) <= 1e-10 * size,
                   "contact surface '" << contact.face << "' is not planar: the parts of rank " << r / 7
                                       << " and of a lower rank lie in different planes");
  }
  TRIBOS_REQUIRE(found, "contact surface '" << contact.face << "' has no facets");
  std::vector<ContactConstraint> local;
  checkOnEveryRank(*comm, [&] {
    if (!part.faceNodes(contact.face).empty()) local = contactConstraints(part, {pair});
  });
  std::vector<int> nodes;
  for (auto& c : local) nodes.push_back(c.node = disc.meshNode(c.node));
  // A node on the face between two parts has facets in both.
  const Fem::NodalLayout layout(nodes, comm);
  std::vector<double> area(3 * static_cast<size_t>(layout.numHeld()), 0.0);
  for (const auto& c : local) area[3 * static_cast<size_t>(layout.index(c.node))] = c.area;
  layout.sumOverHolders(area);
  for (auto& c : local) c.area = area[3 * static_cast<size_t>(layout.index(c.node))];
  return local;
}

// Outward unit normal of a face of the box.
std::array<double, 3> faceNormal(const std::string& face) {
  static const std::map<std::string, std::array<double, 3>> normals = {
      {"xmin", {-1, 0, 0}}, {"xmax", {1, 0, 0}}, {"ymin", {0, -1, 0}},
      {"ymax", {0, 1, 0}},  {"zmin", {0, 0, -1}}, {"zmax", {0, 0, 1}}};
  auto it = normals.find(face);
  TRIBOS_REQUIRE(it != normals.end(), "contact face \"" << face << "\" unknown; valid: xmin, xmax, ymin, ymax, zmin, zmax");
  return it->second;
}

std::array<double, 3> faceNormal(const Mesh::Mesh& mesh, const std::string& face) {
  const auto& facets = mesh.face(face);
  TRIBOS_REQUIRE(!facets.empty(), "contact surface '" << face << "' has no facets");
  // Area vectors: half the cross product of the triangle's edges from its
  // first node, or of the quadrilateral's diagonals (its mean plane). Built
  // from coordinate differences, so a facet in an axis plane has exactly
  // zero in-plane components and a box face gets the box table's normal.
  std::array<double, 3> sum{0, 0, 0}, lo = mesh.coords[facets[0].nodes[0]], hi = lo;
  std::vector<std::array<double, 3>> area;
  area.reserve(facets.size());
  for (const Mesh::Facet& f : facets) {
    const auto& x = mesh.coords;
    const auto& v = f.nodes;
    const bool quad = v.size() == 4;
    std::array<double, 3> u{}, w{};
    for (int d = 0; d < 3; ++d) {
      u[d] = x[v[quad ? 2 : 1]][d] - x[v[0]][d];
      w[d] = quad ? x[v[3]][d] - x[v[1]][d] : x[v[2]][d] - x[v[0]][d];
    }
    const Vec3 uw = cross(u, w), a{uw[0] / 2, uw[1] / 2, uw[2] / 2};
    for (int d = 0; d < 3; ++d) sum[d] += a[d];
    for (int node : v)
      for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], x[node][d]), hi[d] = std::max(hi[d], x[node][d]);
    area.push_back(a);
  }
  TRIBOS_REQUIRE(norm(sum) > 0, "contact surface '" << face << "' has no area");
  const Vec3 n = normalized(sum);
  // The rigid plane is one plane: every facet must face along n and every
  // node lie on the plane through the first, to round-off of the extent.
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const auto& x0 = mesh.coords[facets[0].nodes[0]];
  for (size_t i = 0; i < facets.size(); ++i) {
    const auto& a = area[i];
    bool planar = dot(a, n) >= (1 - 1e-10) * norm(a);
    for (int node : facets[i].nodes) {
      const auto& p = mesh.coords[node];
      planar = planar && std::abs(dot(minus(p, x0), n)) <= 1e-10 * extent;
    }
    TRIBOS_REQUIRE(planar, "contact surface '" << face << "' is not planar: its facet " << i << " (of cell "
                                               << facets[i].cell << ") leaves the plane of mean normal (" << n[0] << ", "
                                               << n[1] << ", " << n[2] << "); the contact partner is a rigid plane");
  }
  return n;
}

}  // namespace Contact
}  // namespace Tribos
