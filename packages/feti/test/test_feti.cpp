// FETI against the monolithic solve of the same problem (F applied implicitly
// and from explicit dense blocks, which must agree), generalized inverse
// K K+ K = K, and rank independence: every run also solves the problem on
// rank 0 alone (split communicator) and compares iteration counts and
// displacements.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_ConstraintRows.hpp"
#include "Tribos_FetiDual.hpp"
#include "Tribos_FetiOperators.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_ProjectedCG.hpp"
#include "Tribos_SplitCholesky.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;

using Test::relDiff;

struct Case {
  Mesh::CellType type;
  std::array<int, 3> cells;
  int subdomains;
  std::string gluing;
  std::string partitioner = "METIS";
  std::array<int, 3> grid{1, 1, 1};
  bool sameIterations = false;  // checked where round-off cannot move the count
  std::string formulation = "TFETI";
  std::string preconditioner = "Lumped";
  std::string dualOperator = "Implicit";
};

Mesh::Discretization makeDisc(const Case& c, const Comm& comm) {
  Mesh::BoxSpec spec;
  spec.type = c.type;
  spec.x = {0, 2};
  spec.cells = c.cells;
  Mesh::DecompositionSpec dec;
  dec.partitioner = c.partitioner;
  dec.subdomains = c.subdomains;
  dec.grid = c.grid;
  return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
}

Fem::LoadCase loads() {
  Fem::LoadCase l;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  Fem::DirichletCondition roller;
  roller.face = "zmin";
  roller.fix = {false, false, true};
  l.dirichlet = {clamp, roller};
  l.tractions = {{"zmax", {0, 0, -4e7}}, {"xmax", {-2e7, 1e7, 0}}};
  l.volumeForce = {0, 0, -7.8e4};
  return l;
}

struct FetiResult {
  std::vector<double> u;
  int iterations;
  double kernelError;
};

// ||B (K+)_bb B' x - B K+ B' x|| / ||B K+ B' x||: the dense blocks against
// the sparse solves, for one x.
double explicitVsImplicit(const Feti::FetiProblem& problem, const Comm& comm) {
  Vector x(problem.dualMap()), p(problem.primalMap()), z1(problem.primalMap()), z2(problem.primalMap());
  Vector F1(problem.dualMap()), F2(problem.dualMap());
  auto xv = x.getDataNonConst();
  for (size_t i = 0; i < xv.size(); ++i) xv[i] = std::cos(0.61 * (i + 7 * comm.getRank()));
  xv = Teuchos::null;
  problem.B()->apply(x, p, Teuchos::TRANS);
  problem.applyKplus(p, z1);
  problem.applyDualKplus(p, z2);
  problem.B()->apply(z1, F1);
  problem.B()->apply(z2, F2);
  F2.update(-1.0, F1, 1.0);
  return F2.norm2() / F1.norm2();
}

FetiResult solveFeti(const Case& c, const RCP<const Comm>& comm, Teuchos::FancyOStream& out, bool& success) {
  auto disc = makeDisc(c, *comm);
  Teuchos::ParameterList p;
  p.set("Gluing", c.gluing);
  p.set("Formulation", c.formulation);
  p.set("Dual Operator", c.dualOperator);
  p.set("Dense Block Precision", "Double");  // explicit = implicit to 1e-10 (single: DualOperator tests)
  auto problem = rcp(new Feti::FetiProblem(disc, Fem::Material{2.1e11, 0.3}, loads(), std::vector<Feti::ContactConstraint>(),
                                           p, comm));
  if (problem->explicitDualOperator()) {
    const double diff = explicitVsImplicit(*problem, *comm);
    out << "explicit vs implicit F x: relative difference " << diff << "\n";
    TEST_COMPARE(diff, <, 1e-10);
  }
  // K K+ K = K on every local subdomain (columns of K applied to random-ish vectors).
  double worst = 0;
  {
    Vector x(problem->primalMap()), Kx(problem->primalMap()), z(problem->primalMap()), Kz(problem->primalMap());
    auto xv = x.getDataNonConst();
    for (size_t i = 0; i < xv.size(); ++i) xv[i] = std::sin(0.37 * i + 1.0);
    xv = Teuchos::null;
    problem->applyK(x, Kx);
    problem->applyKplus(Kx, z);
    problem->applyK(z, Kz);
    Kz.update(-1.0, Kx, 1.0);
    worst = Kz.normInf() / Kx.normInf();
  }
  Feti::FetiDual dual(problem);
  Teuchos::ParameterList pcgParams;
  // Rank-independence cases stop where round-off cannot shift the count;
  // the comparison with the monolithic solve needs the tight tolerance.
  pcgParams.set("Tolerance", c.sameIterations ? 1e-8 : 1e-11);
  pcgParams.set("Preconditioner", c.preconditioner);
  Feti::ProjectedCG pcg(pcgParams);
  Vector lambda(problem->dualMap());
  const auto st = pcg.solve(dual, lambda);
  TEST_ASSERT(st.converged);  // PCG
  return {problem->nodalDisplacement(*dual.recoverPrimal(lambda)).gathered(), st.iterations, worst};
}

