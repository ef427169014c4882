#include "Tribos_ConstraintRows.hpp"

#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_DirichletAtContact.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Feti {

namespace {

// Whether the unit direction dir of a contact row at a node lies in the span
// of the node's Dirichlet-fixed components (then the row would repeat the
// Dirichlet rows). A direction partly fixed has no meaning as a contact or
// friction direction: refused, naming the node.
bool fixedDirection(const std::array<double, 3>& dir, const std::array<bool, 3>& fixed, int node) {
  double inFixed = 0;
  for (int c = 0; c < 3; ++c)
    if (fixed[c]) inFixed += dir[c] * dir[c];
  TRIBOS_REQUIRE(inFixed < 1e-12 || inFixed > 1 - 1e-12,
                 "contact node " << node << ": its Dirichlet components fix part of the contact direction ("
                                 << dir[0] << ", " << dir[1] << ", " << dir[2]
                                 << "); a contact node may fix its normal or tangential components, not an oblique mix");
  return inFixed > 0.5;
}

}  // namespace

std::map<int, Mesh::NodeCopy> contactPartners(const Mesh::Discretization& disc,
                                              const std::vector<ContactConstraint>& contact,
                                              std::map<long long, double>& dirichlet, const Comm& comm) {
  std::vector<int> asked;
  for (const ContactConstraint& cc : contact) {
    const int n = disc.partNode(cc.node);
    if (n < 0 || disc.nodeOwner()[n] != disc.myRank) continue;
    for (const auto& [m, weight] : cc.terms())
      if (disc.partNode(m) < 0) asked.push_back(m);
  }
  // The owner answers: the node's first copy, then per component whether a
  // Dirichlet condition fixes it and its value.
  const auto answers = disc.askOwners(asked, 8,
                                      [&](int n, double* out) {
                                        const Mesh::NodeCopy first = disc.copies(n).front();
                                        out[0] = first.subdomain, out[1] = first.localNode;
                                        for (int c = 0; c < 3; ++c) {
                                          const auto it = dirichlet.find(3LL * disc.meshNode(n) + c);
                                          out[2 + c] = it != dirichlet.end();
                                          out[5 + c] = it != dirichlet.end() ? it->second : 0.0;
                                        }
                                      },
                                      comm);
  std::map<int, Mesh::NodeCopy> partners;
  for (size_t i = 0; i < asked.size(); ++i) {
    const double* a = &answers[8 * i];
    partners[asked[i]] = {static_cast<int>(a[0]), static_cast<int>(a[1])};
    for (int c = 0; c < 3; ++c)
      if (a[2 + c] != 0.0) dirichlet[3LL * asked[i] + c] = a[5 + c];
  }
  return partners;
}

void nodeRows(int node, const std::vector<Mesh::NodeCopy>& cp, const std::map<long long, double>& bc,
              const std::string& gluing, bool eliminateDirichlet, const std::function<void(const DualRow&)>& emit) {
  auto copyOf = [](const Mesh::NodeCopy& c, double weight) { return RowCopy{c.subdomain, c.localNode, weight}; };
  const int k = static_cast<int>(cp.size());
  const bool orthonormal = gluing == "Orthonormal", full = gluing == "Full";
  for (int c = 0; c < 3; ++c) {
    DualRow r{DualRow::Gluing};
    r.node = node;
    r.dir[c] = 1.0;
    auto dirichlet = bc.find(3LL * node + c);
    if (dirichlet != bc.end() && eliminateDirichlet) continue;  // eliminated in every copy
    if (dirichlet != bc.end()) {
      // Orthonormal: u = value on every copy (k orthonormal rows, no gluing
      // needed); otherwise on the first copy, the copies being glued.
      r.kind = DualRow::Dirichlet;
      r.c = dirichlet->second;
      for (int i = 0; i < (orthonormal ? k : 1); ++i) {
        r.copies = {copyOf(cp[i], 1.0)};
        emit(r);
      }
      if (orthonormal) continue;
      r.kind = DualRow::Gluing;
      r.c = 0.0;
    }
    if (orthonormal) {
      // Helmert rows: an orthonormal basis of {w in R^k : sum w = 0}.
      for (int j = 1; j < k; ++j) {
        const double s = 1.0 / std::sqrt(static_cast<double>(j) * (j + 1));
        r.copies.clear();
        for (int i = 0; i < j; ++i) r.copies.push_back(copyOf(cp[i], s));
        r.copies.push_back(copyOf(cp[j], -j * s));
        emit(r);
      }
      continue;
    }
    for (int i = 0; i + 1 < k; ++i)
      for (int j = i + 1; j < (full ? k : i + 2); ++j) {
        r.copies = {copyOf(cp[i], 1.0), copyOf(cp[j], -1.0)};
        emit(r);
      }
  }
}

