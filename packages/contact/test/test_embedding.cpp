// The embedding API: subdomains as Tpetra objects (Feti::TpetraSubdomain),
// contact as per-node conditions (Feti::addContactConditions), every choice
// in one parameter list, the solve as Contact::ContactSolver.
//  - A block of two subdomains (the seed brick of docs/benchmarks.md, Hex8,
//    clamped, pressed onto the plane z = 0 and pushed, Coulomb F = 0.3) is
//    solved through Fem::SubdomainSystem, hand-written contact rows and
//    solveFeti, and again with K a Tpetra::CrsMatrix (assembled by
//    sumIntoGlobalValues on a serial map of global dof numbers), a CrsMatrix
//    handed over as a Tpetra::Operator, and a matrix-free Operator (probed;
//    its matrix is K entry for entry);
//    contact conditions; the solver object: the same displacement, contact
//    counts and a converged verdict every time.
//  - Misuse is refused naming the parameter: K of the wrong size, on more
//    than one process, not symmetric, not fill-complete; R of the wrong
//    width, outside the kernel of K, missing for an Operator; f on another
//    map; an unknown friction law or entry; contact conditions with a zero
//    normal or a node given twice; a solve without a problem.
//  - Choices the solve would refuse are refused first, naming them: NSGS
//    and a value an outer algorithm refuses by setParameters; an algorithm
//    that does not solve the law of the problem's pairs, Tresca and Coulomb
//    pairs together, a dense Newton beyond its Dense Limit by setProblem.
//  - The solver set up through Teuchos::ParameterListAcceptor solves as
//    through its own methods.
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "Tribos.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;
using Test::contains;
using Test::errorOf;

const double kE = 21.2e10, kNu = 0.277, kPressure = 4e7, kPush = 2e7, kFriction = 0.3;

// [0,2]x[0,1]x[0,1], n hexahedra per unit length, subdomains [0,1] and [1,2].
struct Grid {
  int n = 2;
  int node(int i, int j, int k) const { return i + (2 * n + 1) * (j + (n + 1) * k); }
  Fem::Point x(int i, int j, int k) const { return {double(i) / n, double(j) / n, double(k) / n}; }
  int local(int s, int i, int j, int k) const { return (i - s * n) + (n + 1) * (j + (n + 1) * k); }
  int numLocal() const { return (n + 1) * (n + 1) * (n + 1); }
};

// One subdomain's nodes, coordinates, element matrices (local dofs) and load.
struct Subdomain {
  int id;
  std::vector<int> nodes;
  std::vector<Fem::Point> coords;
  std::vector<std::pair<std::vector<int>, std::vector<double>>> elements;  // 24 local dofs, 24 x 24 matrix
  std::vector<double> f;
};

Subdomain subdomain(const Grid& g, int s) {
  Subdomain d{s, std::vector<int>(g.numLocal()), std::vector<Fem::Point>(g.numLocal()), {},
              std::vector<double>(3 * g.numLocal(), 0.0)};
  const int n = g.n;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = s * n; i <= (s + 1) * n; ++i)
        d.nodes[g.local(s, i, j, k)] = g.node(i, j, k), d.coords[g.local(s, i, j, k)] = g.x(i, j, k);
  Fem::Material mat;
  mat.E = kE;
  mat.nu = kNu;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = s * n; i < (s + 1) * n; ++i) {
        const int c[8][3] = {{i, j, k},     {i + 1, j, k},     {i + 1, j + 1, k},     {i, j + 1, k},
                             {i, j, k + 1}, {i + 1, j, k + 1}, {i + 1, j + 1, k + 1}, {i, j + 1, k + 1}};
        std::vector<Fem::Point> X(8);
        std::vector<int> dofs(24);
        for (int a = 0; a < 8; ++a) {
          X[a] = g.x(c[a][0], c[a][1], c[a][2]);
          for (int q = 0; q < 3; ++q) dofs[3 * a + q] = 3 * g.local(s, c[a][0], c[a][1], c[a][2]) + q;
        }
        d.elements.push_back({dofs, Fem::elementStiffness(Mesh::CellType::Hex8, X, mat)});
      }
  const double quarter = 0.25 / (n * n);
  for (int j = 0; j < n; ++j)
    for (int i = s * n; i < (s + 1) * n; ++i)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) d.f[3 * g.local(s, i + a, j + b, n) + 2] -= kPressure * quarter;
  if (s == 1)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) d.f[3 * g.local(s, 2 * n, j + a, k + b)] -= kPush * quarter;
  return d;
}

