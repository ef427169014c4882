// embed: an application that meshes and assembles a contact problem its own
// way and solves it through Tribos' public API (FetiProblem from assembled
// subdomains, Contact::solveFeti).
//
// The body: the block [0,2]x[0,1]x[0,1] of steel, two subdomains [0,1] and
// [1,2] along x (one per rank on 2 ranks), n hexahedra per unit length. It
// is clamped at x = 0, pressed onto a rigid plane z = 0 by the traction
// (0,0,-4e7) on z = 1 and pushed by (-2e7,0,0) on x = 2, with Coulomb
// friction F = 0.3 on the plane. The application numbers the nodes, builds
// each subdomain's K and f from Tribos' element matrices, and writes the rows
// of B itself: gluing at x = 1 (orthonormal pairs), the clamp, and the
// normal and tangential rows of the bottom nodes.
//
// Checks (exit 1 if one fails): the solve converged (its KKT residuals, node
// by node, within the result check), and the displacement equals Tribos' own
// solve of the same block from its mesh generator to 1e-6.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_MpiStartup.hpp"

using namespace Tribos;

namespace {

const double kE = 21.2e10, kNu = 0.277, kPressure = 4e7, kPush = 2e7, kFriction = 0.3;

// The application's structured grid: (2n+1) x (n+1) x (n+1) nodes.
struct Grid {
  int n;
  int nx() const { return 2 * n; }
  int node(int i, int j, int k) const { return i + (nx() + 1) * (j + (n + 1) * k); }
  Fem::Point x(int i, int j, int k) const { return {double(i) / n, double(j) / n, double(k) / n}; }
  // Subdomain s holds the node columns i = s n .. (s+1) n; its local node number.
  int local(int s, int i, int j, int k) const { return (i - s * n) + (n + 1) * (j + (n + 1) * k); }
};

// One subdomain: K from Tribos' Hex8 element matrix, f from the tractions
// (a bilinear facet carries a quarter of its force at each corner).
Fem::SubdomainSystem assemble(const Grid& g, int s) {
  const int n = g.n, nl = (n + 1) * (n + 1) * (n + 1);
  Fem::SubdomainSystem sys;
  sys.id = s;
  sys.nodes.resize(nl);
  sys.coords.resize(nl);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = s * n; i <= (s + 1) * n; ++i) {
        sys.nodes[g.local(s, i, j, k)] = g.node(i, j, k);
        sys.coords[g.local(s, i, j, k)] = g.x(i, j, k);
      }
  Fem::Material mat;
  mat.E = kE;
  mat.nu = kNu;
  std::map<std::pair<int, int>, double> entries;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = s * n; i < (s + 1) * n; ++i) {
        const int c[8][3] = {{i, j, k},         {i + 1, j, k},         {i + 1, j + 1, k},     {i, j + 1, k},
                             {i, j, k + 1},     {i + 1, j, k + 1},     {i + 1, j + 1, k + 1}, {i, j + 1, k + 1}};
        std::vector<Fem::Point> X(8);
        int ln[8];
        for (int a = 0; a < 8; ++a) X[a] = g.x(c[a][0], c[a][1], c[a][2]), ln[a] = g.local(s, c[a][0], c[a][1], c[a][2]);
        const auto Ke = Fem::elementStiffness(Mesh::CellType::Hex8, X, mat);
        for (int a = 0; a < 24; ++a)
          for (int b = 0; b < 24; ++b) entries[{3 * ln[a / 3] + a % 3, 3 * ln[b / 3] + b % 3}] += Ke[a * 24 + b];
      }
  sys.K.rows = sys.K.cols = 3 * nl;
  sys.K.rowptr.assign(1, 0);
  int row = 0;
  for (const auto& [rc, v] : entries) {
    while (row < rc.first) sys.K.rowptr.push_back(static_cast<int>(sys.K.col.size())), ++row;
    sys.K.col.push_back(rc.second);
    sys.K.val.push_back(v);
  }
  while (row < 3 * nl) sys.K.rowptr.push_back(static_cast<int>(sys.K.col.size())), ++row;
  sys.f.assign(3 * nl, 0.0);
  const double quarter = 0.25 / (n * n);  // a quarter of a facet's area
  for (int j = 0; j < n; ++j)
    for (int i = s * n; i < (s + 1) * n; ++i)  // top facets: (0, 0, -p)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) sys.f[3 * g.local(s, i + a, j + b, n) + 2] -= kPressure * quarter;
  if (s == 1)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)  // end facets x = 2: (-q, 0, 0)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) sys.f[3 * g.local(s, 2 * n, j + a, k + b)] -= kPush * quarter;
  // R left empty: FetiProblem builds the rigid-body modes from the coordinates.
  return sys;
}

