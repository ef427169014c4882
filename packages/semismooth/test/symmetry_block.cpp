// symmetry_block.cpp: contact nodes with a partial Dirichlet condition.
// A quarter of a compressed block: (0,1)^3, E = 1e9, nu = 0.3, symmetry
// planes u_x = 0 on xmin and u_y = 0 on ymin, u_z = -0.01 on zmax (f = 0),
// contact of zmin with the plane z = 0 at gap 0; Hex8 and Tet4, 4x4x4 cells.
//  (a) Frictionless (slip bound 0): the exact solution is uniform uniaxial
//      compression, u = (nu 0.01 x, nu 0.01 y, -0.01 z), contact pressure
//      p = E 0.01, so the normal force of contact node i is p times its
//      nodal area (computed here from the facets). Asserted at every node,
//      including the edge nodes on the symmetry planes (one tangential
//      direction fixed) and the corner (both fixed), for every
//      "Newton Solver" (and Dense Schur, KLU2, Nodal step sizes); the
//      Contact::resultKKT figures of the result are below 1e-6. Again with the
//      exact values prescribed as u_x on xmax and u_y on ymax (non-zero
//      prescribed tangential values at contact nodes).
//  (b) Tresca with a slip bound of 5 % and 30 % of p: the solution is not
//      uniform (friction holds the Poisson expansion back); every solver
//      gives resultKKT figures below 1e-6, all of them agree with Sparse
//      Direct, the symmetry-edge nodes are contact nodes, and the friction
//      force there has no component along the fixed direction.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "Tribos_ResultKKT.hpp"
#include "Tribos_SemismoothStarNewton.hpp"
#include "Tribos_TestSupport.hpp"

using namespace Tribos;