// FETI against the monolithic solve, K K+ K = K, and the same problem on
// rank 0 alone.
void checkCase(const Case& c, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  auto self = comm->split(comm->getRank() == 0 ? 0 : 1, comm->getRank());
  const std::string name = Mesh::cellTypeName(c.type) + " S=" + std::to_string(c.subdomains) + " " + c.gluing + " " + c.partitioner + " " + c.formulation + " " + c.preconditioner + " " + c.dualOperator;
  out << name << "\n";
  const auto feti = solveFeti(c, comm, out, success);
  auto disc = makeDisc(c, *comm);
  Fem::MonolithicSystem mono(disc, Fem::Material{2.1e11, 0.3}, loads(), comm);
  Teuchos::ParameterList mp = *Fem::MonolithicSystem::getValidParameters();
  mp.set("Linear Solver", "Direct");
  const auto ref = mono.solve(mp);
  const double diff = relDiff(feti.u, ref.u.gathered());
  out << "PCG iterations " << feti.iterations << ", |u_FETI - u_mono|/|u_mono| = " << diff
      << ", K K+ K - K: " << feti.kernelError << "\n";
  TEST_COMPARE(diff, <, (c.sameIterations ? 1e-6 : 1e-8));
  TEST_COMPARE(feti.kernelError, <, 1e-8);
  // Rank independence: rank 0 alone solves the same problem.
  std::vector<double> serialU(feti.u.size());
  int serialIter = 0;
  if (comm->getRank() == 0) {
    const auto serial = solveFeti(c, self, out, success);
    serialU = serial.u;
    serialIter = serial.iterations;
  }
  Teuchos::broadcast(*comm, 0, static_cast<int>(serialU.size()), serialU.data());
  Teuchos::broadcast(*comm, 0, &serialIter);
  const double rankDiff = relDiff(feti.u, serialU);
  out << "iterations " << feti.iterations << " on " << comm->getSize() << " ranks vs " << serialIter
      << " on 1; displacements differ by " << rankDiff << "\n";
  if (c.sameIterations) TEST_EQUALITY(feti.iterations, serialIter);
  TEST_COMPARE(rankDiff, <, 1e-10);
}

}  // namespace

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4NonRedundant) {
  checkCase({Mesh::CellType::Tet4, {8, 4, 4}, 6, "Non-redundant"}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8NonRedundant) {
  checkCase({Mesh::CellType::Hex8, {8, 4, 4}, 6, "Non-redundant"}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8Full) {
  checkCase({Mesh::CellType::Hex8, {6, 3, 3}, 4, "Full"}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4Orthonormal) {
  checkCase({Mesh::CellType::Tet4, {8, 4, 4}, 6, "Orthonormal"}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8OrthonormalStructured) {
  checkCase({Mesh::CellType::Hex8, {9, 4, 4}, 6, "Orthonormal", "Structured", {3, 2, 1}, true}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4OrthonormalFeti1) {
  checkCase({Mesh::CellType::Tet4, {8, 4, 4}, 6, "Orthonormal", "METIS", {1, 1, 1}, false, "FETI-1"}, out, success);
}

// Round-off moves this case's count at 1e-8 (27 or 28 steps on 1 or 3 ranks).
TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8NonRedundantStructuredFeti1) {
  checkCase({Mesh::CellType::Hex8, {9, 4, 4}, 6, "Non-redundant", "Structured", {3, 2, 1}, false, "FETI-1"}, out,
            success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4OrthonormalStructuredDirichlet) {
  checkCase({Mesh::CellType::Tet4, {9, 4, 4}, 6, "Orthonormal", "Structured", {3, 2, 1}, true, "TFETI", "Dirichlet"},
            out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8OrthonormalNoPreconditioner) {
  checkCase({Mesh::CellType::Hex8, {8, 4, 4}, 6, "Orthonormal", "METIS", {1, 1, 1}, false, "TFETI", "None"}, out,
            success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4NonRedundantStructured) {
  checkCase({Mesh::CellType::Tet4, {9, 4, 4}, 6, "Non-redundant", "Structured", {3, 2, 1}, true}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8NonRedundantStructured) {
  checkCase({Mesh::CellType::Hex8, {9, 4, 4}, 6, "Non-redundant", "Structured", {3, 2, 1}, true}, out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Tet4OrthonormalExplicit) {
  checkCase({Mesh::CellType::Tet4, {8, 4, 4}, 6, "Orthonormal", "METIS", {1, 1, 1}, false, "TFETI", "Lumped", "Explicit"},
            out, success);
}

TEUCHOS_UNIT_TEST(FetiVsMonolithic, Hex8NonRedundantStructuredFeti1DirichletExplicit) {
  checkCase({Mesh::CellType::Hex8, {9, 4, 4}, 6, "Non-redundant", "Structured", {3, 2, 1}, true, "FETI-1", "Dirichlet",
             "Explicit"},
            out, success);
}

namespace {

// x: a fixed dual vector with different values on every rank.
void fillDual(Vector& x, const Comm& comm) {
  auto xv = x.getDataNonConst();
  for (size_t i = 0; i < xv.size(); ++i) xv[i] = std::cos(0.37 * (i + 11 * comm.getRank()) + 0.5);
}

// The sparse GG' (assembled from 6 x 6 blocks on every rank) against G G'
// column by column through applyG(applyGt(e_j)); the projector and the
// orthonormalized constraint built on its sparse Cholesky factor:
// G P x = 0, P P x = P x, G^ G^' = I.
void checkCoarseSpace(const Case& c, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  auto disc = makeDisc(c, *comm);
  Teuchos::ParameterList p;
  p.set("Gluing", c.gluing);
  p.set("Formulation", c.formulation);
  auto problem = rcp(new Feti::FetiProblem(disc, Fem::Material{2.1e11, 0.3}, loads(), std::vector<Feti::ContactConstraint>(),
                                           p, comm));
  Feti::CoarseSpace coarse(problem);
  const int n = coarse.size();
  const LocalCsr A = coarse.gramian(nullptr);
  TEST_EQUALITY(A.rows, n);
  double worst = 0, scale = 0;
  Vector v(problem->dualMap());
  std::vector<double> e(n), col;
  for (int j = 0; j < n; ++j) {
    std::fill(e.begin(), e.end(), 0.0);
    e[j] = 1.0;
    coarse.applyGt(e, v);
    coarse.applyG(v, col);
    // Column j of the sparse matrix (symmetric: row j).
    std::vector<double> sparseCol(n, 0.0);
    for (int k = A.rowptr[j]; k < A.rowptr[j + 1]; ++k) sparseCol[A.col[k]] = A.val[k];
    for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(col[i] - sparseCol[i])), scale = std::max(scale, std::abs(col[i]));
  }
  out << Mesh::cellTypeName(c.type) << " " << c.formulation << ": coarse size " << n << ", nnz(GG') " << A.val.size()
      << ", |GG'_sparse - G G'| = " << worst / scale << "\n";
  TEST_COMPARE(worst, <=, 1e-13 * scale);
  TEST_COMPARE(static_cast<double>(A.val.size()), <, 1.0 * n * n);  // sparse: not every pair of subdomains couples
  Vector x(problem->dualMap()), Px(problem->dualMap()), PPx(problem->dualMap());
  fillDual(x, *comm);
  coarse.project(x, Px);
  coarse.project(Px, PPx);
  std::vector<double> GPx, Gx;
  coarse.applyG(Px, GPx);
  coarse.applyG(x, Gx);
  double gpx = 0, gx = 0;
  for (int i = 0; i < n; ++i) gpx = std::max(gpx, std::abs(GPx[i])), gx = std::max(gx, std::abs(Gx[i]));
  PPx.update(-1.0, Px, 1.0);
  out << "|G P x| / |G x| = " << gpx / gx << ", |P P x - P x| / |P x| = " << PPx.norm2() / Px.norm2() << "\n";
  TEST_COMPARE(gpx, <, 1e-12 * gx);
  TEST_COMPARE(PPx.norm2(), <, 1e-12 * Px.norm2());
  // G^ G^' y = y for the orthonormalized constraint G^ = L^-1 P G.
  std::vector<double> y(n), Gy;
  for (int i = 0; i < n; ++i) y[i] = std::sin(1.3 * i + 0.2);
  coarse.applyOrthonormalTranspose(y, v);
  coarse.applyOrthonormal(v, Gy);
  double orth = 0, ynorm = 0;
  for (int i = 0; i < n; ++i) orth = std::max(orth, std::abs(Gy[i] - y[i])), ynorm = std::max(ynorm, std::abs(y[i]));
  out << "|G^ G^' y - y| / |y| = " << orth / ynorm << "\n";
  TEST_COMPARE(orth, <, 1e-10 * ynorm);
}

}  // namespace

TEUCHOS_UNIT_TEST(CoarseSpace, SparseGramianTFETI) {
  checkCoarseSpace({Mesh::CellType::Tet4, {8, 4, 4}, 8, "Orthonormal", "Structured", {4, 2, 1}}, out, success);
}

// FETI-1: the subdomains at the clamped end keep fewer than six rigid modes,
// so the blocks of GG' are not all 6 x 6.
TEUCHOS_UNIT_TEST(CoarseSpace, SparseGramianFETI1) {
  checkCoarseSpace({Mesh::CellType::Hex8, {9, 4, 4}, 6, "Non-redundant", "Structured", {3, 2, 1}, false, "FETI-1"}, out,
                   success);
}

namespace {

// The problem of disc without contact, with the FETI parameters p.
RCP<Feti::FetiProblem> problemWith(const Mesh::Discretization& disc, const Teuchos::ParameterList& p,
                                   const RCP<const Comm>& comm) {
  return rcp(new Feti::FetiProblem(disc, Fem::Material{2.1e11, 0.3}, loads(), std::vector<Feti::ContactConstraint>(),
                                   p, comm));
}

RCP<Feti::FetiProblem> problemWithCoarse(const Mesh::Discretization& disc, const Case& c,
                                         const std::string& coarseProblem, const RCP<const Comm>& comm) {
  Teuchos::ParameterList p;
  p.set("Coarse Problem", coarseProblem);
  p.set("Gluing", c.gluing);
  p.set("Formulation", c.formulation);
  return problemWith(disc, p, comm);
}

}  // namespace

// The coarse problem split among the ranks (SplitCholesky) against the one
// every rank factors whole: the same projector P and the same G^'G^ = I - P
// to round-off (G^ itself depends on the factor's ordering), and the split
// factor's solves against CHOLMOD's of the whole GG'. On one rank nothing is
// split; on 2 and 3 ranks METIS' parts and their separator are.
namespace {

void checkSplitCoarseProblem(const Case& c, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  auto disc = makeDisc(c, *comm);
  auto replicated = problemWithCoarse(disc, c, "Replicated", comm), split = problemWithCoarse(disc, c, "Split", comm);
  Feti::CoarseSpace whole(replicated), shared(split);
  TEST_EQUALITY(whole.size(), shared.size());
  Vector x(replicated->dualMap()), P1(replicated->dualMap()), P2(replicated->dualMap());
  fillDual(x, *comm);
  whole.project(x, P1);
  shared.project(x, P2);
  P2.update(-1.0, P1, 1.0);
  out << "|P_split x - P x| / |P x| = " << P2.norm2() / P1.norm2() << "\n";
  TEST_COMPARE(P2.norm2(), <, 1e-12 * P1.norm2());
  // G^'G^ x = (I - P) x whichever factor orthonormalizes.
  std::vector<double> y;
  Vector Q(replicated->dualMap());
  shared.applyOrthonormal(x, y);
  shared.applyOrthonormalTranspose(y, Q);
  Q.update(1.0, P1, -1.0, x, 1.0);  // G^'G^ x + P x - x
  out << "|G^'G^ x - (I - P) x| / |x| = " << Q.norm2() / x.norm2() << "\n";
  TEST_COMPARE(Q.norm2(), <, 1e-12 * x.norm2());
  // The split factor itself.
  const LocalCsr A = whole.gramian(nullptr);
  std::vector<int> blocks;
  for (int k : replicated->kernelOffsets())
    if (blocks.empty() || k > blocks.back()) blocks.push_back(k);
  Feti::SplitCholesky chol(comm, blocks);
  chol.factor(A);
  out << "ranks " << comm->getSize() << ": split " << chol.isSplit() << ", separator rows " << chol.separatorRows()
      << " of " << A.rows << "\n";
  TEST_EQUALITY(chol.isSplit(), comm->getSize() > 1);
  auto reference = createLocalSolver("CHOLMOD");
  reference->factor(A);
  std::vector<double> b(A.rows), x1(A.rows), x2(A.rows), r(A.rows);
  for (int i = 0; i < A.rows; ++i) b[i] = std::sin(0.9 * i + 0.3);
  reference->solve(b.data(), x1.data(), 1);
  chol.solve(b.data(), x2.data(), 1);
  A.multiply(x2.data(), r.data());
  double dx = 0, nx = 0, res = 0, nb = 0;
  for (int i = 0; i < A.rows; ++i) {
    dx = std::max(dx, std::abs(x2[i] - x1[i])), nx = std::max(nx, std::abs(x1[i]));
    res = std::max(res, std::abs(r[i] - b[i])), nb = std::max(nb, std::abs(b[i]));
  }
  out << "split solve: |x - x_CHOLMOD| / |x| = " << dx / nx << ", |A x - b| / |b| = " << res / nb << "\n";
  TEST_COMPARE(dx, <, 1e-10 * nx);
  TEST_COMPARE(res, <, 1e-12 * nb);
  // ||L^-1 P b||^2 = b'A^-1 b, and L^-T undoes it: P'L^-T L^-1 P b = A^-1 b.
  std::vector<double> z(b);
  chol.solveFactor(z.data(), false);
  double zz = 0, bx = 0;
  for (int i = 0; i < A.rows; ++i) zz += z[i] * z[i], bx += b[i] * x1[i];
  chol.solveFactor(z.data(), true);
  double dz = 0;
  for (int i = 0; i < A.rows; ++i) dz = std::max(dz, std::abs(z[i] - x1[i]));
  out << "|L^-1 P b|^2 / b'A^-1 b - 1 = " << zz / bx - 1 << ", |P'L^-T L^-1 P b - A^-1 b| / |A^-1 b| = " << dz / nx
      << "\n";
  TEST_COMPARE(std::abs(zz / bx - 1), <, 1e-12);
  TEST_COMPARE(dz, <, 1e-10 * nx);
  TEST_COMPARE(chol.pivotRatio(), >, 1e-12);
  // Not positive definite: every rank throws, none waits.
  LocalCsr negative = A;
  for (double& v : negative.val) v = -v;
  Feti::SplitCholesky broken(comm, blocks);
  TEST_THROW(broken.factor(negative), CollectiveError);
}

}  // namespace

TEUCHOS_UNIT_TEST(CoarseSpace, SplitAgreesWithReplicated) {
  checkSplitCoarseProblem({Mesh::CellType::Tet4, {16, 8, 8}, 128, "Orthonormal", "Structured", {8, 4, 4}}, out,
                          success);
}

// FETI-1: the subdomains at the clamped end keep fewer than six rigid modes
// (blocks of GG' of other sizes, some subdomains with none).
TEUCHOS_UNIT_TEST(CoarseSpace, SplitAgreesWithReplicatedFETI1) {
  checkSplitCoarseProblem(
      {Mesh::CellType::Hex8, {16, 8, 8}, 128, "Non-redundant", "Structured", {8, 4, 4}, false, "FETI-1"}, out,
      success);
}

// A problem of disc without contact whose dual operator is explicit, its
// dense blocks in the precision given ("Double" or "Single").
namespace {
RCP<Feti::FetiProblem> explicitProblem(const Mesh::Discretization& disc, const std::string& precision,
                                       const RCP<const Comm>& comm) {
  Teuchos::ParameterList p;
  p.set("Dual Operator", "Explicit");
  p.set("Dense Block Precision", precision);
  return problemWith(disc, p, comm);
}
}  // namespace

// Single-precision dense blocks: B (K+)_bb B' x agrees with the sparse solves
// to float accuracy, and is not the double product (the blocks are rounded).
TEUCHOS_UNIT_TEST(DualOperator, SinglePrecisionBlocks) {
  auto comm = Tpetra::getDefaultComm();
  const Case c{Mesh::CellType::Tet4, {8, 4, 4}, 6, "Orthonormal"};
  auto disc = makeDisc(c, *comm);
  auto problem = explicitProblem(disc, "Single", comm);
  TEST_ASSERT(problem->explicitDualOperator());
  const double diff = explicitVsImplicit(*problem, *comm);
  out << "single-precision explicit vs implicit F x: relative difference " << diff << "\n";
  TEST_COMPARE(diff, <, 1e-5);
  TEST_COMPARE(diff, >, 1e-12);
}

// F formed densely from the blocks (K+)_bb equals F applied to every unit
// vector, in double and single precision, on every number of ranks (the
// rows of B that meet a subdomain of another rank included).
TEUCHOS_UNIT_TEST(DualOperator, DenseFormEqualsApplications) {
  auto comm = Tpetra::getDefaultComm();
  const Case c{Mesh::CellType::Tet4, {6, 3, 3}, 6, "Orthonormal"};
  auto disc = makeDisc(c, *comm);
  for (const char* precision : {"Double", "Single"}) {
    auto problem = explicitProblem(disc, precision, comm);
    std::vector<double> D;
    TEST_ASSERT(problem->formDenseF(D));
    const auto map = problem->dualMap();
    const size_t n = map->getGlobalNumElements();
    TEST_EQUALITY(D.size(), n * n);
    if (D.size() != n * n) return;
    Feti::DualOperator F(problem);
    Vector e(map), Fe(map);
    double worst = 0, scale = 0;
    for (size_t j = 0; j < n; ++j) {
      e.putScalar(0.0);
      if (map->isNodeGlobalElement(static_cast<GO>(j))) e.replaceGlobalValue(static_cast<GO>(j), 1.0);
      F.apply(e, Fe);
      auto v = Fe.getData();
      for (size_t l = 0; l < v.size(); ++l) {
        const double d = D[j * n + static_cast<size_t>(map->getGlobalElement(static_cast<LO>(l)))];
        worst = std::max(worst, std::abs(d - v[l]));
        scale = std::max(scale, std::abs(v[l]));
      }
    }
    double all = 0, allScale = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, worst, Teuchos::outArg(all));
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, scale, Teuchos::outArg(allScale));
    out << precision << ": n = " << n << ", max |D - F e_j| / max |F| = " << all / allScale << "\n";
    // The same block values summed in another order: single blocks are
    // applied in double arithmetic, so F is the matrix of its rounded
    // entries to double round-off, not to float's.
    TEST_COMPARE(all, <=, 1e-12 * allScale);
  }
}

// Single-precision blocks: F~ (what apply reads) is one symmetric operator,
// y'F~x = x'F~y to double round-off; it differs from the exact F
// (applyExact) by float's rounding; and FetiDual::roundingDefect is F~ x -
// F x with F from a second problem of double blocks, on every number of
// ranks (zero for double blocks).
TEUCHOS_UNIT_TEST(FetiDual, RoundingDefect) {
  auto comm = Tpetra::getDefaultComm();
  const Case c{Mesh::CellType::Tet4, {8, 4, 4}, 6, "Orthonormal"};
  auto disc = makeDisc(c, *comm);
  for (const char* precision : {"Double", "Single"}) {
    auto problem = explicitProblem(disc, precision, comm);
    const Feti::FetiDual dual(problem);
    const bool single = std::string(precision) == "Single";
    TEST_EQUALITY(dual.F()->rounded(), single);
    Vector x(problem->dualMap()), y(problem->dualMap());
    {
      auto xv = x.getDataNonConst();
      auto yv = y.getDataNonConst();
      for (size_t i = 0; i < xv.size(); ++i) {
        const double g = static_cast<double>(problem->dualMap()->getGlobalElement(static_cast<LO>(i)));
        xv[i] = 1e-3 * std::cos(0.61 * g);
        yv[i] = 1e-3 * std::sin(0.37 * g + 0.2);
      }
    }
    Vector Fx(problem->dualMap()), Fy(problem->dualMap()), Ex(problem->dualMap());
    dual.F()->apply(x, Fx);
    dual.F()->apply(y, Fy);
    dual.F()->applyExact(x, Ex);
    const double asym = std::abs(y.dot(Fx) - x.dot(Fy)) / std::abs(x.dot(Fx));
    Ex.update(-1.0, Fx, 1.0);
    const double rounding = Ex.norm2() / Fx.norm2();
    out << precision << ": |y'F~x - x'F~y| / x'F~x = " << asym << ", ||(F - F~) x|| / ||F~ x|| = " << rounding << "\n";
    TEST_COMPARE(asym, <, 1e-13);
    TEST_COMPARE(rounding, <, single ? 1e-5 : 1e-12);
    if (single) TEST_COMPARE(rounding, >, 1e-10);
    // The defect against F~ x minus F x of the double-block problem.
    Feti::DualOperator F(explicitProblem(disc, "Double", comm));
    Vector expected(problem->dualMap());
    F.apply(x, expected);
    expected.update(1.0, Fx, -1.0);
    const auto defect = dual.roundingDefect(x);
    const double defectSize = defect->norm2() / Fx.norm2();
    defect->update(-1.0, expected, 1.0);
    const double defectError = defect->norm2() / Fx.norm2();
    out << "  ||defect|| / ||F~ x|| = " << defectSize << ", against F~ x - F x: " << defectError << "\n";
    TEST_COMPARE(defectError, <, 1e-12);
    TEST_COMPARE(defectSize, <, single ? 1e-5 : 1e-300);
    if (single) TEST_COMPARE(defectSize, >, 1e-10);
  }
}


// The lumped preconditioner's shortcuts are exact where they are taken:
// with the orthonormal gluing BB' = I on the gluing and Dirichlet rows
// (so diag(BB')^-1 is (BB')^+), the chain gluing is recognized as not
// orthonormal (its rows have norm sqrt 2), and B K B' = B K_bb B' (B
// reads and writes only the dofs it touches).
TEUCHOS_UNIT_TEST(DualPreconditioner, LumpedShortcutsExact) {
  auto comm = Tpetra::getDefaultComm();
  for (const std::string gluing : {"Orthonormal", "Non-redundant"}) {
    const Case c{Mesh::CellType::Hex8, {9, 4, 4}, 6, gluing, "Structured", {3, 2, 1}};
    auto disc = makeDisc(c, *comm);
    Teuchos::ParameterList p;
    p.set("Gluing", gluing);
    auto problem = problemWith(disc, p, comm);
    const bool orthonormal = gluing == "Orthonormal";
    TEST_EQUALITY(problem->orthonormalEqualityRows(), orthonormal);
    Vector x(problem->dualMap()), BBtx(problem->dualMap()), Btx(problem->primalMap());
    fillDual(x, *comm);
    problem->B()->apply(x, Btx, Teuchos::TRANS);
    problem->B()->apply(Btx, BBtx);
    BBtx.update(-1.0, x, 1.0);
    out << gluing << ": |BB'x - x| / |x| = " << BBtx.norm2() / x.norm2() << "\n";
    if (orthonormal) {
      TEST_COMPARE(BBtx.norm2(), <=, 1e-14 * x.norm2());
    } else {
      TEST_COMPARE(BBtx.norm2(), >, 0.1 * x.norm2());
    }
    Vector Kfull(problem->primalMap()), Kbb(problem->primalMap()), BK(problem->dualMap()), BKbb(problem->dualMap());
    problem->applyK(Btx, Kfull);
    problem->applyKBoundary(Btx, Kbb);
    problem->B()->apply(Kfull, BK);
    problem->B()->apply(Kbb, BKbb);
    BKbb.update(-1.0, BK, 1.0);
    out << gluing << ": |B K_bb B'x - B K B'x| / |B K B'x| = " << BKbb.norm2() / BK.norm2() << "\n";
    TEST_COMPARE(BKbb.norm2(), <=, 1e-13 * BK.norm2());
  }
}
