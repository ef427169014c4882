// The application interface: FetiProblem from assembled subdomains and rows
// of B, solved by Contact::solveFeti.
//  - The same problem through the mesh constructor and through the
//    application constructor (subdomains assembled by Fem, rows by
//    meshConstraintRows, handed over as an application would) gives the same
//    displacement, and the same on 1, 2 and 3 ranks (every rank count also
//    solves on rank 0 alone and compares).
//  - An application may give every rank all rows of B or only its own
//    (those on its subdomains): the same displacement either way; a mix
//    that would lose rows is refused.
//  - Misuse is refused before any work, naming what is wrong: sizes, a
//    kernel that is not one, ids out of order, rows naming missing nodes,
//    contact rows off the plane's frame.
//  - Subdomains whose K is positive definite (an implicit time step's
//    K + M / (beta dt^2), floating = false) solve without a coarse space, as
//    the dense solve of the same assembled matrix does.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <functional>
#include <set>
#include <string>

#include "Tribos_Assembly.hpp"
#include "Tribos_ContactConditions.hpp"
#include "Tribos_DenseCholesky.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mass.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;

// The seed brick, coarse: Tet4, 3 unit cubes along x, clamped at x = 0,
// pressed onto z = 0 and pushed along -x; Coulomb F = 0.3.
struct Brick {
  Mesh::BoxSpec spec;
  Mesh::DecompositionSpec dec;
  Fem::Material mat;
  Fem::LoadCase loads;
  Contact::ContactSpec contact;
  Brick() {
    spec.type = Mesh::CellType::Tet4;
    spec.x = {0, 3};
    spec.cells = {6, 2, 2};
    dec.grid = {3, 1, 1};
    mat.E = 21.2e10;
    mat.nu = 0.277;
    Fem::DirichletCondition clamp;
    clamp.face = "xmin";
    loads.dirichlet.push_back(clamp);
    loads.tractions.push_back({"zmax", {0, 0, -4e7}});
    loads.tractions.push_back({"xmax", {-2e7, 0, 0}});
    contact.enabled = true;
  }
  Mesh::Discretization disc(const Comm& comm) const {
    return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
  }
};

const Contact::FrictionSpec kCoulomb{FrictionLaw::Coulomb, 0.3, 0.0};

Teuchos::ParameterList tight() {
  Teuchos::ParameterList p;
  p.sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  p.sublist("Semismooth Newton").set("Relative Tolerance", 1e-10);  // Auto's for Coulomb where Dirichlet holds
  return p;
}

// What an application would hand over, built from the brick's mesh.
struct Handover {
  std::vector<Fem::SubdomainSystem> systems;
  Feti::FetiConstraints constraints;
};

Handover handover(const Brick& b, const Mesh::Discretization& disc) {
  Handover h;
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s) {
    h.systems.push_back(Fem::assembleSubdomain(disc, s, b.mat, b.loads));
    h.systems.back().R.clear();  // built again from the coordinates
  }
  // The application holds the whole mesh on every rank.
  const auto whole = Mesh::generateBox(b.spec);
  auto& fc = h.constraints;
  fc.dirichlet = Fem::constrainedDofs(whole, b.loads.dirichlet);
  const auto contact = b.contact.enabled ? Contact::contactConstraints(
                                               whole, {Contact::planeBeyondFace(whole, "zmin", b.contact.gap)})
                                         : std::vector<Feti::ContactConstraint>();
  fc.rows = Feti::meshConstraintRows(disc, fc.dirichlet, contact, "Orthonormal", false);
  if (!b.contact.enabled) return h;
  fc.contactNormal = Contact::faceNormal("zmin");
  const auto area = Fem::faceNodalAreas(whole, "zmin");
  for (int node : whole.faceNodes("zmin")) fc.contactArea[node] = area[node];
  return h;
}

Contact::FetiSolveResult solveApplication(Handover h, const RCP<const Comm>& comm) {
  auto problem = rcp(new Feti::FetiProblem(std::move(h.systems), std::move(h.constraints), Teuchos::ParameterList(), comm));
  return Contact::solveFeti(problem, kCoulomb, tight());
}