namespace {

const double E = 1e9, nu = 0.3, strain = 0.01;

struct Block {
  Mesh::Mesh mesh;
  Fem::Material material;
  Fem::LoadCase loads;
};

// shifted: also u_x = nu 0.01 on xmax and u_y = nu 0.01 on ymax, the values
// of the exact solution there, so that contact nodes carry non-zero
// prescribed tangential values (both at the corner (1, 1, 0)).
Block quarterBlock(Mesh::CellType type, bool shifted = false) {
  Block b;
  Mesh::BoxSpec spec;
  spec.cells = {4, 4, 4};
  spec.type = type;
  b.mesh = Mesh::generateBox(spec);
  b.material.E = E;
  b.material.nu = nu;
  Fem::DirichletCondition symX, symY, top;
  symX.face = "xmin";
  symX.fix = {true, false, false};
  symY.face = "ymin";
  symY.fix = {false, true, false};
  top.face = "zmax";
  top.fix = {false, false, true};
  top.value = {0, 0, -strain};
  b.loads.dirichlet = {symX, symY, top};
  if (shifted) {
    Fem::DirichletCondition right = symX, back = symY;
    right.face = "xmax";
    right.value = {nu * strain, 0, 0};
    back.face = "ymax";
    back.value = {0, nu * strain, 0};
    b.loads.dirichlet.push_back(right);
    b.loads.dirichlet.push_back(back);
  }
  return b;
}

// Nodal areas of the zmin face from its facets: a quarter of each
// rectangle, a third of each triangle (the consistent nodal forces of a
// uniform pressure on bilinear / linear facets).
std::map<int, double> nodalAreas(const Mesh::Mesh& mesh) {
  std::map<int, double> area;
  for (const Mesh::Facet& f : mesh.face("zmin")) {
    const auto& X0 = mesh.coords[f.nodes[0]];
    const auto& X1 = mesh.coords[f.nodes[1]];
    const auto& X2 = mesh.coords[f.nodes[2]];
    double a;
    if (f.nodes.size() == 4) {
      const auto& X3 = mesh.coords[f.nodes[3]];
      a = std::abs((X2[0] - X0[0]) * (X3[1] - X1[1]) - (X2[1] - X0[1]) * (X3[0] - X1[0])) / 2;
    } else {
      a = std::abs((X1[0] - X0[0]) * (X2[1] - X0[1]) - (X1[1] - X0[1]) * (X2[0] - X0[0])) / 2;
    }
    for (int v : f.nodes) area[v] += a / f.nodes.size();
  }
  return area;
}

Contact::ResultKKT kkt(const Semismooth::SemismoothResult& r, FrictionLaw law) {
  const auto comm = Tpetra::getDefaultComm();
  // Every contact node is held by one rank.
  std::vector<Contact::ContactNodeForce> forces;
  if (comm->getRank() == 0) forces = Semismooth::contactForces(r);
  // The result is the same on every rank: held everywhere, owned by rank 0.
  const auto layout = Fem::NodalLayout::everyNode(static_cast<int>(r.u.size() / 3), comm);
  return Contact::resultKKT(Fem::NodalVector(layout, r.u), Fem::NodalVector(layout, r.Ku), Fem::NodalVector(layout, r.f),
                        r.dirichlet, law, forces);
}

void printKKT(const std::string& what, const Contact::ResultKKT& k, Teuchos::FancyOStream& out) {
  out << what << ": KKT equilibrium " << k.equilibrium << ", dirichlet " << k.dirichlet << ", nonpenetration "
            << k.nonpenetration << ", complementarity " << k.complementarity << ", friction " << k.frictionLaw << "\n";
}

struct Variant {
  std::string name;
  Teuchos::ParameterList params;
};

std::vector<Variant> variants() {
  Teuchos::ParameterList base;
  base.set("Tolerance", 1e-10);
  std::vector<Variant> v;
  v.push_back({"Sparse Direct", base});
  v.push_back({"Dense Schur", base});
  v.back().params.set("Dense Schur", true);
  v.push_back({"Reduced CG", base});
  v.back().params.set("Newton Solver", "Reduced CG");
  v.push_back({"CG+MueLu", base});
  v.back().params.set("Newton Solver", "CG+MueLu");
  v.push_back({"KLU2, Nodal", base});
  v.back().params.set("Local Solver", "KLU2");
  v.back().params.set("Step Scaling", "Nodal");
  return v;
}

Semismooth::SemismoothResult solve(const Block& b, double slipBoundTraction, const Teuchos::ParameterList& params) {
  // "CG+MueLu" distributes its solves over all ranks; the others are serial.
  return Semismooth::solveFromMesh(b.mesh, b.material, b.loads, "zmin", 0.0, slipBoundTraction, params, nullptr,
                                   Tpetra::getDefaultComm());
}

// Every node of zmin is a contact node (the symmetry edges and the corner
// included), and all of them are in contact.
void checkContactSet(const Block& b, const Semismooth::SemismoothResult& r, const std::string& what,
                     Teuchos::FancyOStream& out, bool& success) {
  const std::vector<int> face = b.mesh.faceNodes("zmin");
  std::vector<int> nodes = r.contactNodes;
  std::sort(nodes.begin(), nodes.end());
  out << what << ": " << nodes.size() << " contact nodes for " << face.size() << " nodes of zmin\n";
  TEST_ASSERT(nodes == face);
  const std::vector<int> status = Semismooth::contactStatus(r);
  int edge = 0;
  for (size_t i = 0; i < r.contactNodes.size(); ++i) {
    const auto& X = b.mesh.coords[r.contactNodes[i]];
    TEST_INEQUALITY(status[i], 0);  // in contact
    edge += X[0] == 0 || X[1] == 0;
  }
  TEST_EQUALITY(edge, 9);  // contact nodes on the symmetry planes
}

// (a) the exact uniaxial compression.
void frictionless(Mesh::CellType type, bool shifted, Teuchos::FancyOStream& out, bool& success) {
  const Block b = quarterBlock(type, shifted);
  const std::map<int, double> area = nodalAreas(b.mesh);
  const double p = E * strain;
  for (const Variant& v : variants()) {
    const std::string what =
        Mesh::cellTypeName(type) + " frictionless" + (shifted ? " (u_x, u_y given on xmax, ymax)" : "") + ", " + v.name;
    const Semismooth::SemismoothResult r = solve(b, 0.0, v.params);
    out << what << ": " << r.iterations << " Newton steps, residual " << r.residuals.back() << "\n";
    TEST_ASSERT(r.converged);
    checkContactSet(b, r, what, out, success);

    double du = 0;
    for (int node = 0; node < b.mesh.numNodes(); ++node) {
      const auto& X = b.mesh.coords[node];
      const double exact[3] = {nu * strain * X[0], nu * strain * X[1], -strain * X[2]};
      for (int c = 0; c < 3; ++c) du = std::max(du, std::abs(r.u[3 * node + c] - exact[c]));
    }
    double dn = 0, dt = 0, ds = 0;
    const auto forces = Semismooth::contactForces(r);
    const auto slip = Semismooth::contactSlip(r);
    for (size_t i = 0; i < forces.size(); ++i) {
      const int node = forces[i].node;
      const auto& X = b.mesh.coords[node];
      dn = std::max(dn, std::abs(forces[i].normalForce - p * area.at(node)) / (p * area.at(node)));
      for (int c = 0; c < 3; ++c) dt = std::max(dt, std::abs(forces[i].tangentialForce[c]));
      const double exactSlip[3] = {nu * strain * X[0], nu * strain * X[1], 0.0};
      for (int c = 0; c < 3; ++c) ds = std::max(ds, std::abs(slip[i][c] - exactSlip[c]));
    }
    out << what << ": max |u - u_exact| " << du << ", max rel. error of the normal forces " << dn << "\n";
    TEST_COMPARE(du, <=, 1e-8 * strain);
    TEST_COMPARE(dn, <=, 1e-7);  // normal force vs p A_i, relative
    TEST_EQUALITY(dt, 0.0);      // frictionless contact: no tangential force
    // Without friction a node never sticks; only the corners whose both
    // tangential directions are fixed cannot slide.
    TEST_EQUALITY(r.numStick.back(), (shifted ? 4 : 1));
    TEST_COMPARE(ds, <=, 1e-8 * strain);  // slip vs the exact one
    const Contact::ResultKKT k = kkt(r, FrictionLaw::Frictionless);
    printKKT(what, k, out);
    std::string worst;
    const double worstValue = k.worst(&worst);
    out << what << ": worst KKT figure " << worst << "\n";
    TEST_COMPARE(worstValue, <, 1e-6);
  }
}

// (b) Tresca: no closed form; the KKT conditions of the written result.
void tresca(Mesh::CellType type, double boundFraction, Teuchos::FancyOStream& out, bool& success) {
  const Block b = quarterBlock(type);
  const double g = boundFraction * E * strain;
  Semismooth::SemismoothResult reference;
  for (const Variant& v : variants()) {
    const std::string what = Mesh::cellTypeName(type) + " Tresca " + std::to_string(boundFraction) + " p, " + v.name;
    const Semismooth::SemismoothResult r = solve(b, g, v.params);
    out << what << ": " << r.iterations << " Newton steps, residual " << r.residuals.back() << ", stick "
        << r.numStick.back() << ", slip " << r.numSlip.back() << "\n";
    TEST_ASSERT(r.converged);
    checkContactSet(b, r, what, out, success);
    const Contact::ResultKKT k = kkt(r, FrictionLaw::Tresca);
    printKKT(what, k, out);
    std::string worst;
    const double worstValue = k.worst(&worst);
    out << what << ": worst KKT figure " << worst << "\n";
    TEST_COMPARE(worstValue, <, 1e-6);
    // The friction force has no part along a direction a symmetry plane
    // fixes, and it reaches the bound on the edges, which slide outwards.
    int edgeSlip = 0;
    for (size_t i = 0; i < r.contactNodes.size(); ++i) {
      const auto& X = b.mesh.coords[r.contactNodes[i]];
      if (X[0] == 0) TEST_EQUALITY(r.lambdaT[i][0], 0.0);  // no friction along the fixed x
      if (X[1] == 0) TEST_EQUALITY(r.lambdaT[i][1], 0.0);  // no friction along the fixed y
      edgeSlip += (X[0] == 0) != (X[1] == 0) && r.state[i] == Semismooth::NodeState::ContactSlip;
    }
    if (boundFraction < 0.1) TEST_EQUALITY(edgeSlip, 8);  // all 8 symmetry-edge nodes slide
    if (v.name == "Sparse Direct") {
      reference = r;
    } else {
      const double diff = Test::maxRelDiff(r.u, reference.u);
      out << what << ": u differs from Sparse Direct by " << diff << "\n";
      TEST_COMPARE(diff, <=, 1e-6);
    }
  }
}

}  // namespace

TEUCHOS_UNIT_TEST(Frictionless, Hex8) { frictionless(Mesh::CellType::Hex8, false, out, success); }
TEUCHOS_UNIT_TEST(Frictionless, Hex8TangentialValuesGiven) { frictionless(Mesh::CellType::Hex8, true, out, success); }
TEUCHOS_UNIT_TEST(Frictionless, Tet4) { frictionless(Mesh::CellType::Tet4, false, out, success); }
TEUCHOS_UNIT_TEST(Frictionless, Tet4TangentialValuesGiven) { frictionless(Mesh::CellType::Tet4, true, out, success); }

TEUCHOS_UNIT_TEST(Tresca, Hex8Bound5Percent) { tresca(Mesh::CellType::Hex8, 0.05, out, success); }
TEUCHOS_UNIT_TEST(Tresca, Hex8Bound30Percent) { tresca(Mesh::CellType::Hex8, 0.3, out, success); }
TEUCHOS_UNIT_TEST(Tresca, Tet4Bound5Percent) { tresca(Mesh::CellType::Tet4, 0.05, out, success); }
TEUCHOS_UNIT_TEST(Tresca, Tet4Bound30Percent) { tresca(Mesh::CellType::Tet4, 0.3, out, success); }
