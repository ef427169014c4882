// tribos_fclib_vs_siconos: one FCLIB problem solved by Siconos' fc3d solvers
// (PROX, NSN Alart-Curnier, NSGS) and by Tribos' friction algorithms, to the
// same tolerance, in one run; every solution measured by the same function
// (FCLIB::naturalMapError, ||F_nat|| / ||q||), not by each library's own
// error. A global problem is reduced to its local one first (W = H'M^-1 H
// formed, q = H'M^-1 f + w), and both libraries solve that.
//   tribos_fclib_vs_siconos FILE.hdf5 [--tolerance 1e-8] [--max-iterations N (Siconos, 10000)]
//                           [--tribos-max-iterations N (default: the algorithms' own)] [--repeat R]
//                           [--siconos PROX,NSN-AC,NSGS] [--tribos "Semismooth Newton,NSGS,Algorithm2,MSA+Algorithm1"]
//                           [--storage sparse-block|sparse|dense] [--siconos-scaled] [--reuse]
// Prints one Markdown table row per solver (Siconos' rows note its return
// code, the error its solver reported, dparam[RESIDU], and its
// fc3d_compute_error of the returned r with u = c (W r + q), on the
// problem it solved: c W, c q with c = 1/max|W_ij|, see siconosMatrix): time (the fastest of R runs, the
// solver call alone: fc3d_driver on the assembled matrix and made options;
// FCLIB::Solver::solve on the read problem with the solver made, without the
// diagnostic spectrum), iterations (Siconos:
// iparam[ITER_DONE]; Tribos: Newton steps, Algorithm 2 loops, MSA steps),
// the residual, and whether it is at most the tolerance. By default each run
// makes its method anew (Siconos' problem and options, Tribos' Solver)
// outside the timing; with --reuse both are made once and the R solves
// follow each other, as in a time-stepping code that solves one problem per
// step with the same method.
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_FCLIB.hpp"
#include "Tribos_FCLIB_Accuracy.hpp"
#include "Tribos_FCLIB_Solve.hpp"

extern "C" {
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "NumericsVerbose.h"
#include "SolverOptions.h"
#include "SparseBlockMatrix.h"
#include "fc3d_compute_error.h"
}

#include "Tribos_ProcessStartup.hpp"

namespace {

using namespace Tribos;

struct Args {
  std::string input;
  double tolerance = 1e-8;
  int maxIterations = 10000;        // Siconos' iparam[MAX_ITER]
  int tribosMaxIterations = 0;      // 0: each algorithm's own limit (FCLIB defaults)
  int repeat = 3;
  std::vector<std::string> siconos{"PROX", "NSN-AC", "NSGS"};
  std::vector<std::string> tribos{"Semismooth Newton", "NSGS", "Algorithm2", "MSA+Algorithm1"};
  std::string storage = "sparse-block";
  bool scaleSiconos = false;
  bool reuse = false;  // the method made once for all R runs
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() {
      TRIBOS_REQUIRE(i + 1 < argc, s << " needs a value");
      return std::string(argv[++i]);
    };
    auto number = [&](const std::string& text) {
      std::size_t used = 0;
      double v = std::numeric_limits<double>::quiet_NaN();
      try {
        v = std::stod(text, &used);
      } catch (const std::exception&) {
      }
      TRIBOS_REQUIRE(used == text.size() && std::isfinite(v), s << ": \"" << text << "\" is not a finite number");
      return v;
    };
    if (s == "--tolerance") {
      a.tolerance = number(next());
      TRIBOS_REQUIRE(a.tolerance > 0 && a.tolerance < 1, "--tolerance: expected 0 < TOL < 1");
    } else if (s == "--max-iterations") {
      const double v = number(next());
      TRIBOS_REQUIRE(v >= 1 && v <= 1e8 && v == std::floor(v), "--max-iterations: expected an integer >= 1");
      a.maxIterations = static_cast<int>(v);
    } else if (s == "--tribos-max-iterations") {
      const double v = number(next());
      TRIBOS_REQUIRE(v >= 1 && v <= 1e8 && v == std::floor(v), "--tribos-max-iterations: expected an integer >= 1");
      a.tribosMaxIterations = static_cast<int>(v);
    } else if (s == "--repeat") {
      const double v = number(next());
      TRIBOS_REQUIRE(v >= 1 && v <= 100000 && v == std::floor(v), "--repeat: expected an integer in 1 .. 100000");
      a.repeat = static_cast<int>(v);
    } else if (s == "--siconos") {
      a.siconos = split(next());
    } else if (s == "--tribos") {
      a.tribos = split(next());
    } else if (s == "--storage") {
      a.storage = next();
      TRIBOS_REQUIRE(a.storage == "sparse-block" || a.storage == "sparse" || a.storage == "dense",
                     "--storage: unknown \"" << a.storage << "\"; valid: sparse-block, sparse, dense");
    } else if (s == "--siconos-scaled") {
      a.scaleSiconos = true;
    } else if (s == "--reuse") {
      a.reuse = true;
    } else if (!s.empty() && s[0] == '-') {
      throw Error("unknown option " + s);
    } else {
      a.input = s;
    }
  }
  TRIBOS_REQUIRE(!a.input.empty(), "usage: tribos_fclib_vs_siconos FILE.hdf5 [--tolerance TOL] [--max-iterations N] "
                                   "[--repeat R] [--siconos PROX,NSN-AC,NSGS] [--tribos NAME,...] [--storage S] [--reuse]");
  for (const auto& n : a.siconos)
    TRIBOS_REQUIRE(n == "PROX" || n == "NSN-AC" || n == "NSGS",
                   "--siconos: unknown \"" << n << "\"; valid: PROX, NSN-AC, NSGS");
  const auto valid = FCLIB::coulombAlgorithms();
  for (const auto& n : a.tribos)
    TRIBOS_REQUIRE(std::find(valid.begin(), valid.end(), n) != valid.end(),
                   "--tribos: unknown \"" << n << "\"; valid: " << joinNames(valid));
  return a;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The local problem of a global one: W = H'M^-1 H (its nonzero entries), q.
FCLIB::LocalProblem localOf(const FCLIB::GlobalProblem& g, const RCP<const Comm>& comm) {
  auto M = std::make_shared<const FCLIB::MassSolver>(g.M, "KLU2");
  const int n = 3 * g.numberOfContacts();
  auto map = rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, comm));
  FCLIB::DelassusOperator op(g.H, M, map);
  const LocalCsr W = op.explicitMatrix();
  FCLIB::LocalProblem p;
  p.spacedim = 3;
  p.W = FCLIB::fromCSR(n, n, W.rowptr, W.col, W.val, "W = H'M^-1 H");
  p.mu = g.mu;
  std::vector<double> vFree;
  M->solve(g.f, vFree);
  g.H.multiplyTranspose(vFree, p.q);
  for (int i = 0; i < n; ++i) p.q[i] += g.w[i];
  return p;
}

