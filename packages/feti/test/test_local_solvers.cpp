// Every local solver backend factors a regularized subdomain stiffness of more
// than 1024 rows (Tacho's sparse path) and solves it to round-off, one and
// several right-hand sides at once.
#include <Tpetra_Core.hpp>

#include <cmath>

#include "Tribos_Assembly.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_TestSupport.hpp"

using namespace Tribos;

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  for (auto type : {Mesh::CellType::Hex8, Mesh::CellType::Tet4}) {
    Mesh::BoxSpec spec;
    spec.type = type;
    spec.cells = {7, 7, 7};  // 512 nodes, 1536 dofs
    const auto mesh = Mesh::generateBox(spec);
    const auto sub = Mesh::extractSubdomains(mesh, std::vector<int>(mesh.numCells(), 0), 1)[0];
    const auto sys = Fem::assembleSubdomain(mesh, sub, {2.1e11, 0.3}, {});
    LocalCsr K = sys.K;
    const int n = K.rows;
    const double rho = K.maxAbsDiagonal();
    for (int i : Feti::fixingDofs(sys.R, n))
      for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k)
        if (K.col[k] == i) K.val[k] += rho;
    const int nrhs = 3;
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
      std::cout << Mesh::cellTypeName(type) << " " << name << ": ||K y - b|| / ||b|| = " << worst
                << ", single vs block rhs " << same << std::endl;
      CHECK(worst < 1e-10, name << " residual " << worst);
      CHECK(same < 1e-12, name << " single vs block right-hand side " << same);
    }
  }
  return Test::failures() ? 1 : 0;
}
