// Contact with friction by FETI: KKT conditions, a reference solved without
// FETI (dual of the assembled problem restricted to the contact rows),
// Coulomb fixed point, agreement of the two Coulomb algorithms, the limits
// F -> 0, large F and a pulled-away body, and rank independence (every run
// also solves on rank 0 alone).
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <map>

#include "Tribos_FetiContact.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_QP.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;

using Test::relDiff;

struct Setup {
  std::string law = "Coulomb";
  double F = 0.3, slipTraction = 0.0;
  std::string algorithm = "Algorithm2";
  double topLoad = -4e7;  // z traction on zmax
  double gap = 0.0;
  double residualBalancing = -1;  // Algorithm 2's rho update; < 0: the default
};

struct Result {
  std::vector<double> u;           // nodal displacement, replicated
  std::vector<double> normalForce; // per contact node, gathered by mesh node (replicated, 0 elsewhere)
  Contact::ResultKKT kkt;
  Contact::ContactCounts counts;
  Friction::FrictionStatus status;
  double fixedPoint = 0;           // ||F lambda_N - g|| / ||g|| for Coulomb
};

Mesh::Discretization makeDisc(const Comm& comm) {
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Tet4;
  spec.x = {0, 3};
  spec.cells = {6, 2, 2};
  Mesh::DecompositionSpec dec;
  dec.grid = {3, 1, 1};
  return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
}

Fem::LoadCase loads(const Setup& s) {
  Fem::LoadCase l;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  l.dirichlet = {clamp};
  l.tractions = {{"zmax", {0, 0, s.topLoad}}, {"xmax", {-2e7, 0, 0}}};
  return l;
}

const Fem::Material kSteel{21.2e10, 0.277};

Teuchos::ParameterList tightSolverParams() {
  Teuchos::ParameterList p;
  p.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-9);
  p.sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  p.sublist("Algorithm 2").set("Slip Bound Tolerance", 1e-8);
  p.sublist("MSA").set("Tolerance", 1e-8);
  return p;
}

Result solve(const Setup& s, const RCP<const Comm>& comm) {
  auto disc = makeDisc(*comm);
  Contact::ContactSpec contact;
  contact.enabled = true;
  contact.gap = s.gap;
  auto problem = rcp(new Feti::FetiProblem(disc, kSteel, loads(s), Contact::faceContactConstraints(disc, contact, comm),
                                           Teuchos::ParameterList(), comm));
  auto dual = rcp(new Feti::FetiDual(problem));
  Contact::FrictionSpec fs;
  fs.law = frictionLawNamed(s.law);
  fs.coefficient = s.F;
  fs.slipBoundTraction = s.slipTraction;
  Contact::FetiContactProblem cp(dual, fs);
  auto params = tightSolverParams();
  if (s.residualBalancing >= 0) params.sublist("Algorithm 2").set("Residual Balancing", s.residualBalancing);
  auto sol = cp.solve(s.algorithm, params);
  Result r;
  r.status = sol.status;
  const auto& lambda = sol.lambda;
  const auto& u = sol.u;
  const auto uNodal = problem->nodalDisplacement(*u);
  auto nodes = Contact::contactResults(*problem, uNodal, *lambda, r.status.slipBound, {fs});
  r.kkt = Contact::resultKKT(*problem, uNodal, nodes, {fs}, r.counts);
  r.u = uNodal.gathered();  // every node on every rank, to compare runs
  r.normalForce.assign(disc.numMeshNodes(), 0.0);
  for (size_t k = 0; k < nodes.nodes.size(); ++k) r.normalForce[nodes.nodes[k]] = nodes.normalForce[k];
  const std::vector<double> mine(r.normalForce);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), r.normalForce.data());
  if (s.law == "Coulomb") {
    const auto g = cp.contactDual().coulombSlipBound(*sol.x);
    r.fixedPoint = Friction::globalDistance(g, r.status.slipBound, *comm) /
                   std::max(Friction::globalNorm(g, *comm), 1e-300);
  }
  return r;
}

