// Every shipped FCLIB problem solved by Algorithm 2 and by MSA + Algorithm 1
// (local problems directly, global ones through W = H'M^-1 H with a KLU2
// factorization of M), judged by the natural-map error err = ||phi||/||q||.
#include <Tpetra_Core.hpp>

#include <cstdio>
#include <iostream>

#include "Tribos_FCLIB_Solve.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::printf("%-46s %-15s %4s %6s %7s %8s %10s %10s %9s %s\n", "file", "method", "nc", "outer", "n_A", "time", "err",
              "err/max", "rank(W)", "reason");
  const char* only = argc > 1 ? argv[1] : nullptr;
  for (const auto& sample : fclib_test::samples()) {
    if (only && sample.name.find(only) == std::string::npos) continue;
    for (const std::string alg : {"Algorithm2", "MSA+Algorithm1"}) {
      FCLIB::SolveOptions opt;
      opt.algorithm = alg;
      opt.verbose = std::getenv("FCLIB_VERBOSE") != nullptr;
      const int cap = std::getenv("FCLIB_CAP") ? std::atoi(std::getenv("FCLIB_CAP")) : 200;
      opt.solverParams.sublist("Algorithm 2").set("Maximum Iterations", cap);
      opt.solverParams.sublist("MSA").set("Maximum Iterations", cap / 4);
      FCLIB::SolveReport rep;
      if (sample.kind == FCLIB::ProblemKind::Local)
        rep = FCLIB::solve(FCLIB::readLocal(fclib_test::samplePath(sample)), opt, comm);
      else
        rep = FCLIB::solve(FCLIB::readGlobal(fclib_test::samplePath(sample)), opt, comm);
      const int outer = alg == "Algorithm2" ? rep.status.outer_iterations : rep.status.msa_iterations;
      std::printf("%-46s %-15s %4d %6d %7lld %8.3f %10.2e %10.2e %4d/%-4d %s\n", sample.name.c_str(), alg.c_str(),
                  sample.contacts, outer, rep.n_A, rep.timeSolve, rep.err.relativeToQ, rep.err.relativeToMax,
                  rep.numericalRank, 3 * sample.contacts, rep.status.reason.c_str());
      FCLIB_CHECK(rep.err.relativeToQ <= 1e-8, sample.name << " " << alg << ": err " << rep.err.relativeToQ);
    }
  }
  return fclib_test::finish("fclib_test_solve");
}
