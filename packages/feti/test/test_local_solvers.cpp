// Every local solver backend factors a regularized subdomain stiffness of more
// than 1024 rows (Tacho's sparse path) and solves it to round-off, one and
// several right-hand sides at once. The block of the inverse on the dofs of
// two faces, (K^-1)_bb, agrees between backends: CHOLMOD reads it off the
// trailing block of a factor that orders those dofs last (supernodal on the
// large matrix, simplicial on the small one), the others solve with unit
// vectors.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>

#include "Tribos_Assembly.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;

// Regularized stiffness of the unit cube and the dofs of its faces x = 1 and z = 0.
LocalCsr regularizedStiffness(Mesh::CellType type, int cells, std::vector<int>& faceDofs) {
  Mesh::BoxSpec spec;
  spec.type = type;
  spec.cells = {cells, cells, cells};
  const auto mesh = Mesh::generateBox(spec);
  const auto sub = Mesh::extractSubdomains(mesh, std::vector<int>(mesh.numCells(), 0), 1)[0];
  const auto sys = Fem::assembleSubdomain(mesh, sub, Fem::Material{2.1e11, 0.3}, {});
  LocalCsr K = sys.K;
  const double rho = K.maxAbsDiagonal();
  for (int i : Feti::fixingDofs(sys.R, K.rows))
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k)
      if (K.col[k] == i) K.val[k] += rho;
  faceDofs.clear();
  for (size_t a = 0; a < sub.nodes.size(); ++a) {
    const auto& x = mesh.coords[sub.nodes[a]];
    if (std::abs(x[0] - spec.x[1]) < 1e-12 || std::abs(x[2] - spec.z[0]) < 1e-12)
      for (int c = 0; c < 3; ++c) faceDofs.push_back(3 * static_cast<int>(a) + c);
  }
  return K;
}

void checkSolves(const std::string& label, const LocalCsr& K, Teuchos::FancyOStream& out, bool& success) {
  const int n = K.rows, nrhs = 3;
  std::vector<double> x(static_cast<size_t>(n) * nrhs), b(x.size()), r(n);
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.1 * i + 0.3);
  for (int j = 0; j < nrhs; ++j) K.multiply(&x[static_cast<size_t>(j) * n], &b[static_cast<size_t>(j) * n]);
  for (const auto& name : localSolverNames()) {
    auto solver = createLocalSolver(name);
    solver->factor(K);
    std::vector<double> y(x.size());
    solver->solve(b.data(), y.data(), nrhs);
    double worst = 0;
    for (int j = 0; j < nrhs; ++j) {
      K.multiply(&y[static_cast<size_t>(j) * n], r.data());
      double num = 0, den = 0;
      for (int i = 0; i < n; ++i) {
        const double d = r[i] - b[static_cast<size_t>(j) * n + i];
        num += d * d;
        den += b[static_cast<size_t>(j) * n + i] * b[static_cast<size_t>(j) * n + i];
      }
      worst = std::max(worst, std::sqrt(num / den));
    }
    // One right-hand side alone gives the same as the block solve.
    std::vector<double> y1(n);
    solver->solve(b.data(), y1.data(), 1);
    const double same = Test::relDiff(y1, std::vector<double>(y.begin(), y.begin() + n));
    out << label << " " << name << ": ||K y - b|| / ||b|| = " << worst << ", single vs block rhs " << same << "\n";
    TEST_COMPARE(worst, <, 1e-10);
    TEST_COMPARE(same, <, 1e-12);
  }
}

void checkInverseBlocks(const std::string& label, const LocalCsr& K, const std::vector<int>& b,
                        Teuchos::FancyOStream& out, bool& success) {
  std::vector<double> reference;
  for (const auto& name : localSolverNames()) {
    auto solver = createLocalSolver(name);
    solver->factor(K, b);
    const auto Z = solver->inverseBlock(b);
    // The factor with b last still solves: K y = K x gives back x.
    std::vector<double> x(K.rows), Kx(K.rows), y(K.rows);
    for (int i = 0; i < K.rows; ++i) x[i] = std::cos(0.2 * i);
    K.multiply(x.data(), Kx.data());
    solver->solve(Kx.data(), y.data(), 1);
    const double solveErr = Test::relDiff(y, x);
    double asym = 0;
    const size_t nb = b.size();
    for (size_t i = 0; i < nb; ++i)
      for (size_t j = 0; j < i; ++j) asym = std::max(asym, std::abs(Z[i * nb + j] - Z[j * nb + i]) / std::abs(Z[i * nb + i]));
    if (reference.empty()) reference = Z;
    const double diff = Test::relDiff(Z, reference);
    out << label << " " << name << ": (K^-1)_bb of " << nb << " dofs vs " << localSolverNames()[0] << " " << diff
        << ", asymmetry " << asym << ", solve with b last " << solveErr << "\n";
    TEST_COMPARE(diff, <, 1e-9);
    TEST_COMPARE(asym, <, 1e-9);
    TEST_COMPARE(solveErr, <, 1e-8);
  }
}

