// From a mesh to the semismooth* contact problem: one assembly of the whole
// body, rigid-plane contact on a named face, Tresca slip bounds from a
// traction bound.
#include <Teuchos_Time.hpp>

#include <cmath>
#include <set>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Assembly.hpp"
#include "Tribos_Decomposition.hpp"
#include "Tribos_DirichletAtContact.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_SemismoothStarNewton.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Semismooth {

std::vector<ContactNode> contactFaceNodes(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                                          const std::string& contactFace, double gap, double slipBoundTraction) {
  std::vector<ContactNode> nodes;
  // Outward area-weighted nodal normals (facets are counter-clockwise seen
  // from outside) and nodal areas.
  const int N = mesh.numNodes();
  std::vector<std::array<double, 3>> normal(N, {0, 0, 0});
  std::vector<double> area(N, 0.0);
  for (const Mesh::Facet& facet : mesh.face(contactFace)) {
    std::vector<Fem::Point> X;
    for (int v : facet.nodes) X.push_back(mesh.coords[v]);
    const size_t nv = X.size();
    const Fem::Point& p0 = X[0];
    const Fem::Point& p1 = X[1];
    const Fem::Point& p2 = X[2];
    const Fem::Point& p3 = nv == 4 ? X[3] : X[0];
    // Quadrilateral: (x2 - x0) x (x3 - x1); triangle: (x1 - x0) x (x2 - x0).
    Vec3 e1, e2;
    for (int c = 0; c < 3; ++c) {
      e1[c] = nv == 4 ? p2[c] - p0[c] : p1[c] - p0[c];
      e2[c] = nv == 4 ? p3[c] - p1[c] : p2[c] - p0[c];
    }
    const Vec3 nrm = cross(e1, e2);
    const std::vector<double> w = Fem::facetNodalAreas(X);
    for (size_t a = 0; a < nv; ++a) {
      for (int c = 0; c < 3; ++c) normal[facet.nodes[a]][c] += nrm[c];
      area[facet.nodes[a]] += w[a];
    }
  }
  // A node whose normal displacement is prescribed is a Dirichlet node (e.g.
  // on a clamped face). Tangential components prescribed by a symmetry plane
  // do not take the node out of contact, they only remove that friction
  // direction (see RotatedSystem).
  for (int node : mesh.faceNodes(contactFace)) {
    const std::array<bool, 3> fixed{dirichlet.count(3LL * node) > 0, dirichlet.count(3LL * node + 1) > 0,
                                    dirichlet.count(3LL * node + 2) > 0};
    const PrescribedDirections kind = classifyPrescribed(normal[node], fixed);
    Fem::requireNoPrescribedPenetration(dirichlet, node, mesh.coords[node], normal[node], gap, {});
    if (slipBoundTraction > 0) Fem::requireNoPrescribedSlip(dirichlet, node, mesh.coords[node], normal[node], {});
    if (kind == PrescribedDirections::Normal) continue;
    if (kind == PrescribedDirections::Oblique) {
      const auto& X = mesh.coords[node];
      const auto& n = normal[node];
      const double len = norm(n);
      std::string oblique;
      for (int c = 0; c < 3; ++c)
        if (fixed[c] && std::abs(n[c]) > 1e-8 * len) oblique += std::string(oblique.empty() ? "" : ", ") + "xyz"[c];
      TRIBOS_REQUIRE(false, "semismooth*: contact node " << node << " at (" << X[0] << ", " << X[1] << ", " << X[2]
                                                         << ") of face \"" << contactFace << "\" has a Dirichlet condition on "
                                                         << oblique << ", which is neither its normal (" << n[0] / len
                                                         << ", " << n[1] / len << ", " << n[2] / len
                                                         << ") nor a tangent direction; the contact frame cannot "
                                                            "represent it");
    }
    ContactNode cn;
    cn.node = node;
    cn.normal = normal[node];
    cn.g = slipBoundTraction * area[node];
    cn.d = gap;
    nodes.push_back(cn);
  }
  return nodes;
}

ContactProblem buildContactProblem(const Mesh::Mesh& mesh, const Fem::Material& material, const Fem::LoadCase& loads,
                                   const std::string& contactFace, double gap, double slipBoundTraction,
                                   const Comm* comm) {
  TRIBOS_REQUIRE(slipBoundTraction >= 0, "semismooth*: negative slip bound traction " << slipBoundTraction);
  // One subdomain covering the mesh: its K and f are the global ones.
  const Mesh::Subdomain whole = Mesh::extractSubdomains(mesh, std::vector<int>(mesh.numCells(), 0), 1)[0];
  Fem::SubdomainSystem sys =
      comm ? Fem::assembleSubdomain(mesh, whole, material, loads, *comm) : Fem::assembleSubdomain(mesh, whole, material, loads);
  for (int i = 0; i < static_cast<int>(whole.nodes.size()); ++i)
    TRIBOS_REQUIRE(whole.nodes[i] == i, "semismooth*: the mesh has unused nodes");

  ContactProblem p;
  p.K = std::move(sys.K);
  p.f = std::move(sys.f);
  p.dirichlet = Fem::constrainedDofs(mesh, loads.dirichlet);
  p.coords = mesh.coords;

  p.contact = contactFaceNodes(mesh, p.dirichlet, contactFace, gap, slipBoundTraction);
  TRIBOS_REQUIRE(!p.contact.empty(),
                 "semismooth*: face \"" << contactFace << "\" has no node whose normal displacement is free");
  return p;
}

SemismoothResult solveFromMesh(const Mesh::Mesh& mesh, const Fem::Material& material, const Fem::LoadCase& loads,
                               const std::string& contactFace, double gap, double slipBoundTraction,
                               const Teuchos::ParameterList& params, std::ostream* log,
                               const RCP<const Comm>& comm) {
  Teuchos::Time timer("assembly");
  timer.start();
  // Built alike on every rank from the whole mesh: a refusal is the input's
  // fault, agreed on so that no rank aborts the others.
  ContactProblem problem;
  auto build = [&] {
    problem = buildContactProblem(mesh, material, loads, contactFace, gap, slipBoundTraction, comm.get());
  };
  if (comm.is_null()) build();
  else checkOnEveryRank(*comm, build);
  problem.comm = comm;
  timer.stop();
  SemismoothStarNewton solver(problem, params);
  SemismoothResult result = solver.solve(log);
  addAssembledVectors(problem, result);
  result.assemblySeconds = timer.totalElapsedTime();
  return result;
}

}  // namespace Semismooth
}  // namespace Tribos