// The subdomains of this rank: both on one rank, one each on two.
std::vector<Subdomain> mine(const Grid& g, const Comm& comm) {
  std::vector<Subdomain> out;
  for (int s = 0; s < 2; ++s)
    if (comm.getSize() == 1 || s == comm.getRank()) out.push_back(subdomain(g, s));
  return out;
}

// Tribos' own CSR type, as the old path takes it.
Fem::SubdomainSystem system(const Subdomain& d) {
  std::map<std::pair<int, int>, double> entries;
  for (const auto& [dofs, Ke] : d.elements)
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 24; ++b) entries[{dofs[a], dofs[b]}] += Ke[a * 24 + b];
  Fem::SubdomainSystem sys;
  sys.id = d.id;
  sys.nodes = d.nodes;
  sys.coords = d.coords;
  sys.f = d.f;
  const int rows = 3 * static_cast<int>(d.nodes.size());
  sys.K.rows = sys.K.cols = rows;
  auto it = entries.begin();
  for (int row = 0; row < rows; ++row) {
    for (; it != entries.end() && it->first.first == row; ++it)
      sys.K.col.push_back(it->first.second), sys.K.val.push_back(it->second);
    sys.K.rowptr.push_back(static_cast<int>(sys.K.col.size()));
  }
  return sys;
}

// A serial map whose global indices are the global dofs 3 node + c (any
// numbering would do; local index i is local dof i).
RCP<const Map> dofMap(const Subdomain& d) {
  Teuchos::Array<GO> gids;
  for (int node : d.nodes)
    for (int c = 0; c < 3; ++c) gids.push_back(3LL * node + c);
  return rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), gids(), 0,
                     rcp(new Teuchos::SerialComm<int>())));
}

// K assembled the Tpetra way: element by element into a CrsMatrix.
RCP<CrsMatrix> crsMatrix(const Subdomain& d, const RCP<const Map>& map, bool fillComplete = true) {
  auto K = rcp(new CrsMatrix(map, 8 * 24));  // room for every element's entries before they are merged
  for (const auto& [dofs, Ke] : d.elements)
    for (int a = 0; a < 24; ++a) {
      Teuchos::Array<GO> cols(24);
      for (int b = 0; b < 24; ++b) cols[b] = map->getGlobalElement(dofs[b]);
      const GO row = map->getGlobalElement(dofs[a]);
      K->insertGlobalValues(row, cols(), Teuchos::ArrayView<const SC>(&Ke[a * 24], 24));
    }
  if (fillComplete) K->fillComplete();
  return K;
}

// A matrix-free operator: K x without being a RowMatrix.
class MatrixFree : public Operator {
 public:
  explicit MatrixFree(RCP<const CrsMatrix> K) : K_(std::move(K)) {}
  RCP<const Map> getDomainMap() const override { return K_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return K_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, SC alpha, SC beta) const override {
    K_->apply(X, Y, mode, alpha, beta);
  }

 private:
  RCP<const CrsMatrix> K_;
};

enum class Stiffness { Crs, CrsAsOperator, MatrixFree };

Feti::TpetraSubdomain tpetraSubdomain(const Subdomain& d, Stiffness how) {
  const auto map = dofMap(d);
  Feti::TpetraSubdomain t;
  t.id = d.id;
  t.nodes = d.nodes;
  t.coords = d.coords;
  const RCP<const CrsMatrix> K = crsMatrix(d, map);
  t.K = how == Stiffness::MatrixFree ? RCP<const Operator>(rcp(new MatrixFree(K))) : RCP<const Operator>(K);
  auto f = rcp(new Vector(map));
  for (size_t i = 0; i < d.f.size(); ++i) f->replaceLocalValue(static_cast<LO>(i), d.f[i]);
  t.f = f;
  if (how != Stiffness::Crs) {  // the modes, required for an operator
    const auto R = Fem::rigidBodyModes(d.coords);
    auto modes = rcp(new MultiVector(map, 6));
    for (size_t j = 0; j < 6; ++j)
      for (size_t i = 0; i < d.f.size(); ++i) modes->replaceLocalValue(static_cast<LO>(i), j, R[j * d.f.size() + i]);
    t.R = modes;
  }
  return t;
}

// Gluing at x = 1 and the clamp at x = 0, as rows of B.
Feti::FetiConstraints glueAndClamp(const Grid& g) {
  Feti::FetiConstraints fc;
  const int n = g.n;
  const double w = 1.0 / std::sqrt(2.0);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int c = 0; c < 3; ++c) {
        Feti::DualRow clamp{Feti::DualRow::Dirichlet};
        clamp.node = g.node(0, j, k);
        clamp.copies = {{0, g.local(0, 0, j, k), 1.0}};
        clamp.dir[c] = 1.0;
        fc.rows.push_back(clamp);
        fc.dirichlet[3LL * clamp.node + c] = 0.0;
        Feti::DualRow glue{Feti::DualRow::Gluing};
        glue.node = g.node(n, j, k);
        glue.copies = {{0, g.local(0, n, j, k), w}, {1, g.local(1, n, j, k), -w}};
        glue.dir[c] = 1.0;
        fc.rows.push_back(glue);
      }
  return fc;
}

