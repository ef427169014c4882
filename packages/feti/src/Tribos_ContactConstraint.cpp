#include "Tribos_ContactConstraint.hpp"

#include <cmath>

#include "Tribos_AllGather.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Feti {

void tangents(const std::array<double, 3>& n, std::array<double, 3>& t1, std::array<double, 3>& t2) {
  const std::array<double, 3> e = std::abs(n[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  t1 = normalized(cross(e, n));
  t2 = cross(n, t1);
}

namespace {

// Each constraint as doubles: node, pair, glued, normal, t1, t2, gap, area,
// the number of master nodes, then (node, weight) per master node, and the
// same for the slave side.
std::vector<double> packConstraints(const std::vector<ContactConstraint>& list) {
  std::vector<double> packed;
  for (const auto& c : list) {
    packed.insert(packed.end(), {double(c.node), double(c.pair), double(c.glued)});
    for (const auto* v : {&c.normal, &c.t1, &c.t2}) packed.insert(packed.end(), v->begin(), v->end());
    packed.insert(packed.end(), {c.gap, c.area, double(c.master.size())});
    for (const auto& [node, weight] : c.master) packed.insert(packed.end(), {double(node), weight});
    packed.push_back(double(c.slave.size()));
    for (const auto& [node, weight] : c.slave) packed.insert(packed.end(), {double(node), weight});
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
    const size_t slaves = static_cast<size_t>(all[i++]);
    for (size_t m = 0; m < slaves; ++m, i += 2) c.slave.emplace_back(static_cast<int>(all[i]), all[i + 1]);
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

std::vector<std::pair<int, double>> rowTerms(int node, const std::vector<std::pair<int, double>>& slave,
                                             const std::vector<std::pair<int, double>>& master) {
  std::vector<std::pair<int, double>> out;
  if (slave.empty()) out.push_back({node, 1.0});
  else out = slave;
  for (const auto& [m, weight] : master) out.push_back({m, -weight});
  return out;
}

std::vector<std::pair<int, double>> ContactConstraint::terms() const { return rowTerms(node, slave, master); }

std::array<double, 3> relativeDisplacement(const ContactConstraint& c, const Fem::NodalVector& u) {
  std::array<double, 3> w{0, 0, 0};
  for (const auto& [node, weight] : c.terms())
    for (int d = 0; d < 3; ++d) w[d] += weight * u.at(node)[d];
  return w;
}

}  // namespace Feti
}  // namespace Tribos
