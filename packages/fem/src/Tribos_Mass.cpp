#include "Tribos_Mass.hpp"

#include <cmath>

#include "Tribos_Assembly.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

namespace {

void requireDensity(double rho) {
  TRIBOS_REQUIRE(std::isfinite(rho) && rho > 0,
                 "density " << rho << ": a density must be positive and finite (the mass matrix must be "
                               "positive definite)");
}

// The rule exact for N_a N_b det J on Tet10 cells with straight sides and
// on hexahedra with straight edges (Tribos_Mass.hpp); for Tet10 it is
// cellQuadrature's 14 points.
std::vector<QuadraturePoint> massQuadrature(Mesh::CellType type) { return accurateQuadrature(type); }

// The scalar mass int rho N_a N_b dV (npc x npc, row-major).
std::vector<double> scalarMass(Mesh::CellType type, const std::vector<Point>& X, double rho) {
  const int npc = Mesh::nodesPerCell(type);
  std::vector<double> m(npc * npc, 0.0), dN;
  if (type == Mesh::CellType::Tet4) {
    const double volume = shapeGradients(type, X, {0, 0, 0}, dN) / 6.0;
    for (int a = 0; a < npc; ++a)
      for (int b = 0; b < npc; ++b) m[a * npc + b] = rho * volume * (a == b ? 2.0 : 1.0) / 20.0;
    return m;
  }
  // A second-order cell folded at a corner may show det J > 0 at every
  // quadrature point; the stiffness refuses it, and so does its mass.
  requirePositiveJacobianAtNodes(type, X);
  for (const QuadraturePoint& q : massQuadrature(type)) {
    const double w = rho * q.weight * shapeGradients(type, X, q.xi, dN);
    const std::vector<double> N = shapeFunctions(type, q.xi);
    for (int a = 0; a < npc; ++a)
      for (int b = a; b < npc; ++b) m[a * npc + b] += w * N[a] * N[b];
  }
  // Mirrored, not summed twice: (w N_a) N_b and (w N_b) N_a may differ in
  // the last bit, and M must be symmetric to the bit as K is.
  for (int a = 0; a < npc; ++a)
    for (int b = 0; b < a; ++b) m[a * npc + b] = m[b * npc + a];
  return m;
}

}  // namespace

BodyDensities::BodyDensities(double all) : perBody_{all} { requireDensity(all); }

BodyDensities::BodyDensities(std::vector<double> perBody) : perBody_(std::move(perBody)) {
  TRIBOS_REQUIRE(!perBody_.empty(), "BodyDensities: no density given");
  for (double rho : perBody_) requireDensity(rho);
}

std::vector<double> elementMass(Mesh::CellType type, const std::vector<Point>& X, double density) {
  requireDensity(density);
  const int npc = Mesh::nodesPerCell(type), n = 3 * npc;
  const std::vector<double> m = scalarMass(type, X, density);
  // Each component moves with its own inertia: M = m (x) I_3.
  std::vector<double> Me(n * n, 0.0);
  for (int a = 0; a < npc; ++a)
    for (int b = 0; b < npc; ++b)
      for (int c = 0; c < 3; ++c) Me[(3 * a + c) * n + 3 * b + c] = m[a * npc + b];
  return Me;
}

LocalCsr assembleSubdomainMass(const Mesh::Mesh& mesh, const Mesh::Subdomain& sub, const BodyDensities& rho) {
  return assembleCellMatrices(
      mesh, sub,
      [&](int cell, const std::vector<Point>& X) { return elementMass(mesh.cellType(cell), X, rho.ofCell(mesh, cell)); }, 0,
      sub.cells.size());
}

LocalCsr assembleSubdomainMass(const Mesh::Discretization& disc, int s, const BodyDensities& rho) {
  return assembleSubdomainMass(disc.part, disc.subdomain(s), rho);
}

}  // namespace Fem
}  // namespace Tribos
