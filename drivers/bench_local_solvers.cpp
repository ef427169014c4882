// bench_local_solvers: the sparse direct solvers behind K+ (Tribos_LocalSolver)
// on one regularized subdomain stiffness matrix, the matrix FetiProblem
// factors: K_reg = K_s + rho sum_{i in I} e_i e_i' with I = fixingDofs(R_s)
// and rho = max diag K_s.
//
// For every solver: factor time, solve time with 1 and 6 right-hand sides,
// memory (heap held by the factorization, peak-RSS growth, and the factor
// size the backend reports), and the accuracy ||K_reg x - b|| / ||b||.
//
//   tribos_bench_local_solvers [--element Tet4|Hex8|both] [--cells N]
//                              [--solvers CHOLMOD,KLU2,Tacho] [--repeat R]
//
// The peak-RSS growth is only meaningful for the first solver of a process
// (the peak never decreases), so docs/benchmarks.md runs one solver per
// process; the heap figure (mallinfo2) is valid in any order.
#include <Tpetra_Core.hpp>

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_ProcessStartup.hpp"

using namespace Tribos;

namespace {

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double heapInUseMb() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<double>(mi.uordblks + mi.hblkhd) / 1048576.0;
}

double peakRssMb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

// One floating subdomain: a unit cube of N^3 cells, regularized by fixing nodes.
LocalCsr regularizedSubdomain(Mesh::CellType type, int cells) {
  Mesh::BoxSpec spec;
  spec.type = type;
  spec.cells = {cells, cells, cells};
  Mesh::DecompositionSpec dec;  // one Structured subdomain
  Mesh::Discretization disc(Mesh::generateBox(spec), spec, dec, 1, 0);
  const auto sys = Fem::assembleSubdomain(disc, 0, Fem::Material{2.1e11, 0.3}, Fem::LoadCase{});
  LocalCsr K = sys.K;
  const double rho = K.maxAbsDiagonal();
  for (int i : Feti::fixingDofs(sys.R, sys.numDofs()))
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k)
      if (K.col[k] == i) K.val[k] += rho;
  return K;
}

struct Result {
  std::string element, solver;
  int n = 0;
  long long nnz = 0;
  double factor = 0, solve1 = 0, solve6 = 0, heapMb = 0, rssMb = 0, factorMb = 0, residual = 0;
  std::string error;
};

Result bench(const std::string& element, const LocalCsr& K, const std::string& name, int repeat) {
  Result r;
  r.element = element;
  r.solver = name;
  r.n = K.rows;
  r.nnz = static_cast<long long>(K.val.size());
  const int n = K.rows;
  // Smooth, non-trivial right-hand sides.
  std::vector<double> b(6 * static_cast<size_t>(n)), x(b.size()), Kx(n);
  for (size_t i = 0; i < b.size(); ++i) b[i] = std::sin(0.013 * i + 0.7) + 0.1 * std::cos(1.7 * i);
  try {
    const double heap0 = heapInUseMb(), rss0 = peakRssMb();
    auto solver = createLocalSolver(name);
    double t = nowSeconds();
    solver->factor(K);
    r.factor = nowSeconds() - t;
    t = nowSeconds();
    for (int k = 0; k < repeat; ++k) solver->solve(b.data(), x.data(), 1);
    r.solve1 = (nowSeconds() - t) / repeat;
    t = nowSeconds();
    for (int k = 0; k < repeat; ++k) solver->solve(b.data(), x.data(), 6);
    r.solve6 = (nowSeconds() - t) / repeat;
    r.heapMb = heapInUseMb() - heap0;
    r.rssMb = peakRssMb() - rss0;
    r.factorMb = solver->factorMemoryMb();
    double num = 0, den = 0;
    for (int j = 0; j < 6; ++j) {
      K.multiply(&x[static_cast<size_t>(j) * n], Kx.data());
      for (int i = 0; i < n; ++i) {
        const double d = Kx[i] - b[static_cast<size_t>(j) * n + i];
        num += d * d;
        den += b[static_cast<size_t>(j) * n + i] * b[static_cast<size_t>(j) * n + i];
      }
    }
    r.residual = std::sqrt(num / den);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  // Kokkos (used by Amesos2 and Tacho) is initialized by the Tpetra guard.
  Tpetra::ScopeGuard guard(&argc, &argv);
  std::string element = "both", solvers = "CHOLMOD,KLU2,Tacho";
  int cells = 14, repeat = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--element") element = next();
    else if (a == "--cells") cells = std::stoi(next());
    else if (a == "--solvers") solvers = next();
    else if (a == "--repeat") repeat = std::max(1, std::stoi(next()));
    else {
      std::cerr << "usage: " << argv[0]
                << " [--element Tet4|Hex8|both] [--cells N] [--solvers CHOLMOD,KLU2,Tacho] [--repeat R]\n";
      return 2;
    }
  }
  std::vector<std::string> elements = element == "both" ? std::vector<std::string>{"Hex8", "Tet4"}
                                                        : std::vector<std::string>{element};
  std::printf("%-5s %-8s %7s %9s %10s %10s %10s %9s %9s %10s %9s\n", "elem", "solver", "dofs", "nnz", "factor_s",
              "solve1_s", "solve6_s", "heap_MB", "rss_MB", "factor_MB", "residual");
  for (const auto& e : elements) {
    const LocalCsr K = regularizedSubdomain(Mesh::cellTypeFromName(e), cells);
    for (const auto& s : split(solvers)) {
      const Result r = bench(e, K, s, repeat);
      if (!r.error.empty()) {
        std::printf("%-5s %-8s %7d %9lld  FAILED: %s\n", r.element.c_str(), r.solver.c_str(), r.n, r.nnz,
                    r.error.c_str());
        continue;
      }
      std::printf("%-5s %-8s %7d %9lld %10.4f %10.5f %10.5f %9.1f %9.1f %10.1f %9.1e\n", r.element.c_str(),
                  r.solver.c_str(), r.n, r.nnz, r.factor, r.solve1, r.solve6, r.heapMb, r.rssMb, r.factorMb,
                  r.residual);
      std::fflush(stdout);
    }
  }
  return 0;
}
