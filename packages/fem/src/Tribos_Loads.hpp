// Tribos_Loads.hpp: boundary conditions and loads on named faces.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "Tribos_Elasticity.hpp"
#include "Tribos_Discretization.hpp"

namespace Tribos {
namespace Fem {

// u_c = value_c on a face for every component c with fix[c] (e.g. only u_z = 0).
struct DirichletCondition {
  std::string face;
  std::array<bool, 3> fix{true, true, true};
  Point value{0, 0, 0};
  // When set, the prescribed value at a node is field(x) instead of value
  // (e.g. a uniform-strain field for the patch test).
  std::function<Point(const Point&)> field;
};

struct TractionCondition {
  std::string face;
  Point traction{0, 0, 0};
};

struct LoadCase {
  std::vector<DirichletCondition> dirichlet;
  std::vector<TractionCondition> tractions;
  Point volumeForce{0, 0, 0};
};

// Global dof (3 node + c) -> prescribed value. Faces meeting at an edge may
// both constrain a dof; conflicting values are an error naming both faces.
std::map<long long, double> constrainedDofs(const Mesh::Mesh& mesh, const std::vector<DirichletCondition>& bcs);
// The same at the nodes of a rank's part, by mesh node numbers (3 node + c).
std::map<long long, double> constrainedDofs(const Mesh::Discretization& disc, const std::vector<DirichletCondition>& bcs);

// The area of a face attached to every mesh node (the integral of its shape
// function over the face; 0 off the face): a traction bound times it is the
// node's slip bound.
std::vector<double> faceNodalAreas(const Mesh::Mesh& mesh, const std::string& face);

}  // namespace Fem
}  // namespace Tribos
