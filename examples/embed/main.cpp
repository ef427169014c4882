// embed: an application that meshes and assembles a contact problem its own
// way, as a Trilinos code does, and solves it through Tribos' embedding API
// (#include <Tribos.hpp>).
//
// The body: the block [0,2]x[0,1]x[0,1] of steel, two subdomains [0,1] and
// [1,2] along x (one per rank on 2 ranks), n hexahedra per unit length. It
// is clamped at x = 0, pressed onto a rigid plane z = 0 by the traction
// (0,0,-4e7) on z = 1 and pushed by (-2e7,0,0) on x = 2, with Coulomb
// friction F = 0.3 on the plane. The application numbers the nodes and
// assembles each subdomain's K as a Tpetra::CrsMatrix (element matrices
// summed in by insertGlobalValues) and f as a Tpetra::Vector; it writes the
// gluing and clamp rows of B, and states the contact as one condition per
// bottom node (its copy, the plane's outward normal, the gap, its area):
// Tribos builds the contact rows in its own frame. Every choice, friction
// included, is one parameter list; Contact::ContactSolver solves.
//
// Checks (exit 1 if one fails): the solve converged, every KKT residual of
// the result (equilibrium, Dirichlet values, non-penetration,
// complementarity, friction law; node by node) within the result check;
// the displacement equals Tribos' own solve of the same block from its mesh
// generator to 1e-6; the contact has a stick and a slip zone; the solver's
// valid parameters written as Teuchos XML read back with their validators.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <Tribos.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

using namespace Tribos;

namespace {

const double kE = 21.2e10, kNu = 0.277, kPressure = 4e7, kPush = 2e7;

// The application's structured grid: (2n+1) x (n+1) x (n+1) nodes.
struct Grid {
  int n;
  int nx() const { return 2 * n; }
  int node(int i, int j, int k) const { return i + (nx() + 1) * (j + (n + 1) * k); }
  Fem::Point x(int i, int j, int k) const { return {double(i) / n, double(j) / n, double(k) / n}; }
  // Subdomain s holds the node columns i = s n .. (s+1) n; its local node number.
  int local(int s, int i, int j, int k) const { return (i - s * n) + (n + 1) * (j + (n + 1) * k); }
};

// Subdomain s's dofs on one process: local dof 3 localNode + c has the
// global number 3 node + c (any global numbering would do).
RCP<const Map> dofMap(const std::vector<int>& nodes) {
  Teuchos::Array<GO> dofs;
  for (int node : nodes)
    for (int c = 0; c < 3; ++c) dofs.push_back(3LL * node + c);
  return rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), dofs(), 0,
                     rcp(new Teuchos::SerialComm<int>())));
}

// K from Tribos' Hex8 element matrix, summed into a CrsMatrix.
RCP<CrsMatrix> stiffness(const Grid& g, int s, const RCP<const Map>& map) {
  Fem::Material mat;
  mat.E = kE;
  mat.nu = kNu;
  auto K = rcp(new CrsMatrix(map, 8 * 24));  // room for every element's entries of a row before they merge
  const int n = g.n;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = s * n; i < (s + 1) * n; ++i) {
        const int c[8][3] = {{i, j, k},     {i + 1, j, k},     {i + 1, j + 1, k},     {i, j + 1, k},
                             {i, j, k + 1}, {i + 1, j, k + 1}, {i + 1, j + 1, k + 1}, {i, j + 1, k + 1}};
        std::vector<Fem::Point> X(8);
        Teuchos::Array<GO> dofs(24);
        for (int a = 0; a < 8; ++a) {
          X[a] = g.x(c[a][0], c[a][1], c[a][2]);
          for (int q = 0; q < 3; ++q) dofs[3 * a + q] = 3LL * g.node(c[a][0], c[a][1], c[a][2]) + q;
        }
        const auto Ke = Fem::elementStiffness(Mesh::CellType::Hex8, X, mat);
        for (int a = 0; a < 24; ++a) K->insertGlobalValues(dofs[a], dofs(), Teuchos::ArrayView<const SC>(&Ke[24 * a], 24));
      }
  K->fillComplete();
  return K;
}

// f from the tractions (a bilinear facet carries a quarter of its force at
// each corner).
RCP<Vector> load(const Grid& g, int s, const RCP<const Map>& map) {
  auto f = rcp(new Vector(map));
  const int n = g.n;
  const double quarter = 0.25 / (n * n);  // a quarter of a facet's area
  for (int j = 0; j < n; ++j)
    for (int i = s * n; i < (s + 1) * n; ++i)  // top facets: (0, 0, -p)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) f->sumIntoLocalValue(3 * g.local(s, i + a, j + b, n) + 2, -kPressure * quarter);
  if (s == 1)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)  // end facets x = 2: (-q, 0, 0)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) f->sumIntoLocalValue(3 * g.local(s, 2 * n, j + a, k + b), -kPush * quarter);
  return f;
}

Feti::TpetraSubdomain subdomain(const Grid& g, int s) {
  const int n = g.n;
  Feti::TpetraSubdomain sub;
  sub.id = s;
  sub.nodes.resize((n + 1) * (n + 1) * (n + 1));
  sub.coords.resize(sub.nodes.size());
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = s * n; i <= (s + 1) * n; ++i) {
        sub.nodes[g.local(s, i, j, k)] = g.node(i, j, k);
        sub.coords[g.local(s, i, j, k)] = g.x(i, j, k);
      }
  const auto map = dofMap(sub.nodes);
  sub.K = stiffness(g, s, map);
  sub.f = load(g, s, map);
  // R left null: Tribos builds the six rigid-body modes from the coordinates.
  return sub;
}