// The bottom nodes that are not clamped, on the plane z = 0, on the
// subdomain of lowest number that holds them.
std::vector<Feti::ContactCondition> bottom(const Grid& g) {
  std::vector<Feti::ContactCondition> out;
  for (int j = 0; j <= g.n; ++j)
    for (int i = 1; i <= 2 * g.n; ++i) {
      Feti::ContactCondition c;
      c.node = g.node(i, j, 0);
      c.subdomain = i <= g.n ? 0 : 1;
      c.localNode = g.local(c.subdomain, i, j, 0);
      c.normal = {0, 0, -1};
      c.gap = 0.0;
      c.area = 1.0 / (g.n * g.n);
      out.push_back(c);
    }
  return out;
}

// The old path's contact: the rows written by hand in Tribos' frame.
Feti::FetiConstraints handWrittenRows(const Grid& g) {
  Feti::FetiConstraints fc = glueAndClamp(g);
  fc.contactNormal = {0, 0, -1};
  std::array<double, 3> t1, t2;
  Feti::tangents(fc.contactNormal, t1, t2);
  for (const auto& c : bottom(g)) {
    Feti::DualRow r{Feti::DualRow::Normal};
    r.node = c.node;
    r.copies = {{c.subdomain, c.localNode, 1.0}};
    r.dir = c.normal;
    fc.rows.push_back(r);
    r.kind = Feti::DualRow::Tangent1;
    r.dir = t1;
    fc.rows.push_back(r);
    r.kind = Feti::DualRow::Tangent2;
    r.dir = t2;
    fc.rows.push_back(r);
    fc.contactArea[c.node] = c.area;
  }
  return fc;
}

RCP<Teuchos::ParameterList> parameters() {
  auto p = Teuchos::parameterList();
  p->set("Outer Algorithm", "Algorithm2");
  p->sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", kFriction);
  return p;
}

// The old path: SubdomainSystem, hand-written rows, solveFeti.
Contact::FetiSolveResult oldPath(const Grid& g, const RCP<const Comm>& comm) {
  std::vector<Fem::SubdomainSystem> systems;
  for (const auto& d : mine(g, *comm)) systems.push_back(system(d));
  auto problem = rcp(new Feti::FetiProblem(std::move(systems), handWrittenRows(g), Teuchos::ParameterList(), comm));
  Teuchos::ParameterList p;
  p.set("Outer Algorithm", "Algorithm2");
  p.sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  return Contact::solveFeti(problem, Contact::FrictionSpec{FrictionLaw::Coulomb, kFriction, 0.0}, p);
}

// The embedding API: TpetraSubdomain, contact conditions, ContactSolver.
// pair: the contact conditions' pair; params: the solver's list.
Contact::FetiSolveResult newPath(const Grid& g, const RCP<const Comm>& comm, Stiffness how,
                                 Contact::SolveStatus& status, int pair = 0,
                                 const RCP<Teuchos::ParameterList>& params = parameters()) {
  std::vector<Feti::TpetraSubdomain> subdomains;
  for (const auto& d : mine(g, *comm)) subdomains.push_back(tpetraSubdomain(d, how));
  Feti::FetiConstraints constraints = glueAndClamp(g);
  auto conditions = bottom(g);
  for (auto& c : conditions) c.pair = pair;
  Feti::addContactConditions(constraints, conditions, *comm);
  Contact::ContactSolver solver;
  solver.setParameters(params);
  solver.setProblem(Feti::createFetiProblem(subdomains, std::move(constraints), params->sublist("FETI"), comm));
  status = solver.solve();
  return solver.getResult();
}

// max |a - b| / max |b| over the nodes every rank owns.
double difference(const Fem::NodalVector& a, const Fem::NodalVector& b, const Comm& comm) {
  double local[2] = {0, 0}, global[2];
  for (int i = 0; i < b.layout().numOwned(); ++i) {
    const int node = b.layout().nodes()[i];
    for (int c = 0; c < 3; ++c) {
      local[0] = std::max(local[0], std::abs(a.at(node)[c] - b.at(node)[c]));
      local[1] = std::max(local[1], std::abs(b.at(node)[c]));
    }
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 2, local, global);
  return global[0] / global[1];
}