void contactRows(const ContactConstraint& cc, const std::function<Mesh::NodeCopy(int)>& firstCopy,
                 const std::map<long long, double>& bc, const std::array<double, 3>& x, bool eliminateDirichlet,
                 std::vector<DualRow>& rows) {
  auto copyOf = [](const Mesh::NodeCopy& c, double weight) { return RowCopy{c.subdomain, c.localNode, weight}; };
  // A direction is left out when Dirichlet conditions fix it at the slave
  // node and at every master node (then the row would repeat theirs). A
  // Dirichlet condition on the normal takes the node out of the contact
  // set. A friction direction goes with a Dirichlet condition on it at the
  // slave node alone (a symmetry plane through the contact surface, where
  // the friction across the plane vanishes): the node cannot move along
  // it, and a mortar row, whose master weights reach off the plane, would
  // otherwise tie a weighted mean of the free masters' motion across the
  // plane with a multiplier that nothing determines well (the
  // Cattaneo-Mindlin half model with mortar: 1387 iterations of
  // Algorithm 2 for its first load step, 25 Newton steps without it).
  auto fixedAt = [&](int node, const std::array<double, 3>& dir) {
    std::array<bool, 3> fixed{};
    for (int c = 0; c < 3; ++c) fixed[c] = bc.count(3LL * node + c) > 0;
    return fixedDirection(dir, fixed, node);
  };
  const std::vector<std::pair<int, double>> terms = cc.terms();  // the slave side first
  auto fixedAtAll = [&](const std::array<double, 3>& dir) {
    for (const auto& [node, weight] : terms)
      if (!fixedAt(node, dir)) return false;
    return true;
  };
  // Out of the contact set (below) only if the values keep it out.
  if (!cc.glued) Fem::requireNoPrescribedPenetration(bc, cc.node, x, cc.normal, cc.gap, terms);
  if (!cc.glued && fixedAtAll(cc.normal)) return;
  DualRow r{cc.glued ? DualRow::Bonded : DualRow::Normal};
  r.node = cc.node;
  std::vector<int> copyNodes;
  for (const auto& [node, weight] : terms) {
    r.copies.push_back(copyOf(firstCopy(node), weight));
    copyNodes.push_back(node);
  }
  const std::array<double, 3>* dirs[3] = {&cc.normal, &cc.t1, &cc.t2};
  const DualRow::Kind kinds[3] = {DualRow::Normal, DualRow::Tangent1, DualRow::Tangent2};
  for (int j = 0; j < 3; ++j) {
    if (cc.glued ? fixedAtAll(*dirs[j]) : j > 0 && fixedAt(cc.node, *dirs[j])) continue;
    DualRow row = r;
    row.kind = cc.glued ? DualRow::Bonded : kinds[j];
    row.dir = *dirs[j];
    row.c = j == 0 && !cc.glued ? cc.gap : 0.0;
    // FETI-1 has eliminated the Dirichlet dofs from the subdomains, so the
    // row must not act on them (K+ would move them by B'lambda): a copy
    // whose node has the direction fixed (wholly, by fixedDirection) takes
    // weight 0 and its known part, weight * dir . ubar, moves to c.
    for (size_t k = 0; eliminateDirichlet && k < row.copies.size(); ++k) {
      if (!fixedAt(copyNodes[k], row.dir)) continue;
      double known = 0;
      for (int c = 0; c < 3; ++c) {
        const auto it = bc.find(3LL * copyNodes[k] + c);
        if (it != bc.end()) known += row.dir[c] * it->second;
      }
      row.c -= row.copies[k].weight * known;
      row.copies[k].weight = 0.0;
    }
    rows.push_back(row);
  }
}

std::vector<DualRow> meshConstraintRows(const Mesh::Discretization& disc, const std::map<long long, double>& bc,
                                        const std::vector<ContactConstraint>& contact, const std::string& gluing,
                                        bool eliminateDirichlet, const std::map<int, Mesh::NodeCopy>& partners) {
  const Mesh::Mesh& mesh = disc.part;  // the rank's part
  // The first copy of a mesh node: from the part, or a contact partner's.
  auto firstCopy = [&](int meshNode) {
    const int n = disc.partNode(meshNode);
    if (n >= 0) return disc.copies(n).front();
    const auto it = partners.find(meshNode);
    TRIBOS_REQUIRE(it != partners.end(), "contact partner node " << meshNode << " is neither in the part of rank "
                                                                 << disc.myRank << " nor among its partner nodes");
    return it->second;
  };
  // A row belongs to the rank of its first copy's subdomain; only this
  // rank's rows are kept (the dual numbering is made from the counts).
  std::vector<DualRow> rows;
  auto emit = [&](const DualRow& r) {
    if (disc.layout.owner(r.copies.front().subdomain) == disc.myRank) rows.push_back(r);
  };
  for (int n = 0; n < mesh.numNodes(); ++n) nodeRows(disc.meshNode(n), disc.copies(n), bc, gluing, eliminateDirichlet, emit);
  for (const ContactConstraint& cc : contact) {
    // The rows of a contact node start at its first copy.
    const int slave = disc.partNode(cc.node);
    if (slave < 0 || disc.nodeOwner()[slave] != disc.myRank) continue;
    contactRows(cc, firstCopy, bc, mesh.coords[slave], eliminateDirichlet, rows);
  }
  return rows;
}