TEUCHOS_UNIT_TEST(ApplicationInterface, SameAsMeshPathOnEveryRankCount) {
  const auto comm = Tpetra::getDefaultComm();
  const Brick b;
  const auto disc = b.disc(*comm);
  auto meshProblem = rcp(new Feti::FetiProblem(disc, b.mat, b.loads, Contact::faceContactConstraints(disc, b.contact, comm),
                                               Teuchos::ParameterList(), comm));
  const auto viaMesh = Contact::solveFeti(meshProblem, kCoulomb, tight());
  const auto viaApp = solveApplication(handover(b, disc), comm);
  TEST_ASSERT(viaMesh.verdict.converged);
  TEST_ASSERT(viaApp.verdict.converged);
  TEST_COMPARE(viaApp.counts.slip, >, 0);
  const double d = Test::maxRelDiff(viaApp.u.gathered(), viaMesh.u.gathered());
  out << "application vs mesh path: " << d << "\n";
  TEST_COMPARE(d, <=, 1e-7);
  // Rank 0 alone (all three subdomains on one rank) gives the same.
  const auto gathered = viaApp.u.gathered();
  std::vector<double> serial(gathered.size());
  const auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  if (comm->getRank() == 0) serial = solveApplication(handover(b, b.disc(*self)), self).u.gathered();
  Teuchos::broadcast(*comm, 0, static_cast<int>(serial.size()), serial.data());
  const double dr = Test::maxRelDiff(gathered, serial);
  out << comm->getSize() << " ranks vs 1: " << dr << "\n";
  TEST_COMPARE(dr, <=, 1e-7);
}

// The brick's subdomains as an implicit time step sees them
// (docs/dynamics.md): K + M / (beta dt^2), trapezoidal rule (beta = 1/4),
// dt = 1e-4 s, steel's density; positive definite, no kernel, declared so
// (floating = false, R empty).
constexpr double kDensity = 7850, kMassShift = 1 / (0.25 * 1e-4 * 1e-4);

Handover timeStepHandover(const Brick& b, const Mesh::Discretization& disc, double massShift = kMassShift) {
  Handover h = handover(b, disc);
  for (size_t k = 0; k < h.systems.size(); ++k) {
    const LocalCsr M = Fem::assembleSubdomainMass(disc, disc.firstLocalSubdomain() + static_cast<int>(k), kDensity);
    auto& sys = h.systems[k];
    for (size_t i = 0; i < M.val.size(); ++i) sys.K.val[i] += massShift * M.val[i];  // K's pattern
    sys.R.clear();
    sys.floating = false;
  }
  return h;
}

// The displacement of the assembled K u = f of the handed-over subdomains
// (one rank holding them all), dense: the Dirichlet dofs fixed and, with
// contact, u_z >= 0 at the contact nodes by a primal active set
// (frictionless: the plane's reaction K u - f at an active dof pushes).
std::vector<double> denseSolve(const Handover& h, int numNodes) {
  const int N = 3 * numNodes;
  std::vector<double> K(static_cast<size_t>(N) * N, 0.0), f(N, 0.0);
  for (const auto& sys : h.systems)
    for (int i = 0; i < sys.numDofs(); ++i) {
      const int gi = 3 * sys.nodes[i / 3] + i % 3;
      f[gi] += sys.f[i];
      for (int k = sys.K.rowptr[i]; k < sys.K.rowptr[i + 1]; ++k) {
        const int j = sys.K.col[k];
        K[static_cast<size_t>(3 * sys.nodes[j / 3] + j % 3) * N + gi] += sys.K.val[k];
      }
    }
  std::vector<int> contactDofs;
  for (const auto& entry : h.constraints.contactArea) contactDofs.push_back(3 * entry.first + 2);
  std::set<int> active(contactDofs.begin(), contactDofs.end());
  for (int round = 0; round < 100; ++round) {
    std::vector<double> u(N, 0.0);
    std::vector<char> held(N, 0);
    for (const auto& [dof, value] : h.constraints.dirichlet) held[dof] = 1, u[dof] = value;
    for (int dof : active) held[dof] = 1, u[dof] = 0;
    std::vector<int> free;
    for (int i = 0; i < N; ++i)
      if (!held[i]) free.push_back(i);
    const int n = static_cast<int>(free.size());
    std::vector<double> A(static_cast<size_t>(n) * n), x(n);
    for (int a = 0; a < n; ++a) {
      x[a] = f[free[a]];
      for (int i = 0; i < N; ++i)
        if (held[i]) x[a] -= K[static_cast<size_t>(i) * N + free[a]] * u[i];
      for (int c = 0; c < n; ++c) A[static_cast<size_t>(c) * n + a] = K[static_cast<size_t>(free[c]) * N + free[a]];
    }
    DenseCholesky chol;
    TRIBOS_REQUIRE(chol.tryFactor(A, n), "denseSolve: the assembled matrix is singular");
    chol.solve(x);
    for (int a = 0; a < n; ++a) u[free[a]] = x[a];
    bool changed = false;
    for (int dof : contactDofs) {
      double reaction = -f[dof];
      for (int i = 0; i < N; ++i) reaction += K[static_cast<size_t>(i) * N + dof] * u[i];
      if (active.count(dof) && reaction < 0) active.erase(dof), changed = true;
      if (!active.count(dof) && u[dof] < 0) active.insert(dof), changed = true;
    }
    if (!changed) return u;
  }
  throw Error("denseSolve: the active set did not settle");
}

