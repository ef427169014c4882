// tribos_prism_bench: the semismooth* prism benchmark over mesh levels, in
// the format of the paper's Table 1.
//   tribos_prism_bench [--input file.xml] [--levels 2 8] [--log] [--reduced-cg]
//                      [--newton-solver NAME] [--param NAME VALUE]...
// --param sets any other parameter of Solver/SemismoothStarNewton (a number
// with a '.' or 'e' is a double, other numbers are ints, else a string).
// --newton-solver sets Solver/SemismoothStarNewton/"Newton Solver" ("Sparse
// Direct", "Reduced CG", "CG+MueLu"); --reduced-cg is --newton-solver "Reduced CG".
// Columns: reduction(s) is the K_rr factorization and l (CG+MueLu: MueLu
// setup of both hierarchies and the initial solve); setup(s) is all MueLu
// setups (CG+MueLu only, partly inside reduction(s) and solver(s)); total(s)
// is the wall time of everything (assembly, reduction, solve).
#include <Tpetra_Core.hpp>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_SemismoothStarNewton.hpp"
#include "Tribos_ProcessStartup.hpp"

namespace {

void setParameter(Teuchos::ParameterList& pl, const std::string& name, const std::string& value) {
  char* end = nullptr;
  const double d = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end) pl.set(name, value);
  else if (value.find_first_of(".eE") != std::string::npos) pl.set(name, d);
  else pl.set(name, std::atoi(value.c_str()));
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  std::string input;
  if (const char* src = std::getenv("TRIBOS_SOURCE_DIR")) input = std::string(src) + "/input/prism_tresca.xml";
  else input = "input/prism_tresca.xml";
  int Lmin = 2, Lmax = 8;
  bool log = false;
  std::string newtonSolver;
  std::vector<std::pair<std::string, std::string>> extra;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--input") && i + 1 < argc) input = argv[++i];
    else if (!std::strcmp(argv[i], "--levels") && i + 2 < argc) {
      Lmin = std::atoi(argv[++i]);
      Lmax = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--log")) log = true;
    else if (!std::strcmp(argv[i], "--reduced-cg")) newtonSolver = "Reduced CG";
    else if (!std::strcmp(argv[i], "--newton-solver") && i + 1 < argc) newtonSolver = argv[++i];
    else if (!std::strcmp(argv[i], "--param") && i + 2 < argc) {
      extra.emplace_back(argv[i + 1], argv[i + 2]);
      i += 2;
    }
    else {
      std::cerr << "usage: " << argv[0] << " [--input file.xml] [--levels Lmin Lmax] [--log] [--reduced-cg] [--newton-solver NAME] [--param NAME VALUE]...\n";
      return 2;
    }
  }
  // With CG+MueLu the CG solves are spread over the ranks of mpirun; rank 0
  // prints. The other Newton solvers are serial: run them on one rank.
  auto comm = Tpetra::getDefaultComm();
  std::ostringstream sink;
  std::ostream& out = comm->getRank() == 0 ? std::cout : sink;
  try {
    out << "ranks: " << comm->getSize() << "\n";
    out << "input: " << input << "\n"
              << "level    nodes  assembly(s)  reduction(s)  contact nodes  solver(s)  iters"
                 "   contact  stick  slip  Newton-factor(s)  CG steps  setup(s)  total(s)\n";
    for (int L = Lmin; L <= Lmax; ++L) {
      Semismooth::MeshContactProblem pr =
          Input::semismoothProblem(*Input::read(input, {"Mesh/Level=" + std::to_string(L)}));
      if (!newtonSolver.empty()) pr.solverParams.set("Newton Solver", newtonSolver);
      for (const auto& [name, value] : extra) setParameter(pr.solverParams, name, value);
      const auto start = std::chrono::steady_clock::now();
      const Semismooth::SemismoothResult r =
          Semismooth::solveFromMesh(pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction,
                                    pr.solverParams, log ? &out : nullptr, comm);
      // Wall time of assembly, reduction/setup and solve together.
      const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      out << std::setw(5) << L << std::setw(9) << r.numNodes << std::fixed << std::setprecision(3)
                << std::setw(13) << r.assemblySeconds << std::setw(14) << r.reductionSeconds << std::setw(15)
                << r.numContactNodes << std::setw(11) << r.solverSeconds << std::setw(7) << r.iterations
                << (r.converged ? " " : "*") << std::setw(9) << r.numContact.back() << std::setw(7)
                << r.numStick.back() << std::setw(6) << r.numSlip.back() << std::setw(17) << r.newtonFactorSeconds << std::setw(10) << r.cgIterations << std::setw(10)
                << r.preconditionerSeconds << std::setw(10) << total
                << std::defaultfloat << std::endl;
    }
  } catch (const Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