// Reference without FETI, on rank 0 alone: K (Dirichlet eliminated) factored
// by CHOLMOD, A = N K^-1 N' restricted to the contact rows (normal, t1, t2
// per node, dense), solved by MPGP over Lambda_t(g) x Lambda_N, u recovered.
std::vector<double> referenceTresca(const Setup& s, const std::vector<double>& g, const RCP<const Comm>& self,
                                    Teuchos::FancyOStream& out, bool& success) {
  auto disc = makeDisc(*self);
  Fem::MonolithicSystem mono(disc, kSteel, loads(s), self);
  const CrsMatrix& K = *mono.matrix();
  const int n = static_cast<int>(K.getGlobalNumRows());
  LocalCsr Kc;
  Kc.rows = Kc.cols = n;
  for (int i = 0; i < n; ++i) {
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    K.getLocalRowView(i, cols, vals);
    std::vector<std::pair<int, double>> row;
    for (size_t k = 0; k < cols.extent(0); ++k) row.emplace_back(static_cast<int>(K.getColMap()->getGlobalElement(cols(k))), vals(k));
    std::sort(row.begin(), row.end());
    for (auto& e : row) Kc.col.push_back(e.first), Kc.val.push_back(e.second);
    Kc.rowptr.push_back(static_cast<int>(Kc.col.size()));
  }
  auto Kinv = createLocalSolver("CHOLMOD");
  Kinv->factor(Kc);
  // Contact nodes: zmin nodes off the clamped face, frame (n, t1, t2) as in FETI.
  std::vector<int> nodes;
  for (int node : disc.part.faceNodes("zmin"))
    if (disc.part.coords[node][0] > 1e-12) nodes.push_back(node);
  const int nc = static_cast<int>(nodes.size()), m = 3 * nc;
  const double frame[3][3] = {{0, 0, -1}, {0, 1, 0}, {-1, 0, 0}};  // n, t1 = e_x x n, t2 = n x t1
  std::vector<double> Bt(static_cast<size_t>(n) * m, 0.0), KinvBt(Bt.size());
  for (int k = 0; k < nc; ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Bt[static_cast<size_t>(3 * k + r) * n + 3 * nodes[k] + c] = frame[r][c];
  Kinv->solve(Bt.data(), KinvBt.data(), m);
  std::vector<double> f(n), Kf(n);
  {
    auto fv = mono.rhs()->getData();
    for (int i = 0; i < n; ++i) f[i] = fv[i];
  }
  Kinv->solve(f.data(), Kf.data(), 1);
  auto map = rcp(new Map(m, 0, self));
  auto A = rcp(new CrsMatrix(map, m));
  Vector b(map);
  std::vector<GO> cols(m);
  for (int j = 0; j < m; ++j) cols[j] = j;
  for (int i = 0; i < m; ++i) {
    std::vector<double> row(m);
    double bi = 0;
    for (int j = 0; j < m; ++j) {
      double sum = 0;
      for (int q = 0; q < n; ++q) sum += Bt[static_cast<size_t>(i) * n + q] * KinvBt[static_cast<size_t>(j) * n + q];
      row[j] = sum;
    }
    for (int q = 0; q < n; ++q) bi += Bt[static_cast<size_t>(i) * n + q] * Kf[q];
    if (i % 3 == 0) bi -= s.gap;
    b.replaceLocalValue(i, bi);
    A->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const SC>(row));
  }
  A->fillComplete();
  QP::ConstraintSet Omega(map);
  for (int k = 0; k < nc; ++k) {
    Omega.setLower(3 * k, 0.0);
    Omega.setCircle(3 * k + 1, 3 * k + 2, k);
  }
  // g is indexed by mesh node in the caller.
  std::vector<double> radii(nc);
  for (int k = 0; k < nc; ++k) radii[k] = g[nodes[k]];
  Omega.setRadii(radii);
  auto params = Teuchos::parameterList();
  params->set("Relative Tolerance", 1e-12);
  params->set("Maximum Iterations", 100000);
  QP::MPGP mpgp(params);
  Vector lambda(map);
  const auto st = mpgp.solve(*A, b, Omega, lambda);
  TEST_ASSERT(st.converged);  // the reference MPGP
  std::vector<double> rhs(f);
  auto lv = lambda.getData();
  for (int j = 0; j < m; ++j)
    for (int q = 0; q < n; ++q) rhs[q] -= Bt[static_cast<size_t>(j) * n + q] * lv[j];
  std::vector<double> u(n);
  Kinv->solve(rhs.data(), u.data(), 1);
  return u;  // on a single rank the dof numbering is 3 node + c
}