// The rows of B, all of them on every rank (FetiProblem keeps each rank's
// own; a larger application gives each rank only the rows of its subdomains).
Feti::FetiConstraints constraints(const Grid& g) {
  const int n = g.n;
  Feti::FetiConstraints fc;
  const double w = 1.0 / std::sqrt(2.0);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int c = 0; c < 3; ++c) {
        Feti::DualRow clamp{Feti::DualRow::Dirichlet};  // u_c = 0 at x = 0
        clamp.node = g.node(0, j, k);
        clamp.copies = {{0, g.local(0, 0, j, k), 1.0}};
        clamp.dir[c] = 1.0;
        fc.rows.push_back(clamp);
        fc.dirichlet[3LL * clamp.node + c] = 0.0;
        Feti::DualRow glue{Feti::DualRow::Gluing};  // (u_0 - u_1)_c / sqrt 2 = 0 at x = 1
        glue.node = g.node(n, j, k);
        glue.copies = {{0, g.local(0, n, j, k), w}, {1, g.local(1, n, j, k), -w}};
        glue.dir[c] = 1.0;
        fc.rows.push_back(glue);
      }
  // Contact with the plane z = 0 (outward normal -e_z, gap 0) in the frame
  // Tribos uses for a plane (Feti::tangents), on the subdomain of the lowest
  // number that holds the node; the clamped nodes are held already.
  fc.contactNormal = {0, 0, -1};
  fc.contactGap = 0.0;
  std::array<double, 3> t1, t2;
  Feti::tangents(fc.contactNormal, t1, t2);
  for (int j = 0; j <= n; ++j)
    for (int i = 1; i <= 2 * n; ++i) {
      const int s = i <= n ? 0 : 1;
      Feti::DualRow r{Feti::DualRow::Normal};
      r.node = g.node(i, j, 0);
      r.copies = {{s, g.local(s, i, j, 0), 1.0}};
      r.dir = {0, 0, -1};
      fc.rows.push_back(r);
      r.kind = Feti::DualRow::Tangent1;
      r.dir = t1;
      fc.rows.push_back(r);
      r.kind = Feti::DualRow::Tangent2;
      r.dir = t2;
      fc.rows.push_back(r);
      // Area of the bottom face around the node (for traction slip bounds;
      // Coulomb's bound F lambda_N does not use it).
      const double ax = (i == 0 || i == 2 * n) ? 0.5 : 1.0, ay = (j == 0 || j == n) ? 0.5 : 1.0;
      fc.contactArea[r.node] = ax * ay / (n * n);
    }
  return fc;
}

// Algorithm 2 to a tight tolerance, so that two solves of the same problem
// (rows in another order) agree to 1e-6.
Teuchos::ParameterList solverParameters() {
  Teuchos::ParameterList p("Solver");
  p.set("Outer Algorithm", "Algorithm2");
  p.sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  return p;
}

