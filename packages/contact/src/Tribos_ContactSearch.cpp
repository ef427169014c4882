#include "Tribos_ContactSearch.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "Tribos_AllGather.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Feti {

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
  return out;
}

// Weights below round-off are dropped (a node-matching slave node gets the
// one master node it sits on) and the rest rescaled to sum 1.
std::vector<std::pair<int, double>> significant(const std::vector<std::pair<int, double>>& w) {
  std::vector<std::pair<int, double>> out;
  double sum = 0;
  for (const auto& [node, value] : w)
    if (value > 1e-10) out.push_back({node, value}), sum += value;
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
// (pointing from the node into its partner) with the gap and master weights.
ContactConstraint constraint(int s, int index, const ContactPair& pair, const Vec3& n, double gap,
                             std::vector<std::pair<int, double>> master) {
  ContactConstraint c;
  c.node = s;
  c.pair = index;
  c.glued = pair.glued;
  c.master = std::move(master);
  c.normal = n;
  c.gap = gap;
  return c;
}

// Node-to-segment constraints of the slave nodes of one pair.
void slaveOnMaster(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& slaveNodes,
                   std::vector<ContactConstraint>& out, std::vector<int>& leftOut) {
  const auto& facets = mesh.face(pair.master);
  std::vector<Box> boxes;
  std::vector<char> isMasterNode(mesh.numNodes(), 0);
  for (const auto& f : facets) {
    Box b{mesh.coords[f.nodes[0]], mesh.coords[f.nodes[0]]};
    for (int n : f.nodes) {
      isMasterNode[n] = 1;
      for (int d = 0; d < 3; ++d) b.lo[d] = std::min(b.lo[d], mesh.coords[n][d]), b.hi[d] = std::max(b.hi[d], mesh.coords[n][d]);
    }
    boxes.push_back(b);
  }
  for (int s : slaveNodes) {
    TRIBOS_REQUIRE(!isMasterNode[s], "contact pair '" << pair.name << "': slave node " << s << " of '" << pair.slave
                                                      << "' is also a node of the master surface '" << pair.master
                                                      << "' (bodies that share their interface nodes are bonded); "
                                                         "mesh the two bodies separately for contact");
    const Vec3& x = mesh.coords[s];
    Projection best;
    best.distance = std::numeric_limits<double>::infinity();
    for (size_t f = 0; f < facets.size(); ++f) {
      if (boxes[f].distance(x) > best.distance) continue;
      Projection p = facets[f].nodes.size() == 3 ? projectOnTriangle(x, facets[f].nodes, mesh.coords)
                                                  : projectOnQuad(x, facets[f].nodes, mesh.coords);
      if (!p.onFacet) continue;
      p.distance = norm(minus(p.point, x));
      if (p.distance < best.distance) best = std::move(p);
    }
    if (!best.onFacet || best.distance > pair.searchDistance) {
      leftOut.push_back(s);
      continue;
    }
    const Vec3 n = {-best.outwardNormal[0], -best.outwardNormal[1], -best.outwardNormal[2]};
    out.push_back(constraint(s, index, pair, n, dot(minus(best.point, x), n), significant(best.weights)));
  }
}

void slaveOnPlane(const Mesh::Mesh& mesh, const ContactPair& pair, int index, const std::vector<int>& slaveNodes,
                  std::vector<ContactConstraint>& out, std::vector<int>& leftOut) {
  const Vec3& m = pair.planeNormal;
  for (int s : slaveNodes) {
    const double gap = dot(minus(mesh.coords[s], pair.planePoint), m);
    if (std::abs(gap) > pair.searchDistance) {
      leftOut.push_back(s);
      continue;
    }
    out.push_back(constraint(s, index, pair, {-m[0], -m[1], -m[2]}, gap, {}));
  }
}

}  // namespace

