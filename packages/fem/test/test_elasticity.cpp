// Elasticity: patch test, convergence to a manufactured solution, rigid-body
// kernel of every subdomain. Runs on any number of ranks; results must not
// depend on it.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>

#include "Tribos_Assembly.hpp"
#include "Tribos_Decomposition.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Monolithic.hpp"

namespace {

using namespace Tribos;
using Fem::Point;

Teuchos::ParameterList solverParams(const std::string& kind) {
  Teuchos::ParameterList p = *Fem::MonolithicSystem::getValidParameters();
  p.set("Linear Solver", kind);
  p.set("Tolerance", 1e-13);
  return p;
}

Mesh::Discretization makeDisc(Mesh::CellType type, std::array<int, 3> cells, int S, const Comm& comm) {
  Mesh::BoxSpec spec;
  spec.type = type;
  spec.cells = cells;
  Mesh::DecompositionSpec dec;
  dec.partitioner = "METIS";
  dec.subdomains = S;
  return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
}

Fem::LoadCase allFacesDirichlet(std::function<Point(const Point&)> field) {
  Fem::LoadCase loads;
  for (const char* face : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}) {
    Fem::DirichletCondition bc;
    bc.face = face;
    bc.field = field;
    loads.dirichlet.push_back(bc);
  }
  return loads;
}

// A uniform strain (with a rotation part) imposed on the boundary must be
// reproduced at every interior node to round-off.
void patchTest(Mesh::CellType type, const std::string& solver, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, 5e-4, 2.5e-4}, {4e-4, -2e-4, -6e-4}};
  const Point b = {1e-3, -2e-3, 5e-4};
  auto exact = [&](const Point& x) {
    Point u;
    for (int i = 0; i < 3; ++i) u[i] = b[i] + A[i][0] * x[0] + A[i][1] * x[1] + A[i][2] * x[2];
    return u;
  };
  auto disc = makeDisc(type, {3, 3, 4}, 3, *comm);
  Fem::Material mat{2.1e11, 0.3};
  Fem::MonolithicSystem sys(disc, mat, allFacesDirichlet(exact), comm);
  const auto res = sys.solve(solverParams(solver));
  // Every rank checks the nodes of its part; the worst over the ranks.
  double worst[2] = {0, 0}, over[2];
  for (int n = 0; n < disc.part.numNodes(); ++n) {
    const Point u = exact(disc.part.coords[n]);
    for (int c = 0; c < 3; ++c) {
      worst[0] = std::max(worst[0], std::abs(res.u.at(disc.meshNode(n))[c] - u[c]));
      worst[1] = std::max(worst[1], std::abs(u[c]));
    }
  }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, worst, over);
  const double err = over[0], scale = over[1];
  out << "patch test " << Mesh::cellTypeName(type) << " " << solver << ": max error / max u = " << err / scale << "\n";
  TEST_COMPARE(err / scale, <, 1e-9);
}

// u = c (y^2, z^2, x^2) has div u = 0, so -div sigma = -mu Laplace u = -2 mu c (1,1,1):
// a constant volume force. Errors in L2 and energy norms over local cells.
std::pair<double, double> manufacturedErrors(Mesh::CellType type, int n, const RCP<const Comm>& comm) {
  const double c = 1e-3;
  Fem::Material mat{1.0, 0.25};
  auto exact = [&](const Point& x) { return Point{c * x[1] * x[1], c * x[2] * x[2], c * x[0] * x[0]}; };
  auto disc = makeDisc(type, {n, n, n}, std::min(4, comm->getSize() * 2), *comm);
  auto loads = allFacesDirichlet(exact);
  // Equilibrium div sigma + b = 0 with div sigma = mu Laplace u = 2 mu c (1,1,1).
  const double b = -2 * mat.lameMu() * c;
  loads.volumeForce = {b, b, b};
  Fem::MonolithicSystem sys(disc, mat, loads, comm);
  const auto res = sys.solve(solverParams("CG+MueLu"));
  const auto D = mat.D();
  double l2 = 0, en = 0;
  const int npc = disc.part.nodesPerCell();
  for (int cell = 0; cell < disc.part.numCells(); ++cell) {
    const auto X = Fem::cellCoordinates(disc.part, cell);
    for (const auto& q : Fem::accurateQuadrature(type)) {
      std::vector<double> dN;
      const double det = Fem::shapeGradients(type, X, q.xi, dN);
      const auto N = Fem::shapeFunctions(type, q.xi);
      Point x{}, uh{};
      double grad[3][3] = {};  // grad[i][j] = d(uh_i - u_i)/dx_j
      for (int a = 0; a < npc; ++a) {
        const double* ua = res.u.at(disc.meshNode(disc.part.cell(cell)[a]));
        for (int i = 0; i < 3; ++i) {
          x[i] += N[a] * X[a][i];
          uh[i] += N[a] * ua[i];
          for (int j = 0; j < 3; ++j) grad[i][j] += dN[3 * a + j] * ua[i];
        }
      }
      const Point u = exact(x);
      grad[0][1] -= 2 * c * x[1];
      grad[1][2] -= 2 * c * x[2];
      grad[2][0] -= 2 * c * x[0];
      const double eps[6] = {grad[0][0], grad[1][1], grad[2][2], grad[1][2] + grad[2][1], grad[0][2] + grad[2][0],
                             grad[0][1] + grad[1][0]};
      double energy = 0;
      for (int r = 0; r < 6; ++r)
        for (int k = 0; k < 6; ++k) energy += eps[r] * D[6 * r + k] * eps[k];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (uh[i] - u[i]) * (uh[i] - u[i]);
      l2 += q.weight * det * d2;
      en += q.weight * det * energy;
    }
  }
  double sums[2] = {l2, en}, total[2];
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 2, sums, total);
  return {std::sqrt(total[0]), std::sqrt(total[1])};
}

