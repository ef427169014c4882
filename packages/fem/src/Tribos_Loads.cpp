#include "Tribos_Loads.hpp"

#include <cmath>
#include <functional>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

namespace {

// meshNode: the number a node of `mesh` has in the keys and messages.
std::map<long long, double> constrainedDofs(const Mesh::Mesh& mesh, const std::vector<DirichletCondition>& bcs,
                                            const std::function<int(int)>& meshNode) {
  std::map<long long, double> dofs;
  std::map<long long, std::string> source;
  for (const auto& bc : bcs) {
    for (int n : mesh.faceNodes(bc.face)) {
      const Point value = bc.field ? bc.field(mesh.coords[n]) : bc.value;
      for (int c = 0; c < 3; ++c) {
        if (!bc.fix[c]) continue;
        const long long dof = 3LL * meshNode(n) + c;
        auto it = dofs.find(dof);
        if (it != dofs.end()) {
          TRIBOS_REQUIRE(std::abs(it->second - value[c]) <= 1e-12 * (1 + std::abs(value[c])),
                         "Dirichlet conditions on faces " << source[dof] << " and " << bc.face
                                                          << " prescribe different values at node " << meshNode(n));
          continue;
        }
        dofs[dof] = value[c];
        source[dof] = bc.face;
      }
    }
  }
  return dofs;
}

}  // namespace

std::map<long long, double> constrainedDofs(const Mesh::Mesh& mesh, const std::vector<DirichletCondition>& bcs) {
  return constrainedDofs(mesh, bcs, [](int n) { return n; });
}

std::map<long long, double> constrainedDofs(const Mesh::Discretization& disc, const std::vector<DirichletCondition>& bcs) {
  return constrainedDofs(disc.part, bcs, [&](int n) { return disc.meshNode(n); });
}

std::vector<double> faceNodalAreas(const Mesh::Mesh& mesh, const std::string& face) {
  std::vector<double> area(mesh.numNodes(), 0.0);
  for (const auto& facet : mesh.face(face)) {
    std::vector<Point> X;
    for (int n : facet.nodes) X.push_back(mesh.coords[n]);
    const auto w = facetNodalAreas(X);
    for (size_t a = 0; a < facet.nodes.size(); ++a) area[facet.nodes[a]] += w[a];
  }
  return area;
}

}  // namespace Fem
}  // namespace Tribos