// tolerance: the CrsMatrix path hands FetiProblem the same subdomains and
// rows as the old path, so the solve repeats it to rounding; with R given
// (the operator paths) FetiProblem orthonormalizes that basis of the kernel
// instead of building its own, K+ is another generalized inverse, and the
// two solves (each to 1e-9) agree to the solver's tolerance.
void sameSolution(Stiffness how, double tolerance, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  const auto before = oldPath(g, comm);
  Contact::SolveStatus status;
  const auto after = newPath(g, comm, how, status);
  TEST_ASSERT(before.verdict.converged);
  TEST_ASSERT(status == Contact::SolveStatus::Converged);
  TEST_ASSERT(after.verdict.converged);
  TEST_ASSERT(after.kkt.equilibrium <= after.verdict.limit && after.kkt.frictionLaw <= after.verdict.limit);
  TEST_EQUALITY(after.counts.nodes, before.counts.nodes);
  TEST_EQUALITY(after.counts.stick, before.counts.stick);
  TEST_EQUALITY(after.counts.slip, before.counts.slip);
  TEST_ASSERT(after.counts.stick > 0 && after.counts.slip > 0);  // both zones: the friction acts
  const double d = difference(after.u, before.u, *comm);
  out << "max |u_new - u_old| / max |u_old| = " << d << "\n";
  TEST_ASSERT(d <= tolerance);
}

TEUCHOS_UNIT_TEST(Embedding, CrsMatrixSameAsSubdomainSystem) { sameSolution(Stiffness::Crs, 1e-12, out, success); }
TEUCHOS_UNIT_TEST(Embedding, RowMatrixOperatorSameAsSubdomainSystem) {
  sameSolution(Stiffness::CrsAsOperator, 1e-7, out, success);
}
TEUCHOS_UNIT_TEST(Embedding, MatrixFreeOperatorSameAsSubdomainSystem) {
  sameSolution(Stiffness::MatrixFree, 1e-7, out, success);
}

// K as a dense matrix (81 x 81 here).
std::vector<double> dense(const LocalCsr& K) {
  std::vector<double> D(static_cast<size_t>(K.rows) * K.cols, 0.0);
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k) D[static_cast<size_t>(i) * K.cols + K.col[k]] += K.val[k];
  return D;
}

// The copied and the probed matrix are K, entry for entry (probing keeps
// the nonzero entries only: the element matrices' exact zeros drop out).
TEUCHOS_UNIT_TEST(Embedding, CopiedAndProbedMatrixAreK) {
  const Grid g;
  const Subdomain d = subdomain(g, 1);
  const auto reference = system(d).K;
  const auto copied = Feti::subdomainSystem(tpetraSubdomain(d, Stiffness::Crs)).K;
  const auto probed = Feti::subdomainSystem(tpetraSubdomain(d, Stiffness::MatrixFree)).K;
  TEST_COMPARE_ARRAYS(copied.rowptr, reference.rowptr);
  TEST_COMPARE_ARRAYS(copied.col, reference.col);
  TEST_COMPARE_FLOATING_ARRAYS(copied.val, reference.val, 1e-14);
  TEST_COMPARE_FLOATING_ARRAYS(dense(probed), dense(reference), 1e-14);
  size_t nonzero = 0;
  for (double v : reference.val) nonzero += v != 0.0;
  TEST_EQUALITY(probed.val.size(), nonzero);
}

std::string refusal(const Feti::TpetraSubdomain& t) {
  return errorOf([&] { Feti::subdomainSystem(t); });
}