// FETI on positive definite subdomains: no coarse space (every kernel is
// empty), the displacement of the dense solve of the same assembled matrix,
// on 1, 2 and 3 ranks: clamped and free of any Dirichlet condition (the
// mass alone holds the body) without contact, and clamped on the rigid
// plane with frictionless contact.
TEUCHOS_UNIT_TEST(ApplicationInterface, PositiveDefiniteSubdomainsMatchDenseSolve) {
  const auto comm = Tpetra::getDefaultComm();
  const auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  struct Case {
    const char* name;
    bool clamped, contact;
  };
  for (const Case c : {Case{"clamped", true, false}, Case{"free", false, false}, Case{"on the plane", true, true}}) {
    Brick b;
    if (!c.clamped) b.loads.dirichlet.clear();
    b.contact.enabled = c.contact;
    Handover h = timeStepHandover(b, b.disc(*comm));
    auto problem = rcp(new Feti::FetiProblem(std::move(h.systems), std::move(h.constraints), Teuchos::ParameterList(), comm));
    TEST_EQUALITY(problem->hasContact(), c.contact);
    Teuchos::ParameterList params = tight();
    params.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-11);
    const auto r = Contact::solveFeti(problem, Contact::FrictionSpec{FrictionLaw::Frictionless, 0.0, 0.0}, params);
    out << c.name << ": outer algorithm " << r.outerAlgorithm << "\n";
    TEST_ASSERT(r.verdict.converged);
    TEST_EQUALITY(r.coarseSize, 0);
    const auto u = r.u.gathered();
    std::vector<double> reference(u.size());
    if (comm->getRank() == 0)
      reference = denseSolve(timeStepHandover(b, b.disc(*self)), Mesh::generateBox(b.spec).numNodes());
    Teuchos::broadcast(*comm, 0, static_cast<int>(reference.size()), reference.data());
    const double d = Test::maxRelDiff(u, reference);
    out << c.name << ": FETI vs dense " << d << (c.contact ? ", active contacts " : "")
        << (c.contact ? std::to_string(r.counts.active) : "") << "\n";
    TEST_COMPARE(d, <=, 1e-8);
    if (c.contact) TEST_COMPARE(r.counts.active, >, 0);
  }
}