void report(const std::string& name, const Result& r, Teuchos::FancyOStream& out) {
  out << name << ": outer " << r.status.outer_iterations << ", n_A " << r.status.n_A << ", KKT eq " << r.kkt.equilibrium
      << " pen " << r.kkt.nonpenetration << " compl " << r.kkt.complementarity << " fric " << r.kkt.frictionLaw
      << ", active/stick/slip " << r.counts.active << "/" << r.counts.stick << "/" << r.counts.slip << "\n";
}

void checkKKT(const std::string& name, const Result& r, double tol, Teuchos::FancyOStream& out, bool& success) {
  out << name << ": " << r.status.reason << "\n";
  TEST_ASSERT(r.status.converged);
  TEST_COMPARE(r.kkt.equilibrium, <, tol);
  TEST_COMPARE(r.kkt.dirichlet, <, tol);
  TEST_COMPARE(r.kkt.nonpenetration, <, tol);
  TEST_COMPARE(r.kkt.complementarity, <, tol);
  TEST_COMPARE(r.kkt.frictionLaw, <, tol);
}

const Setup frictionless{"Frictionless", 0.0, 0.0, "Tresca"};
const Setup tresca{"Tresca", 0.0, 2.0e6, "Tresca"};
const Setup coulombA2{"Coulomb", 0.3, 0.0, "Algorithm2"};
const Setup coulombMSA{"Coulomb", 0.3, 0.0, "MSA+Algorithm1"};

// The solves several cases compare with, each done once on all ranks.
const Result& solveOnce(const std::string& key, const Setup& s) {
  static std::map<std::string, Result> results;
  auto it = results.find(key);
  if (it == results.end()) it = results.emplace(key, solve(s, Tpetra::getDefaultComm())).first;
  return it->second;
}

// Frictionless and Tresca: KKT to 1e-6 and the FETI-free reference.
void checkAgainstReference(const Setup& s, const Result& r, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  const bool root = comm->getRank() == 0;
  report(s.law, r, out);
  checkKKT(s.law, r, 1e-6, out, success);
  std::vector<double> gByNode(r.u.size() / 3, 0.0);
  if (s.law == "Tresca") {
    // Nodal slip bound = traction x nodal area (recomputed here).
    auto disc = makeDisc(*self);
    for (const auto& facet : disc.part.face("zmin")) {
      std::vector<Fem::Point> X;
      for (int nd : facet.nodes) X.push_back(disc.part.coords[nd]);
      const auto w = Fem::facetNodalAreas(X);
      for (size_t a = 0; a < w.size(); ++a) gByNode[facet.nodes[a]] += s.slipTraction * w[a];
    }
  }
  std::vector<double> ref(r.u.size());
  if (root) ref = referenceTresca(s, gByNode, self, out, success);
  Teuchos::broadcast(*comm, 0, static_cast<int>(ref.size()), ref.data());
  const double d = relDiff(r.u, ref);
  out << s.law << ": |u_FETI - u_ref| / |u_ref| = " << d << "\n";
  TEST_COMPARE(d, <, 1e-6);  // FETI vs the reference without FETI
}

}  // namespace

TEUCHOS_UNIT_TEST(Reference, Frictionless) {
  checkAgainstReference(frictionless, solveOnce("frictionless", frictionless), out, success);
}

TEUCHOS_UNIT_TEST(Reference, Tresca) { checkAgainstReference(tresca, solve(tresca, Tpetra::getDefaultComm()), out, success); }