TEUCHOS_UNIT_TEST(Embedding, SubdomainRefusals) {
  const Grid g;
  const Subdomain d = subdomain(g, 0);
  {
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    t.K = Teuchos::null;
    TEST_ASSERT(contains(refusal(t), "TpetraSubdomain 0: K is null"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    t.nodes.pop_back(), t.coords.pop_back();
    const std::string e = refusal(t);
    out << e << "\n";
    TEST_ASSERT(contains(e, "K has 81 rows, expected 3 x 26 nodes = 78"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    t.coords.pop_back();
    TEST_ASSERT(contains(refusal(t), "26 coordinates for 27 nodes"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    t.K = crsMatrix(d, dofMap(d), false);
    TEST_ASSERT(contains(refusal(t), "K is not fill-complete"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::MatrixFree);
    t.R = Teuchos::null;
    const std::string e = refusal(t);
    out << e << "\n";
    TEST_ASSERT(contains(e, "not a RowMatrix; give its rigid-body modes R"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::CrsAsOperator);
    t.R = rcp(new MultiVector(t.K->getDomainMap(), 5));
    TEST_ASSERT(contains(refusal(t), "R has 5 columns, expected the 6 rigid-body modes"));
  }
  {
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    t.f = rcp(new Vector(dofMap(subdomain(g, 1))));
    TEST_ASSERT(contains(refusal(t), "f has 81 local rows on a map that is not K's domain map"));
  }
  {
    // K + e_0 e_5': not symmetric.
    auto t = tpetraSubdomain(d, Stiffness::Crs);
    auto K = crsMatrix(d, dofMap(d), false);
    const auto map = K->getRowMap();
    K->sumIntoGlobalValues(map->getGlobalElement(0), Teuchos::tuple<GO>(map->getGlobalElement(5)), Teuchos::tuple<SC>(1e9));
    K->fillComplete();
    t.K = K;
    const std::string e = refusal(t);
    out << e << "\n";
    TEST_ASSERT(contains(e, "K is not symmetric: K(0, 5)"));
  }
}

// K of a subdomain distributed over the ranks: refused on 2 ranks and more.
TEUCHOS_UNIT_TEST(Embedding, SubdomainOnSeveralProcessesRefused) {
  const auto comm = Tpetra::getDefaultComm();
  if (comm->getSize() == 1) {
    out << "one rank: every communicator is serial\n";
    return;
  }
  const Grid g;
  const Subdomain d = subdomain(g, 0);
  auto t = tpetraSubdomain(d, Stiffness::Crs);
  const auto map = rcp(new Map(static_cast<Tpetra::global_size_t>(81 * comm->getSize()), 81, 0, comm));
  auto K = rcp(new CrsMatrix(map, 1));
  for (LO i = 0; i < 81; ++i) {
    const GO row = map->getGlobalElement(i);
    K->insertGlobalValues(row, Teuchos::tuple<GO>(row), Teuchos::tuple<SC>(1.0));
  }
  K->fillComplete();
  t.K = K;
  const std::string e = refusal(t);
  out << e << "\n";
  TEST_ASSERT(contains(e, "K is distributed over " + std::to_string(comm->getSize()) + " processes"));
}

// R that K does not annihilate: refused on every rank by createFetiProblem.
TEUCHOS_UNIT_TEST(Embedding, ModesOutsideTheKernelRefused) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  std::vector<Feti::TpetraSubdomain> subdomains;
  for (const auto& d : mine(g, *comm)) {
    auto t = tpetraSubdomain(d, Stiffness::CrsAsOperator);
    auto R = rcp(new MultiVector(*t.R, Teuchos::Copy));
    // Column 2: a translation along (1, 1, 1) but for one entry, not a rigid motion.
    R->getVectorNonConst(2)->putScalar(1.0);
    R->getVectorNonConst(2)->replaceLocalValue(0, 2.0);
    t.R = R;
    subdomains.push_back(t);
  }
  const std::string e =
      errorOf([&] { Feti::createFetiProblem(subdomains, glueAndClamp(g), Teuchos::ParameterList(), comm); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "subdomain 0: column") && contains(e, "of R is not in the kernel of K"));
}

TEUCHOS_UNIT_TEST(Embedding, ContactConditionRefusals) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  auto conditions = bottom(g);
  conditions[3].normal = {0, 0, 0};
  Feti::FetiConstraints fc;
  std::string e = errorOf([&] { Feti::addContactConditions(fc, conditions, *comm); });
  TEST_ASSERT(contains(e, "contact condition 3 (node " + std::to_string(conditions[3].node) + "): the normal (0, 0, 0)"));
  TEST_ASSERT(fc.rows.empty());  // nothing added
  conditions = bottom(g);
  conditions.push_back(conditions[1]);
  e = errorOf([&] { Feti::addContactConditions(fc, conditions, *comm); });
  TEST_ASSERT(contains(e, "has a contact condition already"));
  conditions = bottom(g);
  conditions[0].area = -1;
  e = errorOf([&] { Feti::addContactConditions(fc, conditions, *comm); });
  TEST_ASSERT(contains(e, "contact condition 0") && contains(e, "the area -1"));
  // The rows are Tribos' frame: normal normalized, tangents of Feti::tangents.
  conditions = bottom(g);
  conditions[0].normal = {0, 0, -2};
  Feti::addContactConditions(fc, conditions, *comm);
  std::array<double, 3> t1, t2;
  Feti::tangents({0, 0, -1}, t1, t2);
  TEST_EQUALITY(fc.rows.size(), 3 * conditions.size());
  TEST_ASSERT(fc.rows[0].kind == Feti::DualRow::Normal && fc.rows[0].dir[2] == -1.0);
  TEST_ASSERT(fc.rows[1].kind == Feti::DualRow::Tangent1 && fc.rows[1].dir == t1);
  TEST_ASSERT(fc.rows[2].kind == Feti::DualRow::Tangent2 && fc.rows[2].dir == t2);
  TEST_EQUALITY(fc.contact.size(), conditions.size());
}

std::string parameterRefusal(const RCP<Teuchos::ParameterList>& p) {
  return errorOf([&] { Contact::ContactSolver().setParameters(p); });
}

TEUCHOS_UNIT_TEST(Embedding, ParameterRefusals) {
  auto p = parameters();
  p->sublist("Friction").set("Law", "Stribeck");
  std::string e = parameterRefusal(p);
  out << e << "\n";
  TEST_ASSERT(contains(e, "Friction") && contains(e, "Law") && contains(e, "Stribeck"));
  p = parameters();
  p->sublist("Friction").set("Coeficient", 0.3);
  TEST_ASSERT(contains(parameterRefusal(p), "Coeficient"));
  p = parameters();
  p->sublist("Friction").set("Coefficient", -0.1);
  TEST_ASSERT(contains(parameterRefusal(p), "Coefficient"));
  p = parameters();
  p->sublist("Friction").set("Coefficient", std::nan(""));
  e = parameterRefusal(p);
  TEST_ASSERT(contains(e, "\"Coefficient\" parameter in the \"Friction\" sublist") && contains(e, "nan"));
  p = parameters();
  p->sublist("Friction").sublist("Pear 1");
  TEST_ASSERT(contains(parameterRefusal(p), "Friction/Pear 1 is not a parameter of Friction"));
  p = parameters();
  p->sublist("Friction").sublist("Pair 1").set("Law", "Stribeck");
  e = parameterRefusal(p);
  TEST_ASSERT(contains(e, "Friction/Pair 1") && contains(e, "Stribeck"));
  p = parameters();
  p->set("Outer Algoritm", "Algorithm2");
  TEST_ASSERT(contains(parameterRefusal(p), "Outer Algoritm"));
  p = parameters();
  p->sublist("FETI").set("Local Solver", "Gauss");
  TEST_ASSERT(contains(parameterRefusal(p), "Gauss"));
  // A refused list keeps its entries (Friction among them).
  TEST_ASSERT(p->sublist("Friction").isParameter("Law"));
  TEST_ASSERT(contains(errorOf([] { Contact::ContactSolver().solve(); }), "no problem; call setProblem() first"));
  TEST_ASSERT(contains(errorOf([] { Contact::ContactSolver().getResult(); }), "no result; call solve() first"));
}

// A pair that no "Pair <k>" names takes the list's own friction: the
// conditions of pair 2 with "Pair 0" (F = 0.9) given solve as the old path
// with F = 0.3 everywhere.
TEUCHOS_UNIT_TEST(Embedding, UnnamedPairTakesTheListsFriction) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  const auto before = oldPath(g, comm);
  auto params = parameters();
  params->sublist("Friction").sublist("Pair 0").set("Coefficient", 0.9);
  Contact::SolveStatus status;
  const auto after = newPath(g, comm, Stiffness::Crs, status, 2, params);
  TEST_ASSERT(status == Contact::SolveStatus::Converged);
  TEST_EQUALITY(after.counts.slip, before.counts.slip);
  TEST_ASSERT(difference(after.u, before.u, *comm) <= 1e-12);
  // and pair 0 itself takes its own F = 0.9: fewer nodes slip.
  const auto pair0 = newPath(g, comm, Stiffness::Crs, status, 0, params);
  TEST_ASSERT(status == Contact::SolveStatus::Converged);
  out << "slip nodes: F = 0.3 " << before.counts.slip << ", F = 0.9 " << pair0.counts.slip << "\n";
  TEST_ASSERT(pair0.counts.slip < before.counts.slip);
}

// "Friction" and its "Pair <k>" sublists become the friction of each pair;
// the defaults are filled in the caller's list.
TEUCHOS_UNIT_TEST(Embedding, FrictionOfPairs) {
  auto p = Teuchos::parameterList();
  Contact::ContactSolver solver;
  solver.setParameters(p);
  TEST_EQUALITY(solver.getFriction().size(), 1u);
  TEST_ASSERT(solver.getFriction()[0].law == FrictionLaw::Frictionless);
  TEST_EQUALITY(p->sublist("Friction").get<std::string>("Law"), "Frictionless");
  TEST_ASSERT(p->isParameter("Outer Algorithm"));
  p = parameters();
  p->sublist("Friction").sublist("Pair 2").set("Coefficient", 0.5);
  solver.setParameters(p);
  const auto& f = solver.getFriction();
  TEST_EQUALITY(f.size(), 3u);
  TEST_ASSERT(f[0].law == FrictionLaw::Coulomb && f[0].coefficient == kFriction);
  TEST_ASSERT(f[1].law == FrictionLaw::Coulomb && f[1].coefficient == kFriction);
  TEST_ASSERT(f[2].law == FrictionLaw::Coulomb && f[2].coefficient == 0.5);
}

// Every choice that validParameters() offers for "Outer Algorithm" (an
// alias too) solves a problem of a law it documents: a choice no law solves
// would pass setParameters and fail in solve(). A law it does not solve is
// refused naming the algorithm.
TEUCHOS_UNIT_TEST(Embedding, EveryOfferedOuterAlgorithmSolves) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  const auto choices = Contact::ContactSolver::validParameters()->getEntry("Outer Algorithm").validator()->validStringValues();
  for (const std::string& algorithm : *choices) {
    int solved = 0;
    for (const char* law : {"Tresca", "Coulomb"}) {
      auto params = parameters();
      params->set("Outer Algorithm", algorithm);
      params->sublist("Friction").set("Law", law).set("Slip Bound Traction", 0.1 * kPressure);
      Contact::SolveStatus status = Contact::SolveStatus::Unconverged;
      const std::string error = errorOf([&] { newPath(g, comm, Stiffness::Crs, status, 0, params); });
      out << algorithm << ", " << law << ": " << (error.empty() ? "solved" : error) << "\n";
      TEST_ASSERT(error.empty() ? status == Contact::SolveStatus::Converged
                                : contains(error, "Outer Algorithm = "));
      solved += error.empty();
    }
    TEST_ASSERT(solved > 0);
  }
}

// The block's FetiProblem: the contact conditions of pair `pair`, or none.
RCP<const Feti::FetiProblem> problem(const Grid& g, const RCP<const Comm>& comm, bool contact, int pair = 0) {
  std::vector<Feti::TpetraSubdomain> subdomains;
  for (const auto& d : mine(g, *comm)) subdomains.push_back(tpetraSubdomain(d, Stiffness::Crs));
  Feti::FetiConstraints constraints = glueAndClamp(g);
  if (contact) {
    auto conditions = bottom(g);
    for (auto& c : conditions) c.pair = pair;
    Feti::addContactConditions(constraints, conditions, *comm);
  }
  return Feti::createFetiProblem(subdomains, std::move(constraints), Teuchos::ParameterList(), comm);
}

// A choice that the valid list offers but the solve would refuse is
// refused before any work, naming it, the reason and the valid choices:
// NSGS (it reads W's entries: FCLIB problems only) and a value an outer
// algorithm refuses by setParameters; an algorithm that does not solve the
// law of the problem's pairs by setProblem, or by setParameters once a
// problem is set; the solver keeps what it had.
TEUCHOS_UNIT_TEST(Embedding, ChoicesTheSolveRefusesAreRefusedFirst) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  {
    Contact::ContactSolver solver;
    auto p = parameters();
    p->set("Outer Algorithm", "NSGS");
    const std::string e = errorOf([&] { solver.setParameters(p); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "Outer Algorithm = \"NSGS\" does not solve the FETI dual") && contains(e, "FCLIB"));
    TEST_ASSERT(contains(e, "valid: Auto, Algorithm1") && contains(e, "Algorithm2"));
    TEST_ASSERT(solver.getCurrentParameters().is_null());
    TEST_EQUALITY(p->sublist("Friction").get<std::string>("Law"), "Coulomb");  // the caller's list kept whole
  }
  {
    Contact::ContactSolver solver;
    auto p = parameters();
    p->sublist("Algorithm 2").set("Residual Balancing", 0.5);  // in the valid range [0, 1e6]
    const std::string e = errorOf([&] { solver.setParameters(p); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "ContactSolver: Algorithm 2: Residual Balancing"));
  }
  // Algorithm1 (Tresca, frictionless) for Coulomb friction, and Algorithm2
  // for frictionless contact: refused by setProblem.
  for (const auto& [algorithm, law, refused, valid] :
       {std::tuple<std::string, std::string, std::string, std::string>{"Algorithm1", "Coulomb", "Coulomb friction",
                                                                        "Algorithm2"},
        {"Tresca", "Coulomb", "Coulomb friction", "MSA+Algorithm1"},
        {"Algorithm2", "Frictionless", "frictionless contact", "Algorithm1"},
        {"Semismooth Newton", "Tresca", "Tresca friction", "Algorithm1"}}) {
    Contact::ContactSolver solver;
    auto p = parameters();
    p->set("Outer Algorithm", algorithm);
    p->sublist("Friction").set("Law", law).set("Slip Bound Traction", 0.1 * kPressure);
    solver.setParameters(p);  // no problem yet: nothing to refuse
    const auto withContact = problem(g, comm, true);
    const std::string e = errorOf([&] { solver.setProblem(withContact); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "Outer Algorithm = \"" + algorithm + "\" does not solve " + refused));
    TEST_ASSERT(contains(e, "valid for it: Auto") && contains(e, valid));
    TEST_ASSERT(solver.getProblem().is_null());
    // A problem without contact has no outer algorithm to refuse; the
    // contact problem is still refused, and the solver keeps the other.
    const auto withoutContact = problem(g, comm, false);
    TEST_NOTHROW(solver.setProblem(withoutContact));
    TEST_ASSERT(contains(errorOf([&] { solver.setProblem(withContact); }), "does not solve"));
    TEST_ASSERT(solver.getProblem().get() == withoutContact.get());
    // The same choice given after the problem: refused by setParameters.
    Contact::ContactSolver later;
    later.setProblem(withContact);
    const std::string e2 = errorOf([&] { later.setParameters(p); });
    TEST_ASSERT(contains(e2, "Outer Algorithm = \"" + algorithm + "\" does not solve " + refused));
    TEST_ASSERT(later.getCurrentParameters().is_null());
  }
  // Tresca and Coulomb pairs in one problem: the pair 0 Tresca, the list's
  // own law Coulomb for every other pair. Refused for the conditions of
  // pair 1, taken for those of pair 0 (all Tresca).
  {
    auto p = parameters();
    p->set("Outer Algorithm", "Auto");
    p->sublist("Friction").sublist("Pair 0").set("Law", "Tresca").set("Slip Bound Traction", 0.1 * kPressure);
    Contact::ContactSolver solver;
    solver.setParameters(p);
    const std::string e = errorOf([&] { solver.setProblem(problem(g, comm, true, 1)); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "ContactSolver: Friction: contact pairs with Tresca and with Coulomb friction"));
    TEST_NOTHROW(solver.setProblem(problem(g, comm, true, 0)));
  }
  // Semismooth Newton's dense LU on a dual larger than its Dense Limit.
  {
    auto p = parameters();
    p->set("Outer Algorithm", "Semismooth Newton");
    p->sublist("Semismooth Newton").set("Linear Solver", "Dense LU").set("Dense Limit", 10);
    Contact::ContactSolver solver;
    solver.setParameters(p);
    const std::string e = errorOf([&] { solver.setProblem(problem(g, comm, true)); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "Dense Limit = 10"));
    p->sublist("Semismooth Newton").set("Linear Solver", "Auto");
    solver.setParameters(p);
    TEST_NOTHROW(solver.setProblem(problem(g, comm, true)));
  }
}

// ContactSolver set up and run through Teuchos::ParameterListAcceptor, as
// code written for any Trilinos solver would: the same result as through
// its own methods.
TEUCHOS_UNIT_TEST(Embedding, SolveThroughParameterListAcceptor) {
  const auto comm = Tpetra::getDefaultComm();
  const Grid g;
  auto solver = rcp(new Contact::ContactSolver);
  const RCP<Teuchos::ParameterListAcceptor> acceptor = solver;
  auto p = rcp(new Teuchos::ParameterList(*acceptor->getValidParameters()));  // every default, documented
  p->set("Outer Algorithm", "Algorithm2");
  p->sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", kFriction);
  acceptor->setParameterList(p);
  solver->setProblem(problem(g, comm, true));
  TEST_ASSERT(solver->solve() == Contact::SolveStatus::Converged);
  Contact::SolveStatus status;
  const auto reference = newPath(g, comm, Stiffness::Crs, status);
  TEST_ASSERT(difference(solver->getResult().u, reference.u, *comm) <= 1e-12);
  TEST_EQUALITY(solver->getResult().counts.slip, reference.counts.slip);
}

// The valid list, validators included, written as a Teuchos XML file and
// read back.
TEUCHOS_UNIT_TEST(Embedding, ValidParametersWrittenAsXml) {
  const auto valid = Contact::ContactSolver::validParameters();
  const std::string xml = errorOf([&] {
    std::ostringstream os;
    Teuchos::writeParameterListToXmlOStream(*valid, os);
    const auto back = Teuchos::getParametersFromXmlString(os.str());
    TEST_EQUALITY(back->sublist("Friction").get<std::string>("Law"), "Frictionless");
  });
  out << xml << "\n";
  TEST_ASSERT(xml.empty());
}

}  // namespace