// A step long against h / c (mass shift 4 / dt^2 with dt = 0.1 s: every
// subdomain's rigid motions held by an energy about 1e-6 of its elastic
// one) on the plane: the conjugate projector (Feti::ConjugateProjector)
// takes the subdomains' rigid motions out of F. With it and without, the
// result is the dense solve's to what the solver tolerance 1e-9 allows on
// a problem this ill-conditioned (seen: 5e-8); with it the solve takes
// fewer applications of F (seen: 46 against 313). F in double: in single
// precision its rounding, relative to ||F|| ~ 1 / (c m), is of the order of
// its elastic part here.
TEUCHOS_UNIT_TEST(ApplicationInterface, ConjugateProjectorOnLongSteps) {
  const auto comm = Tpetra::getDefaultComm();
  const auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  constexpr double kLongStepShift = 4 / (0.1 * 0.1);
  Brick b;
  b.contact.enabled = true;
  std::vector<double> reference;
  long long n_A[2] = {0, 0};
  for (const bool projector : {true, false}) {
    Handover h = timeStepHandover(b, b.disc(*comm), kLongStepShift);
    Teuchos::ParameterList feti;
    feti.set("Conjugate Projector", projector);
    feti.set("Dense Block Precision", "Double");
    auto problem = rcp(new Feti::FetiProblem(std::move(h.systems), std::move(h.constraints), feti, comm));
    Teuchos::ParameterList params;
    params.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-9);
    const auto r = Contact::solveFeti(problem, Contact::FrictionSpec{FrictionLaw::Frictionless, 0.0, 0.0}, params);
    TEST_ASSERT(r.verdict.converged);
    const auto u = r.u.gathered();
    if (reference.empty()) {
      reference.resize(u.size());
      if (comm->getRank() == 0)
        reference = denseSolve(timeStepHandover(b, b.disc(*self), kLongStepShift), Mesh::generateBox(b.spec).numNodes());
      Teuchos::broadcast(*comm, 0, static_cast<int>(reference.size()), reference.data());
    }
    const double d = Test::maxRelDiff(u, reference);
    n_A[projector ? 0 : 1] = r.n_A;
    TEST_COMPARE(d, <=, 1e-6);
    out << "conjugate projector " << (projector ? "on" : "off") << ": FETI vs dense " << d << ", n_A " << r.n_A
        << ", active contacts " << r.counts.active << "\n";
    TEST_COMPARE(r.counts.active, >, 0);
  }
  TEST_COMPARE(n_A[0], <, n_A[1]);
}