// Coulomb: both outer algorithms, fixed point, agreement.
TEUCHOS_UNIT_TEST(Coulomb, Algorithm2AndMSA) {
  const Result& a2 = solveOnce("coulombA2", coulombA2);
  const Result msa = solve(coulombMSA, Tpetra::getDefaultComm());
  report("Coulomb Algorithm2", a2, out);
  report("Coulomb MSA+Algorithm1", msa, out);
  checkKKT("Coulomb Algorithm2", a2, 1e-5, out, success);
  checkKKT("Coulomb MSA", msa, 1e-5, out, success);
  TEST_COMPARE(a2.fixedPoint, <, 1e-6);   // Algorithm 2: g = F lambda_N
  TEST_COMPARE(msa.fixedPoint, <, 1e-6);  // MSA: g = F lambda_N
  const double dAlg = relDiff(a2.u, msa.u);
  out << "Algorithm2 vs MSA: " << dAlg << "\n";
  TEST_COMPARE(dAlg, <, 1e-4);
  // F = 0.3 has both stick and slip nodes.
  TEST_COMPARE(a2.counts.stick, >, 0);
  TEST_COMPARE(a2.counts.slip, >, 0);
}

// The penalty rho changes the path, not the solution: Algorithm 2 with rho
// fixed (no residual balancing) reaches the same displacements.
TEUCHOS_UNIT_TEST(Coulomb, FixedPenaltySameSolution) {
  const Result& a2 = solveOnce("coulombA2", coulombA2);
  Setup fixedRho = coulombA2;
  fixedRho.residualBalancing = 0;
  const auto a2fixed = solve(fixedRho, Tpetra::getDefaultComm());
  checkKKT("Coulomb Algorithm2, rho fixed", a2fixed, 1e-5, out, success);
  const double dRho = relDiff(a2.u, a2fixed.u);
  out << "Algorithm2 balanced vs fixed rho: " << dRho << "\n";
  TEST_COMPARE(dRho, <, 1e-6);
}

// F -> 0 gives the frictionless solution (to the solver tolerance).
TEUCHOS_UNIT_TEST(Limits, SmallCoefficientIsFrictionless) {
  const Result& r0 = solveOnce("frictionless", frictionless);
  const auto tiny = solve(Setup{"Coulomb", 1e-9, 0.0, "Algorithm2"}, Tpetra::getDefaultComm());
  const double d0 = relDiff(tiny.u, r0.u);
  out << "F = 1e-9 vs frictionless: " << d0 << "\n";
  TEST_COMPARE(d0, <, 1e-5);
}

// Large F: every active node sticks.
TEUCHOS_UNIT_TEST(Limits, LargeCoefficientSticks) {
  const auto large = solve(Setup{"Coulomb", 50.0, 0.0, "Algorithm2"}, Tpetra::getDefaultComm());
  report("F = 50", large, out);
  TEST_COMPARE(large.counts.active, >, 0);
  TEST_EQUALITY(large.counts.slip, 0);
}

// A pulled-away body has no active contact, and the contact forces vanish.
TEUCHOS_UNIT_TEST(Limits, PulledAwayBody) {
  const Setup pulled{"Coulomb", 0.3, 0.0, "Algorithm2", +4e7};
  const auto away = solve(pulled, Tpetra::getDefaultComm());
  report("pulled away", away, out);
  TEST_EQUALITY(away.counts.active, 0);
  double maxN = 0;
  for (double v : away.normalForce) maxN = std::max(maxN, std::abs(v));
  TEST_ASSERT(maxN == 0.0 || maxN < 1e-8 * 4e7);
}

// Rank independence against rank 0 alone.
TEUCHOS_UNIT_TEST(RankIndependence, CoulombAlgorithm2) {
  auto comm = Tpetra::getDefaultComm();
  auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  const Result& a2 = solveOnce("coulombA2", coulombA2);
  std::vector<double> serial(a2.u.size());
  if (comm->getRank() == 0) serial = solve(coulombA2, self).u;
  Teuchos::broadcast(*comm, 0, static_cast<int>(serial.size()), serial.data());
  const double dr = relDiff(a2.u, serial);
  out << "Coulomb Algorithm2 on " << comm->getSize() << " ranks vs 1: " << dr << "\n";
  TEST_COMPARE(dr, <, 1e-6);
}

