// tribos_prism_bench: the semismooth* prism benchmark over mesh levels, in
// the format of the paper's Table 1.
//   tribos_prism_bench [--input file.xml] [--levels 2 8] [--log] [--reduced-cg]
// --reduced-cg replaces the sparse direct Newton solves by CG on the
// contact boundary (Solver/SemismoothStarNewton/"Newton Solver").
#include <Tpetra_Core.hpp>

#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iostream>

#include "Tribos_Error.hpp"
#include "Tribos_SemismoothInput.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  std::string input;
  if (const char* src = std::getenv("TRIBOS_SOURCE_DIR")) input = std::string(src) + "/input/prism_tresca.xml";
  else input = "input/prism_tresca.xml";
  int Lmin = 2, Lmax = 8;
  bool log = false;
  std::string newtonSolver;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--input") && i + 1 < argc) input = argv[++i];
    else if (!std::strcmp(argv[i], "--levels") && i + 2 < argc) {
      Lmin = std::atoi(argv[++i]);
      Lmax = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--log")) log = true;
    else if (!std::strcmp(argv[i], "--reduced-cg")) newtonSolver = "Reduced CG";
    else {
      std::cerr << "usage: " << argv[0] << " [--input file.xml] [--levels Lmin Lmax] [--log] [--reduced-cg]\n";
      return 2;
    }
  }
  try {
    std::cout << "input: " << input << "\n"
              << "level    nodes  assembly(s)  reduction(s)  contact nodes  solver(s)  iters"
                 "   contact  stick  slip  Newton-factor(s)  CG steps\n";
    for (int L = Lmin; L <= Lmax; ++L) {
      Semismooth::MeshContactProblem pr = Semismooth::readMeshContactProblem(input, L);
      if (!newtonSolver.empty()) pr.solverParams.set("Newton Solver", newtonSolver);
      const Semismooth::SemismoothResult r =
          Semismooth::solveFromMesh(pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction,
                                    pr.solverParams, log ? &std::cout : nullptr);
      std::cout << std::setw(5) << L << std::setw(9) << r.numNodes << std::fixed << std::setprecision(3)
                << std::setw(13) << r.assemblySeconds << std::setw(14) << r.reductionSeconds << std::setw(15)
                << r.numContactNodes << std::setw(11) << r.solverSeconds << std::setw(7) << r.iterations
                << (r.converged ? " " : "*") << std::setw(9) << r.numContact.back() << std::setw(7)
                << r.numStick.back() << std::setw(6) << r.numSlip.back() << std::setw(17) << r.newtonFactorSeconds << std::setw(10) << r.cgIterations
                << std::defaultfloat << std::endl;
    }
  } catch (const Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
