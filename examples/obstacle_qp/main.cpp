// obstacle_qp: a discrete obstacle problem solved by the installed Tribos QP
// solvers, from a program of its own (see CMakeLists.txt beside this file).
//
//   min 1/2 x'Ax - b'x  subject to  x_i >= l_i,
//
// A = tridiag(-1, 2, -1) (the 1D Laplacian, SPD), distributed by Tpetra over
// the MPI ranks. The answer is manufactured: a chosen x* touches the obstacle
// on a known set of nodes, and b = A x* - g with the multipliers g_i > 0 on
// that set and g_i = 0 elsewhere satisfies the KKT conditions, so x* is the
// unique minimizer. The solver is taken by name from the registry
// qpSolvers(), with its parameters validated as in Tribos' input files.
// Exits 0 when the computed x matches x*, 1 otherwise.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>

#include <cmath>
#include <iostream>

#include "Tribos_QP.hpp"
#include "Tribos_Types.hpp"
#include "Tribos_ProcessStartup.hpp"

namespace {

using namespace Tribos;

constexpr GO kN = 200;

// The obstacle and the manufactured solution at global index i: nodes
// 60..139 lie on the obstacle l = -0.5, the others strictly above it.
double obstacle(GO) { return -0.5; }
bool onObstacle(GO i) { return i >= 60 && i < 140; }
double exactX(GO i) {
  if (onObstacle(i)) return obstacle(i);
  const double t = double(i) / double(kN);
  return obstacle(i) + 0.1 + 0.3 * std::sin(3.0 * t) + 0.05 * double(i % 7);  // sin(3t) >= 0 on [0, 1)
}
double multiplier(GO i) { return onObstacle(i) ? 1.0 + 0.01 * double(i % 5) : 0.0; }

RCP<CrsMatrix> laplacian(const RCP<const Map>& map) {
  auto A = rcp(new CrsMatrix(map, 3));
  for (LO l = 0; l < LO(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    Teuchos::Array<GO> cols;
    Teuchos::Array<SC> vals;
    if (i > 0) cols.push_back(i - 1), vals.push_back(-1.0);
    cols.push_back(i), vals.push_back(2.0);
    if (i + 1 < kN) cols.push_back(i + 1), vals.push_back(-1.0);
    A->insertGlobalValues(i, cols(), vals());
  }
  A->fillComplete();
  return A;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  auto map = rcp(new Map(kN, 0, comm));
  auto A = laplacian(map);

  // b = A x* - g.
  Vector xExact(map), g(map), b(map);
  QP::ConstraintSet Omega(map);
  for (LO l = 0; l < LO(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    xExact.replaceLocalValue(l, exactX(i));
    g.replaceLocalValue(l, multiplier(i));
    Omega.setLower(l, obstacle(i));
  }
  A->apply(xExact, b);
  b.update(-1.0, g, 1.0);

  auto params = Teuchos::parameterList();
  params->set("Relative Tolerance", 1e-12);
  params->set("Maximum Iterations", 5000);
  auto solver = QP::qpSolvers().create("MPRGP", params);

  Vector x(map);  // start from 0, projected onto the set by the solver
  const QP::QPStatus status = solver->solve(*A, b, Omega, x);

  Vector err(map);
  err.update(1.0, x, -1.0, xExact, 0.0);
  const double error = err.normInf();
  // Nodes the solver put on the obstacle, against the 80 of x*.
  int active = 0;
  for (LO l = 0; l < LO(map->getNodeNumElements()); ++l)
    active += x.getData()[l] <= obstacle(map->getGlobalElement(l)) + 1e-12;
  int activeTotal = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, active, Teuchos::outArg(activeTotal));

  const bool ok = status.converged && error < 1e-6 && activeTotal == 80;
  if (root) {
    std::cout << "obstacle_qp: " << QP::qpSolvers().canonical("MPRGP") << " on " << comm->getSize()
              << " rank(s), n = " << kN << "\n"
              << status << "\n"
              << "max |x - x*| = " << error << ", nodes on the obstacle = " << activeTotal << " (expected 80)\n"
              << (ok ? "obstacle_qp: correct" : "obstacle_qp: WRONG ANSWER") << std::endl;
  }
  return ok ? 0 : 1;
}