// G on a face (QP::FaceConstraint of FETI's coarse space): with Pi the
// projector onto the complement of a few fixed directions of contact rows,
// T(u) = G'(G Pi G')^-1 G u is the operator with range in range G' and
// G Pi T(u) = G u, and it is symmetric.
TEUCHOS_UNIT_TEST(CoarseFace, InvertsGPiGtOnRangeG) {
  auto comm = Tpetra::getDefaultComm();
  auto disc = makeDisc(*comm);
  Contact::ContactSpec contact;
  contact.enabled = true;
  const Setup s;
  auto problem = rcp(new Feti::FetiProblem(disc, kSteel, loads(s), Contact::faceContactConstraints(disc, contact, comm),
                                           Teuchos::ParameterList(), comm));
  Contact::FrictionSpec fs;
  fs.law = FrictionLaw::Coulomb;
  fs.coefficient = 0.3;
  Contact::FetiContactProblem cp(rcp(new Feti::FetiDual(problem)), fs);
  const Friction::ContactDual& dual = cp.contactDual();
  TEST_ASSERT(!dual.G.is_null());
  auto face = dual.G->face();
  TEST_ASSERT(!face.is_null());
  // Fixed: the normal of every other contact, a tangential combination
  // (0.6, 0.8) of the others.
  LocalCsr fixed;
  fixed.cols = static_cast<int>(dual.map()->getNodeNumElements());
  for (int k = 0; k < dual.numLocalContacts(); ++k) {
    if (k % 2 == 0) {
      fixed.col.push_back(dual.normalRows[k]), fixed.val.push_back(1.0);
    } else {
      fixed.col.push_back(dual.tangentRows[2 * k]), fixed.val.push_back(0.6);
      fixed.col.push_back(dual.tangentRows[2 * k + 1]), fixed.val.push_back(0.8);
    }
    fixed.rowptr.push_back(static_cast<int>(fixed.col.size()));
    ++fixed.rows;
  }
  TEST_ASSERT(face->setFixedDirections(fixed));
  auto removeFixed = [&](const Vector& u, Vector& Piu) {  // Pi u
    Piu.assign(u);
    auto v = Piu.getDataNonConst();
    for (int q = 0; q < fixed.rows; ++q) {
      double c = 0;
      for (int j = fixed.rowptr[q]; j < fixed.rowptr[q + 1]; ++j) c += fixed.val[j] * v[fixed.col[j]];
      for (int j = fixed.rowptr[q]; j < fixed.rowptr[q + 1]; ++j) v[fixed.col[j]] -= c * fixed.val[j];
    }
  };
  Vector u(dual.map()), w(dual.map()), Tu(dual.map()), Tw(dual.map()), PiTu(dual.map()), back(dual.map());
  u.randomize();
  w.randomize();
  face->apply(u, Tu);
  face->apply(w, Tw);
  Vector Gu(dual.G->rangeMap()), GPiTu(dual.G->rangeMap()), GTu(dual.G->rangeMap());
  // G Pi T u = G u.
  removeFixed(Tu, PiTu);
  dual.G->apply(u, Gu);
  dual.G->apply(PiTu, GPiTu);
  GPiTu.update(-1.0, Gu, 1.0);
  out << "||G Pi T u - G u|| / ||G u|| = " << GPiTu.norm2() / Gu.norm2() << "\n";
  TEST_COMPARE(GPiTu.norm2(), <, 1e-10 * Gu.norm2());
  // T u in range G' (G has orthonormal rows: G'G T u = T u).
  dual.G->apply(Tu, GTu);
  dual.G->applyTranspose(GTu, back);
  back.update(-1.0, Tu, 1.0);
  TEST_COMPARE(back.norm2(), <, 1e-10 * Tu.norm2());
  // Symmetric.
  const double a = Tu.dot(w), b = u.dot(Tw);
  TEST_COMPARE(std::abs(a - b), <, 1e-10 * std::abs(a));
  // No fixed direction: T = G'G.
  TEST_ASSERT(face->setFixedDirections(LocalCsr{}));
  face->apply(u, Tu);
  dual.G->applyTranspose(Gu, back);
  back.update(-1.0, Tu, 1.0);
  TEST_COMPARE(back.norm2(), <, 1e-10 * Tu.norm2());
}