void convergenceTest(Mesh::CellType type, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  std::vector<std::pair<double, double>> e;
  for (int n : {2, 4, 8}) e.push_back(manufacturedErrors(type, n, comm));
  for (size_t k = 1; k < e.size(); ++k) {
    const double rL2 = std::log2(e[k - 1].first / e[k].first), rE = std::log2(e[k - 1].second / e[k].second);
    out << Mesh::cellTypeName(type) << " refinement " << k << ": L2 " << e[k].first << " (rate " << rL2
        << "), energy " << e[k].second << " (rate " << rE << ")\n";
    if (k + 1 == e.size()) {
      // L2 rate ~2, energy rate ~1.
      TEST_COMPARE(rL2, >, 1.8);
      TEST_COMPARE(rL2, <, 2.3);
      TEST_COMPARE(rE, >, 0.9);
      TEST_COMPARE(rE, <, 1.3);
    }
  }
}

// K_s R_s = 0 and R_s orthonormal (rank 6) for every subdomain of this rank.
void kernelTest(Mesh::CellType type, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  auto disc = makeDisc(type, {6, 4, 4}, 5, *comm);
  Fem::Material mat{2.1e11, 0.3};
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s) {
    const auto sys = Fem::assembleSubdomain(disc, s, mat, {});
    const int n = sys.numDofs();
    double kmax = 0;
    for (double v : sys.K.val) kmax = std::max(kmax, std::abs(v));
    double worst = 0, orth = 0;
    std::vector<double> KR(n);
    for (int j = 0; j < 6; ++j) {
      sys.K.multiply(&sys.R[j * n], KR.data());
      for (double v : KR) worst = std::max(worst, std::abs(v) / kmax);
      for (int i = 0; i < 6; ++i) {
        double dot = 0;
        for (int k = 0; k < n; ++k) dot += sys.R[i * n + k] * sys.R[j * n + k];
        orth = std::max(orth, std::abs(dot - (i == j ? 1.0 : 0.0)));
      }
    }
    out << "subdomain " << s << ": max |K R| / max |K| = " << worst << ", R'R - I = " << orth << "\n";
    TEST_COMPARE(worst, <, 1e-13);
    TEST_COMPARE(orth, <, 1e-12);  // rank 6
  }
}

// The assembly shared out over the ranks (each computes a block of the
// cells, K summed) gives every rank the K of the serial assembly: the same
// entries to round-off, and the rigid-body kernel.
void sharedAssemblyTest(Mesh::CellType type, Teuchos::FancyOStream& out, bool& success) {
  const auto comm = Tpetra::getDefaultComm();
  Mesh::BoxSpec spec;
  spec.type = type;
  spec.cells = {5, 3, 4};
  const Mesh::Mesh mesh = Mesh::generateBox(spec);
  const Mesh::Subdomain whole = Mesh::extractSubdomains(mesh, std::vector<int>(mesh.numCells(), 0), 1)[0];
  const Fem::Material mat{2.1e11, 0.3};
  const auto serial = Fem::assembleSubdomain(mesh, whole, mat, {});
  const auto shared = Fem::assembleSubdomain(mesh, whole, mat, {}, *comm);
  TEST_ASSERT(shared.K.col == serial.K.col);
  TEST_ASSERT(shared.K.rowptr == serial.K.rowptr);
  double kmax = 0, diff = 0;
  for (size_t k = 0; k < serial.K.val.size(); ++k) {
    kmax = std::max(kmax, std::abs(serial.K.val[k]));
    diff = std::max(diff, std::abs(shared.K.val[k] - serial.K.val[k]));
  }
  out << comm->getSize() << " ranks: max |K_shared - K| / max |K| = " << diff / kmax << "\n";
  TEST_COMPARE(diff, <=, 1e-14 * kmax);
  TEST_COMPARE(kmax, >, 0.0);
}

}  // namespace

TEUCHOS_UNIT_TEST(PatchTest, Tet4Direct) { patchTest(Mesh::CellType::Tet4, "Direct", out, success); }
TEUCHOS_UNIT_TEST(PatchTest, Tet4CGMueLu) { patchTest(Mesh::CellType::Tet4, "CG+MueLu", out, success); }
TEUCHOS_UNIT_TEST(PatchTest, Hex8Direct) { patchTest(Mesh::CellType::Hex8, "Direct", out, success); }
TEUCHOS_UNIT_TEST(PatchTest, Hex8CGMueLu) { patchTest(Mesh::CellType::Hex8, "CG+MueLu", out, success); }

TEUCHOS_UNIT_TEST(Convergence, Tet4) { convergenceTest(Mesh::CellType::Tet4, out, success); }
TEUCHOS_UNIT_TEST(Convergence, Hex8) { convergenceTest(Mesh::CellType::Hex8, out, success); }

TEUCHOS_UNIT_TEST(RigidBodyKernel, Tet4) { kernelTest(Mesh::CellType::Tet4, out, success); }
TEUCHOS_UNIT_TEST(RigidBodyKernel, Hex8) { kernelTest(Mesh::CellType::Hex8, out, success); }
TEUCHOS_UNIT_TEST(SharedAssembly, Tet4) { sharedAssemblyTest(Mesh::CellType::Tet4, out, success); }
TEUCHOS_UNIT_TEST(SharedAssembly, Hex8) { sharedAssemblyTest(Mesh::CellType::Hex8, out, success); }