// A subdomain declared positive definite must be: a stiffness alone (its
// rigid-body motions free) and one that also gives R are refused, naming it.
TEUCHOS_UNIT_TEST(ApplicationInterface, PositiveDefiniteMisuseRefused) {
  const auto comm = Tpetra::getDefaultComm();
  const Brick b;
  const auto disc = b.disc(*comm);
  auto error = [&](const std::function<void(Handover&)>& spoil) {
    Handover h = timeStepHandover(b, disc);
    spoil(h);
    try {
      Feti::FetiProblem(std::move(h.systems), std::move(h.constraints), Teuchos::ParameterList(), comm);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = error([&](Handover& h) {
    h.systems = handover(b, disc).systems;
    for (auto& sys : h.systems) sys.floating = false;
  });
  out << e << "\n";
  TEST_ASSERT(e.find("declared positive definite (floating = false), but rigid-body motion 0 of its nodes has the "
                     "energy") != std::string::npos);
  e = error([&](Handover& h) {
    for (auto& sys : h.systems) sys.R = Fem::rigidBodyModes(sys.coords);
  });
  out << e << "\n";
  TEST_ASSERT(e.find("R has 6 columns, but the subdomain is declared positive definite") != std::string::npos);
}

// Every row of B, on every rank: the rows meshConstraintRows() gives each
// rank of the run, concatenated.
std::vector<Feti::DualRow> allRows(const Brick& b, const Handover& h, const Comm& comm) {
  std::vector<Feti::DualRow> rows;
  const auto mesh = Mesh::generateBox(b.spec);
  const auto contact = Contact::contactConstraints(mesh, {Contact::planeBeyondFace(mesh, "zmin", b.contact.gap)});
  for (int r = 0; r < comm.getSize(); ++r) {
    const Mesh::Discretization disc(mesh, b.spec, b.dec, comm.getSize(), r);
    const auto own = Feti::meshConstraintRows(disc, h.constraints.dirichlet, contact, "Orthonormal", false);
    rows.insert(rows.end(), own.begin(), own.end());
  }
  return rows;
}

TEUCHOS_UNIT_TEST(ApplicationInterface, AllRowsOrOwnRowsAlike) {
  const auto comm = Tpetra::getDefaultComm();
  const Brick b;
  const auto disc = b.disc(*comm);
  auto h = handover(b, disc);
  const auto own = solveApplication(h, comm);
  const size_t ownRows = h.constraints.rows.size();
  h.constraints.rows = allRows(b, h, *comm);
  out << "rows on this rank: own " << ownRows << ", all " << h.constraints.rows.size() << "\n";
  if (comm->getSize() > 1) TEST_COMPARE(h.constraints.rows.size(), >, ownRows);
  const auto all = solveApplication(h, comm);
  TEST_ASSERT(own.verdict.converged);
  TEST_ASSERT(all.verdict.converged);
  const double d = Test::maxRelDiff(all.u.gathered(), own.u.gathered());
  out << "all rows vs own rows: " << d << "\n";
  TEST_COMPARE(d, <=, 1e-12);
}

// Expects the application constructor to throw a message containing `what`.
void refused(const std::string& label, const std::function<void(Handover&)>& spoil, const std::string& what,
             Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  const Brick b;
  auto h = handover(b, b.disc(*comm));
  spoil(h);
  std::string message;
  try {
    Feti::FetiProblem(std::move(h.systems), std::move(h.constraints), Teuchos::ParameterList(), comm);
  } catch (const Error& e) {
    message = e.what();
  }
  out << label << ": " << message << "\n";
  TEST_ASSERT(message.find(what) != std::string::npos);
}

TEUCHOS_UNIT_TEST(ApplicationInterface, MisuseRefused) {
  const int me = Tpetra::getDefaultComm()->getRank();
  refused("short f", [&](Handover& h) { if (me == 0) h.systems[0].f.pop_back(); }, "f has", out, success);
  refused("wrong kernel", [&](Handover& h) {
            if (me != 0) return;
            auto& R = h.systems[0].R;
            R = Fem::rigidBodyModes(h.systems[0].coords);
            for (size_t i = 0; i < R.size() / 6; ++i) R[i] += 0.1 * std::sin(double(i));  // not a translation
          }, "is not in the kernel of K", out, success);
  refused("too few coordinates", [&](Handover& h) { if (me == 0) h.systems[0].coords.pop_back(); }, "coordinates for", out, success);
  refused("missing node", [&](Handover& h) { h.constraints.rows[0].copies[0].localNode = 100000; }, "has no local node", out, success);
  refused("missing subdomain", [&](Handover& h) { h.constraints.rows[0].copies[0].subdomain = 7; }, "subdomain 7 does not exist", out, success);
  refused("oblique tangent", [&](Handover& h) {
            for (auto& r : h.constraints.rows)
              if (r.kind == Feti::DualRow::Tangent1) r.dir = {0.6, 0.8, 0};
          }, "contact frame", out, success);
  refused("not a unit normal", [&](Handover& h) { h.constraints.contactNormal = {0, 0, -2}; }, "not a unit vector", out, success);
  refused("three modes", [&](Handover& h) {  // translations only
            for (auto& s : h.systems) {
              s.R = Fem::rigidBodyModes(s.coords);
              s.R.resize(s.R.size() / 2);
            }
          },
          "expected the 6 rigid-body modes", out, success);
  refused("contact on a Dirichlet dof", [&](Handover& h) {
            for (const auto& r : h.constraints.rows)  // a clamped node: Dirichlet rows on all components
              if (r.kind == Feti::DualRow::Dirichlet) {
                auto c = r;
                c.kind = Feti::DualRow::Normal;
                c.dir = h.constraints.contactNormal;
                c.c = 0;
                h.constraints.rows.push_back(c);
                break;
              }
          }, "acts on a dof that Dirichlet row", out, success);
  if (Tpetra::getDefaultComm()->getSize() > 1) {
    // The last rank also given one row of rank 0 (not all rows): rank 0's
    // row would be built twice or not at all.
    const Brick b;
    const auto comm = Tpetra::getDefaultComm();
    const auto all = allRows(b, handover(b, b.disc(*comm)), *comm);
    refused("a row on a rank that does not own it", [&](Handover& h) {
              if (me == comm->getSize() - 1) h.constraints.rows.push_back(all.front());
            }, "give every rank either all rows or only", out, success);
    refused("all rows on rank 0, own rows elsewhere", [&](Handover& h) {
              if (me == 0) h.constraints.rows = all;
            }, "give every rank either all rows or only", out, success);
  }
  // Reversed ids: a rank's subdomains out of order, or ranks out of order.
  refused("ids reversed", [&](Handover& h) { for (auto& s : h.systems) s.id = 2 - s.id; }, "ascending", out, success);
}

TEUCHOS_UNIT_TEST(ApplicationInterface, NegativeFrictionRefused) {
  const auto comm = Tpetra::getDefaultComm();
  const Brick b;
  const auto disc = b.disc(*comm);  // outlives the problem, which refers to it
  auto problem = rcp(new Feti::FetiProblem(disc, b.mat, b.loads, Contact::faceContactConstraints(disc, b.contact, comm),
                                           Teuchos::ParameterList(), comm));
  for (const Contact::FrictionSpec& bad : {Contact::FrictionSpec{FrictionLaw::Coulomb, -0.3, 0.0},
                                          Contact::FrictionSpec{FrictionLaw::Tresca, 0.0, -1e6},
                                          Contact::FrictionSpec{static_cast<FrictionLaw>(7), 0.3, 0.0}}) {
    std::string message;
    try {
      Contact::solveFeti(problem, bad, tight());
    } catch (const Error& e) {
      message = e.what();
    }
    out << static_cast<int>(bad.law) << " " << bad.coefficient << " " << bad.slipBoundTraction << ": " << message << "\n";
    TEST_ASSERT(message.find("must be a finite number >= 0") != std::string::npos ||
                message.find("valid laws are") != std::string::npos);
  }
  // A law by name: the names of the three laws, nothing else.
  TEST_ASSERT(frictionLawNamed("Tresca") == FrictionLaw::Tresca);
  std::string message;
  try {
    frictionLawNamed("Colomb", "Friction/Law");
  } catch (const Error& e) {
    message = e.what();
  }
  out << message << "\n";
  TEST_ASSERT(message.find("Friction/Law = \"Colomb\" is not a friction law") != std::string::npos);
}

}  // namespace

namespace {

// Contact conditions on a symmetry plane: the brick with u_y = 0 on y = 0
// (through contact nodes of the bottom face), its contact given as one
// ContactCondition per node after the Dirichlet conditions. The friction
// direction across the plane gets no row, as on the mesh path, and the two
// paths give the same displacement.
TEUCHOS_UNIT_TEST(ApplicationInterface, ContactConditionsOnSymmetryPlane) {
  const auto comm = Tpetra::getDefaultComm();
  Brick b;
  Fem::DirichletCondition symmetry;
  symmetry.face = "ymin";
  symmetry.fix = {false, true, false};
  b.loads.dirichlet.push_back(symmetry);
  const auto disc = b.disc(*comm);
  auto meshProblem = rcp(new Feti::FetiProblem(disc, b.mat, b.loads, Contact::faceContactConstraints(disc, b.contact, comm),
                                               Teuchos::ParameterList(), comm));
  const auto viaMesh = Contact::solveFeti(meshProblem, kCoulomb, tight());
  // The application: gluing and Dirichlet rows, then its conditions.
  Handover h;
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s)
    h.systems.push_back(Fem::assembleSubdomain(disc, s, b.mat, b.loads));
  const auto whole = Mesh::generateBox(b.spec);
  h.constraints.dirichlet = Fem::constrainedDofs(whole, b.loads.dirichlet);
  h.constraints.rows = Feti::meshConstraintRows(disc, h.constraints.dirichlet, {}, "Orthonormal", false);
  const auto area = Fem::faceNodalAreas(whole, "zmin");
  std::vector<Feti::ContactCondition> conditions;
  int onPlane = 0;
  for (int node : whole.faceNodes("zmin")) {
    const int n = disc.partNode(node);
    if (n < 0 || disc.nodeOwner()[n] != disc.myRank) continue;
    Feti::ContactCondition c;
    c.node = node;
    c.subdomain = disc.copies(n).front().subdomain;
    c.localNode = disc.copies(n).front().localNode;
    c.normal = {0, 0, -1};
    c.area = area[node];
    onPlane += h.constraints.dirichlet.count(3LL * node + 1) > 0;
    conditions.push_back(c);
  }
  Feti::addContactConditions(h.constraints, conditions, *comm);
  int planeNodes = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, onPlane, Teuchos::outArg(planeNodes));
  TEST_COMPARE(planeNodes, >, 0);
  const auto viaApp = solveApplication(h, comm);
  TEST_ASSERT(viaMesh.verdict.converged);
  TEST_ASSERT(viaApp.verdict.converged);
  const double d = Test::maxRelDiff(viaApp.u.gathered(), viaMesh.u.gathered());
  out << "conditions vs mesh path, symmetry plane through contact nodes: " << d << "\n";
  TEST_COMPARE(d, <=, 1e-7);
}

}  // namespace