// The same block from Tribos' own mesh generator and constructor.
std::vector<double> referenceSolve(int n, const RCP<const Comm>& comm, std::vector<Fem::Point>& coords) {
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Hex8;
  spec.x = {0, 2};
  spec.cells = {2 * n, n, n};
  Mesh::DecompositionSpec dec;
  dec.grid = {2, 1, 1};
  const Mesh::Mesh whole = Mesh::generateBox(spec);  // every rank keeps its part of it
  Mesh::Discretization disc(whole, spec, dec, comm->getSize(), comm->getRank());
  Fem::Material mat;
  mat.E = kE;
  mat.nu = kNu;
  Fem::LoadCase loads;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  loads.dirichlet.push_back(clamp);
  loads.tractions.push_back({"zmax", {0, 0, -kPressure}});
  loads.tractions.push_back({"xmax", {-kPush, 0, 0}});
  Contact::ContactSpec contact;
  contact.enabled = true;
  auto problem = rcp(new Feti::FetiProblem(disc, mat, loads, Contact::faceContactConstraints(disc, contact, comm),
                                           Teuchos::ParameterList(), comm));
  Contact::FrictionSpec friction{"Coulomb", kFriction, 0.0};
  coords = whole.coords;
  // Every node on every rank: the comparison below looks nodes up by position.
  return Contact::solveFeti(problem, friction, solverParameters()).u.gathered();
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareMpiStartup();  // before MPI_Init
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int n = argc > 1 ? std::atoi(argv[1]) : 4;
  const bool root = comm->getRank() == 0;
  if (n < 1 || comm->getSize() > 2) {
    if (root) std::cerr << "usage: mpirun -np 1|2 embed [cells per unit length >= 1]\n";
    return 1;
  }
  try {
    const Grid g{n};
    // This rank's subdomains: both on one rank, one each on two.
    std::vector<Fem::SubdomainSystem> mine;
    for (int s = 0; s < 2; ++s)
      if (comm->getSize() == 1 || s == comm->getRank()) mine.push_back(assemble(g, s));
    Teuchos::ParameterList fetiParams;  // defaults: TFETI, CHOLMOD
    auto problem = rcp(new Feti::FetiProblem(std::move(mine), constraints(g), fetiParams, comm));
    const Contact::FrictionSpec friction{"Coulomb", kFriction, 0.0};
    const auto r = Contact::solveFeti(problem, friction, solverParameters());

    std::vector<Fem::Point> coords;
    const auto ref = referenceSolve(n, comm, coords);
    // The reference numbers nodes as the application does (x fastest);
    // compare by coordinates all the same. r.u holds the displacement of
    // the nodes of this rank's subdomains; each rank compares the nodes it
    // owns, and the largest difference is taken over the ranks.
    std::map<int, size_t> referenceNode;  // application node -> reference node
    for (size_t m = 0; m < coords.size(); ++m) {
      const auto& x = coords[m];
      referenceNode[g.node(int(std::lround(x[0] * n)), int(std::lround(x[1] * n)), int(std::lround(x[2] * n)))] = m;
    }
    double local[2] = {0, 0}, global[2];  // max |u - ref|, max |ref|
    for (int i = 0; i < r.u.layout().numOwned(); ++i) {
      const int node = r.u.layout().nodes()[i];
      const size_t m = referenceNode.at(node);
      for (int c = 0; c < 3; ++c) {
        local[0] = std::max(local[0], std::abs(r.u.at(node)[c] - ref[3 * m + c]));
        local[1] = std::max(local[1], std::abs(ref[3 * m + c]));
      }
    }
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, local, global);
    const double rel = global[0] / global[1];
    if (root) {
      std::cout << "embed: " << problem->primalMap()->getGlobalNumElements() << " primal dofs, "
                << problem->dualMap()->getGlobalNumElements() << " dual, " << r.counts.nodes << " contact nodes ("
                << r.counts.stick << " stick, " << r.counts.slip << " slip), " << r.iterations << " "
                << r.outerAlgorithm << " iterations, n_A = " << r.n_A << "\n"
                << "kkt equilibrium " << r.kkt.equilibrium << " dirichlet " << r.kkt.dirichlet << " nonpenetration "
                << r.kkt.nonpenetration << " complementarity " << r.kkt.complementarity << " friction_law "
                << r.kkt.frictionLaw << " limit " << r.verdict.limit << "\n"
                << "converged " << (r.verdict.converged ? "true" : "false") << " (" << r.verdict.stopReason << ")\n"
                << "max |u - u_tribos_mesh| / max |u| = " << rel << "\n";
    }
    const bool ok = r.verdict.converged && rel <= 1e-6 && r.counts.slip > 0 && r.counts.stick > 0;
    if (root && !ok) std::cerr << "embed: FAILED\n";
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "embed: error: " << e.what() << "\n";
    return 1;
  }
}
