#include "Tribos_ContactConditions.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Feti {

namespace {

bool finite(const std::array<double, 3>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// The node's constraint in Tribos' frame: n normalized, (t1, t2) = tangents(n).
ContactConstraint constraintOf(const ContactCondition& c, const std::string& name) {
  TRIBOS_REQUIRE(finite(c.normal) && norm(c.normal) > 0,
                 name << ": the normal (" << c.normal[0] << ", " << c.normal[1] << ", " << c.normal[2]
                      << ") is zero or not finite");
  TRIBOS_REQUIRE(std::isfinite(c.gap), name << ": the gap " << c.gap << " is not finite");
  TRIBOS_REQUIRE(std::isfinite(c.area) && c.area >= 0, name << ": the area " << c.area << " is negative or not finite");
  TRIBOS_REQUIRE(c.pair >= 0, name << ": the pair " << c.pair << " is negative");
  ContactConstraint cc;
  cc.node = c.node;
  cc.pair = c.pair;
  cc.normal = normalized(c.normal);
  tangents(cc.normal, cc.t1, cc.t2);
  cc.gap = c.gap;
  cc.area = c.area;
  double sum = 0;
  for (const auto& m : c.master) {
    TRIBOS_REQUIRE(std::isfinite(m.N), name << ": master node " << m.node << " has the weight " << m.N);
    cc.master.push_back({m.node, m.N});
    sum += m.N;
  }
  TRIBOS_REQUIRE(c.master.empty() || std::abs(sum - 1) <= 1e-10,
                 name << ": the weights N of its master nodes sum to " << sum << ", not 1");
  return cc;
}

}  // namespace

void addContactConditions(FetiConstraints& constraints, const std::vector<ContactCondition>& conditions,
                          const Comm& comm) {
  std::vector<DualRow> rows;
  std::vector<ContactConstraint> contact;
  checkOnEveryRank(comm, [&] {
    std::set<int> seen;
    for (size_t i = 0; i < conditions.size(); ++i) {
      const auto& c = conditions[i];
      const std::string name = "contact condition " + std::to_string(i) + " (node " + std::to_string(c.node) + ")";
      TRIBOS_REQUIRE(seen.insert(c.node).second, name << ": the node has a contact condition already");
      contact.push_back(constraintOf(c, name));
      // The rows on the copies the condition names, leaving out the
      // directions that the Dirichlet conditions fix there (a symmetry
      // plane through a contact node), as for a mesh's contact nodes.
      std::map<int, Mesh::NodeCopy> copyOf{{c.node, {c.subdomain, c.localNode}}};
      for (const auto& m : c.master) copyOf[m.node] = {m.subdomain, m.localNode};
      const double unknown = std::numeric_limits<double>::quiet_NaN();
      try {
        contactRows(contact.back(), [&](int node) { return copyOf.at(node); }, constraints.dirichlet,
                    {unknown, unknown, unknown}, false, rows);
      } catch (const Error& e) {
        throw Error(name + ": " + e.what());
      }
    }
  });
  constraints.rows.insert(constraints.rows.end(), rows.begin(), rows.end());
  constraints.contact.insert(constraints.contact.end(), contact.begin(), contact.end());
}

}  // namespace Feti
}  // namespace Tribos