void distributeRows(std::vector<DualRow>& rows, const std::vector<int>& owner) {
  for (auto& r : rows) r.owner = owner.at(r.copies.front().subdomain);
  auto group = [](const DualRow& r) { return r.kind == DualRow::Normal ? 1 : (r.kind >= DualRow::Tangent1 ? 2 : 0); };
  std::stable_sort(rows.begin(), rows.end(), [&](const DualRow& a, const DualRow& b) {
    return a.owner != b.owner ? a.owner < b.owner : group(a) < group(b);
  });
}

DualConstraints assembleConstraints(const std::vector<DualRow>& rows, const RCP<const Map>& primalMap,
                                    const std::vector<GO>& primalOffsets,
                                    const std::vector<ContactConstraint>& contact) {
  const RCP<const Comm>& comm = primalMap->getComm();
  const int me = comm->getRank();
  DualConstraints dc;
  // Rows are numbered rank after rank; the map follows from the counts, so
  // each rank needs only its own rows.
  long long mine = 0;
  for (const auto& r : rows) mine += r.owner == me;
  dc.dualMap = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), static_cast<size_t>(mine), 0, comm));
  const GO first = mine > 0 ? dc.dualMap->getMinGlobalIndex() : 0;
  size_t maxCopies = 1;
  for (const auto& r : rows) maxCopies = std::max(maxCopies, r.copies.size());
  dc.B = rcp(new CrsMatrix(dc.dualMap, 3 * maxCopies));
  dc.c = rcp(new Vector(dc.dualMap));
  auto cv = dc.c->getDataNonConst();
  GO gid = first;
  for (const auto& r : rows) {
    if (r.owner != me) continue;
    std::vector<GO> cols;
    std::vector<SC> vals;
    for (const auto& copy : r.copies) {
      if (copy.weight == 0.0) continue;  // a FETI-1 copy at eliminated dofs
      const GO base = primalOffsets[copy.subdomain] + 3 * static_cast<GO>(copy.localNode);
      for (int c = 0; c < 3; ++c)
        if (r.dir[c] != 0.0) cols.push_back(base + c), vals.push_back(copy.weight * r.dir[c]);
    }
    dc.B->insertGlobalValues(gid, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const SC>(vals));
    cv[gid - first] = r.c;
    dc.isEquality.push_back(r.kind == DualRow::Gluing || r.kind == DualRow::Dirichlet || r.kind == DualRow::Bonded);
    ++gid;
  }
  dc.B->fillComplete(primalMap, dc.dualMap);
  std::map<int, const ContactConstraint*> constraintOf;  // slave node -> its constraint
  for (const auto& c : contact) constraintOf[c.node] = &c;
  LocalContact& lc = dc.contact;
  // Rows of one node are on one rank: the normal row, then its tangential
  // rows (t1, t2; a direction fixed by a Dirichlet condition has none: -1).
  std::map<int, size_t> contactIndex;  // mesh node -> local contact number
  LO lid = 0;
  for (const auto& r : rows) {
    if (r.owner != me) continue;
    if (r.kind == DualRow::Normal) {
      contactIndex[r.node] = lc.nodes.size();
      lc.normalRows.push_back(lid);
      lc.nodes.push_back(r.node);
      const auto it = constraintOf.find(r.node);
      TRIBOS_REQUIRE(it != constraintOf.end(), "contact row of node " << r.node << " has no contact constraint");
      lc.constraint.push_back(*it->second);
      lc.nodalArea.push_back(it->second->area);
      lc.tangentRows.insert(lc.tangentRows.end(), {-1, -1});
    } else if (r.kind == DualRow::Tangent1 || r.kind == DualRow::Tangent2) {
      lc.tangentRows[2 * contactIndex.at(r.node) + (r.kind == DualRow::Tangent2)] = lid;
    } else if (r.kind == DualRow::Bonded) {
      const ContactConstraint& cc = *constraintOf.at(r.node);
      if (lc.bondedConstraint.empty() || lc.bondedConstraint.back().node != r.node) {
        lc.bondedConstraint.push_back(cc);
        lc.bondedRows.insert(lc.bondedRows.end(), {-1, -1, -1});
      }
      // Which of n, t1, t2 the row follows.
      const std::array<double, 3>* frame[3] = {&cc.normal, &cc.t1, &cc.t2};
      for (int j = 0; j < 3; ++j)
        if (*frame[j] == r.dir) lc.bondedRows[lc.bondedRows.size() - 3 + j] = lid;
    }
    ++lid;
  }
  return dc;
}

}  // namespace Feti
}  // namespace Tribos