// The gluing and clamp rows of B, all of them on every rank (FetiProblem
// keeps each rank's own; a larger application gives each rank only the
// rows of its subdomains).
Feti::FetiConstraints glueAndClamp(const Grid& g) {
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
  return fc;
}

// Contact with the plane z = 0 (outward normal -e_z, gap 0) at every bottom
// node that is not clamped, on the subdomain of lowest number that holds
// it. The area of the bottom face around the node is Tresca's; Coulomb's
// bound F lambda_N does not use it.
std::vector<Feti::ContactCondition> bottomContact(const Grid& g) {
  const int n = g.n;
  std::vector<Feti::ContactCondition> conditions;
  for (int j = 0; j <= n; ++j)
    for (int i = 1; i <= 2 * n; ++i) {
      Feti::ContactCondition c;
      c.node = g.node(i, j, 0);
      c.subdomain = i <= n ? 0 : 1;
      c.localNode = g.local(c.subdomain, i, j, 0);
      c.normal = {0, 0, -1};
      c.gap = 0.0;
      const double ax = i == 2 * n ? 0.5 : 1.0, ay = (j == 0 || j == n) ? 0.5 : 1.0;
      c.area = ax * ay / (n * n);
      conditions.push_back(c);
    }
  return conditions;
}

// Every choice in one list (ContactSolver::validParameters() documents
// it): the FETI problem's (defaults: TFETI, CHOLMOD), the outer algorithm,
// Algorithm 2 to a tight tolerance (so that two solves of the same problem
// with rows in another order agree to 1e-6), and the friction.
RCP<Teuchos::ParameterList> parameters() {
  auto p = Teuchos::parameterList("embed");
  p->sublist("FETI");
  p->set("Outer Algorithm", "Algorithm2");
  p->sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", 0.3);
  return p;
}

// The solver's valid parameters (every choice, documented, with its
// validator) written as Teuchos XML, as a Trilinos application keeps them,
// and read back: the defaults pass the validators read back, and a
// friction law Tribos does not have does not.
bool validParametersThroughXml(const Teuchos::ParameterListAcceptor& solver) {
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(*solver.getValidParameters(), xml);
  const auto back = Teuchos::getParametersFromXmlString(xml.str());
  Teuchos::ParameterList defaults(*solver.getValidParameters());
  defaults.validateParameters(*back);  // throws for a default refused
  Teuchos::ParameterList unknownLaw;
  unknownLaw.sublist("Friction").set("Law", "Stribeck");
  try {
    unknownLaw.validateParameters(*back);
  } catch (const std::exception&) {
    return true;
  }
  return false;
}

// The same block from Tribos' own mesh generator, solved by the same
// solver object: every node's displacement on every rank (the comparison
// looks nodes up by position), and the nodes' coordinates.
std::vector<double> referenceSolve(int n, Contact::ContactSolver& solver, const Teuchos::ParameterList& feti,
                                   const RCP<const Comm>& comm, std::vector<Fem::Point>& coords) {
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
  solver.setProblem(rcp(
      new Feti::FetiProblem(disc, mat, loads, Contact::faceContactConstraints(disc, contact, comm), feti, comm)));
  solver.solve();
  coords = whole.coords;
  return solver.getResult().u.gathered();
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
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
    const auto params = parameters();
    Contact::ContactSolver solver;
    solver.setParameters(params);  // validated before any work, defaults filled in
    const bool xmlReadBack = validParametersThroughXml(solver);

    // This rank's subdomains: both on one rank, one each on two.
    std::vector<Feti::TpetraSubdomain> mine;
    for (int s = 0; s < 2; ++s)
      if (comm->getSize() == 1 || s == comm->getRank()) mine.push_back(subdomain(g, s));
    Feti::FetiConstraints rows = glueAndClamp(g);
    Feti::addContactConditions(rows, bottomContact(g), *comm);
    const auto problem = Feti::createFetiProblem(mine, std::move(rows), params->sublist("FETI"), comm);
    solver.setProblem(problem);
    const bool converged = solver.solve() == Contact::SolveStatus::Converged;
    const Contact::FetiSolveResult r = solver.getResult();  // a copy: the reference solve below reuses the solver

    std::vector<Fem::Point> coords;
    const auto ref = referenceSolve(n, solver, params->sublist("FETI"), comm, coords);
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
    const auto& kkt = r.kkt;
    const bool kktHolds = std::max({kkt.equilibrium, kkt.dirichlet, kkt.nonpenetration, kkt.complementarity,
                                    kkt.frictionLaw}) <= r.verdict.limit;
    if (root) {
      std::cout << "embed: " << problem->primalMap()->getGlobalNumElements() << " primal dofs, "
                << problem->dualMap()->getGlobalNumElements() << " dual, " << r.counts.nodes << " contact nodes ("
                << r.counts.stick << " stick, " << r.counts.slip << " slip), " << solver.getNumIters() << " "
                << r.outerAlgorithm << " iterations, n_A = " << r.n_A << "\n"
                << "kkt equilibrium " << kkt.equilibrium << " dirichlet " << kkt.dirichlet << " nonpenetration "
                << kkt.nonpenetration << " complementarity " << kkt.complementarity << " friction_law "
                << kkt.frictionLaw << " limit " << r.verdict.limit << "\n"
                << "converged " << (converged ? "true" : "false") << " (" << r.verdict.stopReason << ")\n"
                << "max |u - u_tribos_mesh| / max |u| = " << rel << "\n"
                << "valid parameters written as XML and read back: " << (xmlReadBack ? "true" : "false") << "\n";
    }
    const bool ok = converged && kktHolds && rel <= 1e-6 && r.counts.slip > 0 && r.counts.stick > 0 && xmlReadBack;
    if (root && !ok) std::cerr << "embed: FAILED\n";
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "embed: error: " << e.what() << "\n";
    return 1;
  }
}