struct Row {
  std::string solver;
  double time = 0;
  long long iterations = 0;
  double residual = 0;
  std::string note;
};

// ---------------------------------------------------------------- Siconos

// c W: c = 1 by default, c = 1 / max |W_ij| with --siconos-scaled. c W, c q
// have the same solution r (u scales by c), but ||F_nat||/||q|| is not
// invariant under c (it subtracts velocities from forces), so Siconos then
// stops on the measure of the scaled problem while the table measures the
// original one.
NumericsMatrix* siconosMatrix(const LocalCsr& W, double c, const std::string& storage) {
  const int n = W.rows;
  if (storage == "dense") {
    NumericsMatrix* A = NM_create(NM_DENSE, n, n);
    std::fill(A->matrix0, A->matrix0 + static_cast<size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int k = W.rowptr[i]; k < W.rowptr[i + 1]; ++k) A->matrix0[static_cast<size_t>(W.col[k]) * n + i] += c * W.val[k];
    return A;
  }
  NumericsMatrix* T = NM_create(NM_SPARSE, n, n);
  NM_triplet_alloc(T, W.nnz());
  for (int i = 0; i < n; ++i)
    for (int k = W.rowptr[i]; k < W.rowptr[i + 1]; ++k) NM_entry(T, i, W.col[k], c * W.val[k]);
  if (storage == "sparse") return T;
  NumericsMatrix* A = NM_create(NM_SPARSE_BLOCK, n, n);
  TRIBOS_REQUIRE(SBM_from_csparse(3, NM_csc(T), A->matrix1) == 0, "Siconos: SBM_from_csparse failed");
  NM_free(T);
  return A;
}

int siconosId(const std::string& name) {
  if (name == "PROX") return SICONOS_FRICTION_3D_PROX;
  if (name == "NSN-AC") return SICONOS_FRICTION_3D_NSN_AC;
  return SICONOS_FRICTION_3D_NSGS;
}