// Both sizes of one cell type: 7^3 cells (512 nodes, 1536 dofs) and 2^3
// (CHOLMOD picks a simplicial factor).
void checkSolves(Mesh::CellType type, Teuchos::FancyOStream& out, bool& success) {
  std::vector<int> faceDofs;
  const auto K = regularizedStiffness(type, 7, faceDofs);
  checkSolves(Mesh::cellTypeName(type), K, out, success);
}

void checkInverseBlocks(Mesh::CellType type, int cells, Teuchos::FancyOStream& out, bool& success) {
  std::vector<int> faceDofs;
  const auto K = regularizedStiffness(type, cells, faceDofs);
  checkInverseBlocks(Mesh::cellTypeName(type) + " " + std::to_string(cells) + "^3", K, faceDofs, out, success);
}

}  // namespace

TEUCHOS_UNIT_TEST(LocalSolver, SolvesHex8) { checkSolves(Mesh::CellType::Hex8, out, success); }
TEUCHOS_UNIT_TEST(LocalSolver, InverseBlockHex8Large) { checkInverseBlocks(Mesh::CellType::Hex8, 7, out, success); }
TEUCHOS_UNIT_TEST(LocalSolver, InverseBlockHex8Small) { checkInverseBlocks(Mesh::CellType::Hex8, 2, out, success); }
TEUCHOS_UNIT_TEST(LocalSolver, SolvesTet4) { checkSolves(Mesh::CellType::Tet4, out, success); }
TEUCHOS_UNIT_TEST(LocalSolver, InverseBlockTet4Large) { checkInverseBlocks(Mesh::CellType::Tet4, 7, out, success); }
TEUCHOS_UNIT_TEST(LocalSolver, InverseBlockTet4Small) { checkInverseBlocks(Mesh::CellType::Tet4, 2, out, success); }
// 4^3 cells (375 dofs): CHOLMOD factors it densely (DenseBoundaryLast), the
// other backends by unit-vector solves, and the blocks must agree.
TEUCHOS_UNIT_TEST(LocalSolver, InverseBlockTet4Dense) { checkInverseBlocks(Mesh::CellType::Tet4, 4, out, success); }

// A second factorization on the same solver (refactor: new values on the
// pattern of the first, as the semismooth* Newton matrices come) solves the
// new matrix, not the first one.
TEUCHOS_UNIT_TEST(LocalSolver, RefactorSolvesTheNewMatrix) {
  for (int cells : {2, 7}) {
    std::vector<int> faceDofs;
    const auto K = regularizedStiffness(Mesh::CellType::Hex8, cells, faceDofs);
    LocalCsr K2 = K;  // another SPD matrix on the same pattern
    for (int i = 0; i < K2.rows; ++i)
      for (int k = K2.rowptr[i]; k < K2.rowptr[i + 1]; ++k)
        K2.val[k] *= (K2.col[k] == i ? 3.0 + std::sin(0.7 * i) : 1.0);
    const int n = K.rows;
    std::vector<double> x(n), b(n), y(n);
    for (int i = 0; i < n; ++i) x[i] = std::cos(0.3 * i + 0.1);
    K2.multiply(x.data(), b.data());
    for (const auto& name : localSolverNames()) {
      auto solver = createLocalSolver(name);
      solver->factor(K);
      solver->refactor(K2);
      solver->solve(b.data(), y.data(), 1);
      const double err = Test::relDiff(y, x);
      out << cells << "^3 " << name << ": refactor, then ||y - x|| / ||x|| = " << err << "\n";
      TEST_COMPARE(err, <, 1e-8);
      auto again = createLocalSolver(name);  // factor twice (a backend that factors again on refactor)
      again->factor(K);
      again->factor(K2);
      again->solve(b.data(), y.data(), 1);
      const double err2 = Test::relDiff(y, x);
      out << cells << "^3 " << name << ": factor twice, then ||y - x|| / ||x|| = " << err2 << "\n";
      TEST_COMPARE(err2, <, 1e-8);
    }
  }
}