std::vector<ContactConstraint> contactConstraints(const Mesh::Mesh& mesh, const std::vector<ContactPair>& pairs,
                                                  std::vector<std::string>* notes) {
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
    }
    const std::vector<int> slaveNodes = mesh.faceNodes(pair.slave);
    for (int s : slaveNodes) {
      const auto [it, fresh] = pairOfNode.emplace(s, static_cast<int>(k));
      TRIBOS_REQUIRE(fresh, "node " << s << " is a slave node of contact pairs '" << pairs[it->second].name << "' and '"
                                    << pair.name << "': a node takes part in one pair only");
    }
    const size_t first = out.size();
    std::vector<int> leftOut;
    if (pair.master.empty())
      slaveOnPlane(mesh, pair, static_cast<int>(k), slaveNodes, out, leftOut);
    else
      slaveOnMaster(mesh, pair, static_cast<int>(k), slaveNodes, out, leftOut);
    const std::vector<double> area = Fem::faceNodalAreas(mesh, pair.slave);
    for (size_t i = first; i < out.size(); ++i) {
      ContactConstraint& c = out[i];
      tangents(c.normal, c.t1, c.t2);
      c.area = area[c.node];
    }
    if (!leftOut.empty() && notes) {
      std::ostringstream os;
      os << name << ": " << leftOut.size() << " of " << slaveNodes.size() << " slave nodes of '" << pair.slave
         << "' have no partner (" << (pair.master.empty() ? "farther from the plane than" : "no master facet under them within")
         << " the search distance) and take no part in the contact: nodes " << firstIds(leftOut);
      notes->push_back(os.str());
    }
    TRIBOS_REQUIRE(out.size() > first, name << ": none of the " << slaveNodes.size() << " nodes of '" << pair.slave
                                            << "' finds a partner on "
                                            << (pair.master.empty() ? std::string("the rigid plane")
                                                                    : "'" + pair.master + "'")
                                            << " within the search distance");
  }
  return out;
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

namespace {

// Each constraint as doubles: node, pair, glued, normal, t1, t2, gap, area,
// the number of master nodes, then (node, weight) per master node.
std::vector<double> packConstraints(const std::vector<ContactConstraint>& list) {
  std::vector<double> packed;
  for (const auto& c : list) {
    packed.insert(packed.end(), {double(c.node), double(c.pair), double(c.glued)});
    for (const auto* v : {&c.normal, &c.t1, &c.t2}) packed.insert(packed.end(), v->begin(), v->end());
    packed.insert(packed.end(), {c.gap, c.area, double(c.master.size())});
    for (const auto& [node, weight] : c.master) packed.insert(packed.end(), {double(node), weight});
  }
  return packed;
}

std::vector<ContactConstraint> unpackConstraints(const std::vector<double>& all) {
  std::vector<ContactConstraint> out;
  for (size_t i = 0; i < all.size();) {
    ContactConstraint c;
    c.node = static_cast<int>(all[i++]);
    c.pair = static_cast<int>(all[i++]);
    c.glued = all[i++] != 0.0;
    for (auto* v : {&c.normal, &c.t1, &c.t2})
      for (double& x : *v) x = all[i++];
    c.gap = all[i++];
    c.area = all[i++];
    const size_t masters = static_cast<size_t>(all[i++]);
    for (size_t m = 0; m < masters; ++m, i += 2) c.master.emplace_back(static_cast<int>(all[i]), all[i + 1]);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

std::vector<ContactConstraint> gatherContactConstraints(const std::vector<ContactConstraint>& local, const Comm& comm) {
  return unpackConstraints(allGatherv(packConstraints(local), comm));
}

std::vector<ContactConstraint> scatterContactConstraints(const std::vector<ContactConstraint>& onRoot,
                                                         const Mesh::Discretization& disc, const Comm& comm, int root) {
  const bool isRoot = comm.getRank() == root;
  std::vector<int> slaves;
  if (isRoot)
    for (const auto& c : onRoot) slaves.push_back(c.node);
  const auto owner = disc.askOwners(slaves, 1, [&](int, double* out) { out[0] = disc.myRank; }, comm);
  if (!isRoot) {
    ByteBuffer b = receiveBuffer(root, comm);
    return unpackConstraints(b.getVector<double>());
  }
  std::vector<std::vector<ContactConstraint>> perRank(comm.getSize());
  for (size_t i = 0; i < onRoot.size(); ++i) perRank[static_cast<int>(owner[i])].push_back(onRoot[i]);
  for (int r = 0; r < comm.getSize(); ++r) {
    if (r == root) continue;
    ByteBuffer b;
    b.put(packConstraints(perRank[r]));
    sendBuffer(b, r, comm);
  }
  return perRank[root];
}

std::array<double, 3> relativeDisplacement(const ContactConstraint& c, const Fem::NodalVector& u) {
  std::array<double, 3> w;
  for (int d = 0; d < 3; ++d) w[d] = u.at(c.node)[d];
  for (const auto& [node, weight] : c.master)
    for (int d = 0; d < 3; ++d) w[d] -= weight * u.at(node)[d];
  return w;
}

}  // namespace Feti
}  // namespace Tribos