Row runSiconos(const std::string& name, const FCLIB::LocalProblem& p, const Args& args) {
  Row row;
  row.solver = "Siconos " + name;
  const int nc = p.numberOfContacts(), n = 3 * nc;
  row.time = std::numeric_limits<double>::infinity();
  std::vector<double> r(n), u(n);
  const double c = args.scaleSiconos ? 1.0 / FCLIB::maxAbs(p.W) : 1.0;
  NumericsMatrix* W = nullptr;
  FrictionContactProblem* problem = nullptr;
  SolverOptions* options = nullptr;
  std::vector<double> q, mu;
  auto make = [&] {
    W = siconosMatrix(p.W, c, args.storage);
    q = p.q, mu = p.mu;
    for (double& v : q) v *= c;
    problem = frictionContactProblem_new_with_data(3, nc, W, q.data(), mu.data());
    options = solver_options_create(siconosId(name));
    options->dparam[SICONOS_DPARAM_TOL] = args.tolerance;
    options->iparam[SICONOS_IPARAM_MAX_ITER] = args.maxIterations;
  };
  auto release = [&] {
    solver_options_delete(options);
    // The problem holds W, q and mu; q and mu are ours (std::vector).
    problem->q = nullptr;
    problem->mu = nullptr;
    frictionContactProblem_free(problem);
  };
  if (args.reuse) make();
  for (int rep = 0; rep < args.repeat; ++rep) {
    if (!args.reuse) make();
    std::fill(r.begin(), r.end(), 0.0);
    std::fill(u.begin(), u.end(), 0.0);
    const auto t0 = std::chrono::steady_clock::now();
    const int info = fc3d_driver(problem, r.data(), u.data(), options);
    const double t = seconds(t0);
    row.time = std::min(row.time, t);
    row.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
    if (args.reuse && rep + 1 < args.repeat) continue;
    // Siconos' own measure of its result: the error its solver reported and
    // fc3d_compute_error on (r, W r + q): our natural map, divided by
    // max(||q||, ||r||, ||u||) instead of ||q|| (docs/benchmarks.md).
    std::vector<double> w(n);
    p.W.multiply(r, w);
    for (int i = 0; i < n; ++i) w[i] = c * (w[i] + p.q[i]);
    double normQ = 0, recomputed = 0;
    for (double v : q) normQ += v * v;
    fc3d_compute_error(problem, r.data(), w.data(), args.tolerance, options, std::sqrt(normQ), &recomputed);
    char own[128];
    std::snprintf(own, sizeof own, "info %d, reported error %.2e, fc3d_compute_error %.2e", info,
                  options->dparam[SICONOS_DPARAM_RESIDU], recomputed);
    row.note = own;
    if (!args.reuse) release();
  }
  if (args.reuse) release();
  row.residual = FCLIB::naturalMapError(p, r).relativeToQ;
  return row;
}

// ---------------------------------------------------------------- Tribos

Row runTribos(const std::string& name, const FCLIB::LocalProblem& p, const Args& args, const RCP<const Comm>& comm) {
  Row row;
  row.solver = "Tribos " + name;
  row.time = std::numeric_limits<double>::infinity();
  FCLIB::SolveOptions options;
  options.algorithm = name;
  options.naturalMapTolerance = args.tolerance;
  options.maxIterations = args.tribosMaxIterations;
  options.denseSpectrumLimit = 0;
  FCLIB::SolveReport rep;
  try {
    // The method made and its parameters checked outside the timing, as
    // Siconos' solver_options_create is.
    std::unique_ptr<const FCLIB::Solver> solver;
    for (int k = 0; k < args.repeat; ++k) {
      if (!solver || !args.reuse) solver = std::make_unique<const FCLIB::Solver>(options, comm);
      const auto t0 = std::chrono::steady_clock::now();
      rep = solver->solve(p);
      row.time = std::min(row.time, seconds(t0));
    }
  } catch (const std::exception& e) {
    row.note = e.what();
    row.residual = std::numeric_limits<double>::quiet_NaN();
    return row;
  }
  row.iterations = rep.status.msa_iterations > 0 ? rep.status.msa_iterations : rep.status.outer_iterations;
  row.residual = FCLIB::naturalMapError(p, rep.r).relativeToQ;
  if (!rep.status.converged) row.note = rep.stopReason;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  try {
    TRIBOS_REQUIRE(comm->getSize() == 1, "tribos_fclib_vs_siconos runs on one rank");
    const Args args = parse(argc, argv);
    numerics_set_verbose(0);
    FCLIB::LocalProblem p;
    if (FCLIB::problemKind(args.input) == FCLIB::ProblemKind::Local) p = FCLIB::readLocal(args.input);
    else p = localOf(FCLIB::readGlobal(args.input), comm);
    std::printf("%s: %d contacts, nnz(W) %d, tolerance %.1e on ||F_nat||/||q||, best of %d run(s)\n\n",
                args.input.c_str(), p.numberOfContacts(), p.W.nnz(), args.tolerance, args.repeat);
    std::printf("| solver | time (s) | iterations | ||F_nat||/||q|| | <= tol | note |\n|---|---:|---:|---:|---|---|\n");
    std::vector<Row> rows;
    for (const auto& n : args.siconos) rows.push_back(runSiconos(n, p, args));
    for (const auto& n : args.tribos) rows.push_back(runTribos(n, p, args, comm));
    for (const auto& r : rows)
      std::printf("| %s | %.4g | %lld | %.2e | %s | %s |\n", r.solver.c_str(), r.time, r.iterations, r.residual,
                  r.residual <= args.tolerance ? "yes" : "no", r.note.substr(0, 120).c_str());
    auto best = [&](const std::string& prefix) {
      double t = std::numeric_limits<double>::infinity();
      for (const auto& r : rows)
        if (r.solver.rfind(prefix, 0) == 0 && r.residual <= args.tolerance) t = std::min(t, r.time);
      return t;
    };
    const double s = best("Siconos"), t = best("Tribos");
    std::printf("\nbest within tolerance: Siconos %.4g s, Tribos %.4g s, ratio Siconos/Tribos %.3g\n", s, t, s / t);
  } catch (const std::exception& e) {
    std::cerr << "tribos_fclib_vs_siconos: error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
