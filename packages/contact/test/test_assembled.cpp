// Contact for an application that assembles one Tpetra::FECrsMatrix over
// the ranks (Assembled::ContactProblem, Assembled::ContactSolver), against
// exact solutions:
//  - the contact patch test on a rigid plane: a block with symmetry planes
//    x = 0 and y = 0 pressed by a uniform pressure p on z = 0 (frictionless):
//    u = (nu p x, nu p y, -p z) / E exactly, the traction p at every contact
//    node (the nodes on the symmetry planes among them), no reaction on the
//    symmetry planes (sigma_xx = sigma_yy = 0);
//  - the contact patch test between two bodies: that block on a second one
//    whose mesh does not match it (mortar), the same exact state in both;
//  - a clamped block without contact: the reactions balance the load;
//  - a load history through the reuse path: twice the load gives twice the
//    displacement without building anything again;
//  - refusals naming the object: a matrix summed over the ranks, a facet of
//    a node the rank does not hold, two values for one Dirichlet dof, a load
//    on another map.
// The application's node ids are spread out (2 i + 7) to show that Tribos
// takes any ids; cells are split over the ranks in slabs along x.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_FECrsGraph.hpp>
#include <Tpetra_FECrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "Tribos.hpp"
#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos;
using Test::contains;
using Test::errorOf;
using FEGraph = Tpetra::FECrsGraph<LO, GO, Node>;
using FEMatrix = Tpetra::FECrsMatrix<SC, LO, GO, Node>;

const double kE = 1000.0, kNu = 0.3, kPressure = 2.0;

// A box of Hex8 cells as an application meshes it.
struct Box {
  std::array<double, 3> origin{0, 0, 0}, size{1, 1, 1};
  std::array<int, 3> cells{2, 2, 2};
  GO firstNode = 0;
  GO id(int i, int j, int k) const { return firstNode + 2 * (i + (cells[0] + 1) * (j + (cells[1] + 1) * GO(k))) + 7; }
  Fem::Point x(int i, int j, int k) const {
    return {origin[0] + size[0] * i / cells[0], origin[1] + size[1] * j / cells[1], origin[2] + size[2] * k / cells[2]};
  }
  // The rank of the cells in slab ix.
  int rankOfSlab(int ix, int ranks) const { return static_cast<int>((static_cast<long>(ix) * ranks) / cells[0]); }
};

// The application: its boxes assembled into one FECrsMatrix.
struct App {
  std::vector<Box> boxes;
  RCP<const Comm> comm = Tpetra::getDefaultComm();
  RCP<const Map> owned, overlap, overlapNodes;
  RCP<FEGraph> graph;
  RCP<FEMatrix> K;
  RCP<MultiVector> coords;
  std::map<GO, Fem::Point> position;  // this rank's nodes

  // Every cell of this rank: (box, i, j, k).
  template <class F>
  void forMyCells(F&& f) const {
    for (size_t b = 0; b < boxes.size(); ++b) {
      const Box& B = boxes[b];
      for (int i = 0; i < B.cells[0]; ++i) {
        if (B.rankOfSlab(i, comm->getSize()) != comm->getRank()) continue;
        for (int j = 0; j < B.cells[1]; ++j)
          for (int k = 0; k < B.cells[2]; ++k) f(B, i, j, k);
      }
    }
  }
  static std::vector<GO> cellNodes(const Box& B, int i, int j, int k) {
    return {B.id(i, j, k),         B.id(i + 1, j, k),         B.id(i + 1, j + 1, k),     B.id(i, j + 1, k),
            B.id(i, j, k + 1),     B.id(i + 1, j, k + 1),     B.id(i + 1, j + 1, k + 1), B.id(i, j + 1, k + 1)};
  }
  static std::vector<Fem::Point> cellPoints(const Box& B, int i, int j, int k) {
    return {B.x(i, j, k),     B.x(i + 1, j, k),     B.x(i + 1, j + 1, k),     B.x(i, j + 1, k),
            B.x(i, j, k + 1), B.x(i + 1, j, k + 1), B.x(i + 1, j + 1, k + 1), B.x(i, j + 1, k + 1)};
  }
  RCP<const Map> dofMap(const std::vector<GO>& nodes) const {
    std::vector<GO> dofs;
    for (GO n : nodes)
      for (int c = 0; c < 3; ++c) dofs.push_back(3 * n + c);
    return rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), Teuchos::ArrayView<const GO>(dofs), 0,
                       comm));
  }

  // Maps (a node is owned by the lowest rank whose cells touch it), the
  // graph and K, left open for assembly as Tribos takes it.
  void assemble(bool closeAssembly = false) {
    std::set<GO> mine, ownedNodes;
    for (const Box& B : boxes)
      for (int i = 0; i <= B.cells[0]; ++i) {
        const int lowest = B.rankOfSlab(std::max(i - 1, 0), comm->getSize());
        const int highest = B.rankOfSlab(std::min(i, B.cells[0] - 1), comm->getSize());
        if (comm->getRank() < lowest || comm->getRank() > highest) continue;
        for (int j = 0; j <= B.cells[1]; ++j)
          for (int k = 0; k <= B.cells[2]; ++k) {
            mine.insert(B.id(i, j, k));
            position[B.id(i, j, k)] = B.x(i, j, k);
            if (lowest == comm->getRank()) ownedNodes.insert(B.id(i, j, k));
          }
      }
    // Tpetra's FECrsGraph takes the owned rows first in its owned+shared map.
    const std::vector<GO> own(ownedNodes.begin(), ownedNodes.end());
    std::vector<GO> all = own;
    for (GO n : mine)
      if (!ownedNodes.count(n)) all.push_back(n);
    owned = dofMap(own);
    overlap = dofMap(all);
    overlapNodes = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                               Teuchos::ArrayView<const GO>(all), 0, comm));
    coords = rcp(new MultiVector(overlapNodes, 3));
    for (size_t a = 0; a < all.size(); ++a)
      for (int d = 0; d < 3; ++d) coords->replaceLocalValue(static_cast<LO>(a), d, position[all[a]][d]);
    graph = rcp(new FEGraph(owned, overlap, 81));
    graph->beginAssembly();
    forMyCells([&](const Box& B, int i, int j, int k) {
      std::vector<GO> dofs;
      for (GO n : cellNodes(B, i, j, k))
        for (int c = 0; c < 3; ++c) dofs.push_back(3 * n + c);
      for (GO r : dofs) graph->insertGlobalIndices(r, Teuchos::ArrayView<const GO>(dofs));
    });
    graph->endAssembly();
    K = rcp(new FEMatrix(graph));
    Fem::Material mat;
    mat.E = E_, mat.nu = kNu;
    K->beginAssembly();
    forMyCells([&](const Box& B, int i, int j, int k) {
      const auto Ke = Fem::elementStiffness(Mesh::CellType::Hex8, cellPoints(B, i, j, k), mat);
      std::vector<GO> dofs;
      for (GO n : cellNodes(B, i, j, k))
        for (int c = 0; c < 3; ++c) dofs.push_back(3 * n + c);
      for (int r = 0; r < 24; ++r)
        K->sumIntoGlobalValues(dofs[r], Teuchos::ArrayView<const GO>(dofs),
                               Teuchos::ArrayView<const double>(&Ke[24 * r], 24));
    });
    if (closeAssembly) K->endAssembly();
  }

  // The rank's cells as element matrices (instead of K).
  Assembled::ElementMatrices elementMatrices(int subdomainSize) const {
    Assembled::ElementMatrices E;
    E.nodesPerElement = 8;
    E.subdomainSize = subdomainSize;
    Fem::Material mat;
    mat.E = E_, mat.nu = kNu;
    forMyCells([&](const Box& B, int i, int j, int k) {
      const auto nodes = cellNodes(B, i, j, k);
      E.nodes.insert(E.nodes.end(), nodes.begin(), nodes.end());
      const auto Ke = Fem::elementStiffness(Mesh::CellType::Hex8, cellPoints(B, i, j, k), mat);
      E.values.insert(E.values.end(), Ke.begin(), Ke.end());
    });
    return E;
  }
  double E_ = kE;

  // The facets of this rank's cells on face (axis, side) of box b, outward
  // (counter-clockwise seen from outside).
  Assembled::Surface face(const Box& B, int axis, int side) const {
    Assembled::Surface s;
    s.nodesPerFacet = 4;
    forMyCells([&](const Box& C, int i, int j, int k) {
      if (&C != &B) return;
      const int ijk[3] = {i, j, k};
      if (ijk[axis] != (side == 0 ? 0 : B.cells[axis] - 1)) return;
      const auto n = cellNodes(B, i, j, k);
      // Hex8 faces of the cell, outward.
      static const int faces[3][2][4] = {{{0, 4, 7, 3}, {1, 2, 6, 5}}, {{0, 1, 5, 4}, {3, 7, 6, 2}},
                                         {{0, 3, 2, 1}, {4, 5, 6, 7}}};
      for (int a = 0; a < 4; ++a) s.nodes.push_back(n[faces[axis][side][a]]);
    });
    return s;
  }
  // The pressure p on the top of box b as the rank's elements' nodal forces
  // (on K's row map: Tribos sums them over the ranks).
  RCP<Vector> topPressure(const Box& B, double p) const {
    auto f = rcp(new Vector(overlap));
    const auto top = face(B, 2, 1);
    for (size_t k = 0; k < top.nodes.size(); ++k) {
      const double area = B.size[0] / B.cells[0] * B.size[1] / B.cells[1];
      f->sumIntoGlobalValue(3 * top.nodes[k] + 2, -p * area / 4);
    }
    return f;
  }
  // u_c = 0 on the nodes of this rank with x_c = value (a plane of box b).
  std::vector<std::pair<GO, double>> plane(const Box& B, int c, double value, int components = -1) const {
    std::vector<std::pair<GO, double>> out;
    for (const auto& [id, x] : position) {
      if (std::abs(x[c] - value) > 1e-12) continue;
      if (id < B.firstNode || id >= B.firstNode + 100000) continue;
      if (components < 0) out.push_back({3 * id + c, 0.0});
      else
        for (int d = 0; d < 3; ++d) out.push_back({3 * id + d, 0.0});
    }
    return out;
  }
};

RCP<Teuchos::ParameterList> tightParameters() {
  auto p = Teuchos::parameterList("Tribos");
  p->sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-11);
  p->sublist("Algorithm 2").set("Relative Tolerance", 1e-11);
  p->sublist("FETI").sublist("Projected CG").set("Tolerance", 1e-12);
  return p;
}

// max over the owned dofs of |u - exact| / max |exact|, on every rank.
double exactError(const App& app, const Vector& u, double scale) {
  const auto v = u.getData();
  double worst = 0;
  for (size_t l = 0; l < app.owned->getNodeNumElements(); ++l) {
    const GO dof = app.owned->getGlobalElement(static_cast<LO>(l));
    const Fem::Point& x = app.position.at(dof / 3);
    const double exact[3] = {kNu * kPressure * x[0] / kE, kNu * kPressure * x[1] / kE, -kPressure * x[2] / kE};
    worst = std::max(worst, std::abs(v[l] - exact[dof % 3]) / scale);
  }
  double all = 0;
  Teuchos::reduceAll(*app.comm, Teuchos::REDUCE_MAX, worst, Teuchos::outArg(all));
  return all;
}

TEUCHOS_UNIT_TEST(Assembled, PatchTestOnRigidPlane) {
  App app;
  Box B;
  B.size = {2, 1, 1};
  B.cells = {6, 2, 3};
  app.boxes = {B};
  app.assemble();
  Assembled::ContactProblem problem(app.K, app.owned, app.coords);
  problem.setLoad(app.topPressure(app.boxes[0], kPressure));
  auto fixed = app.plane(app.boxes[0], 0, 0.0);
  const auto fy = app.plane(app.boxes[0], 1, 0.0);
  fixed.insert(fixed.end(), fy.begin(), fy.end());
  problem.setDirichlet(fixed);
  Assembled::ContactPair pair;
  pair.name = "bottom";
  pair.slave = app.face(app.boxes[0], 2, 0);
  pair.planePoint = {0, 0, 0};
  pair.planeNormal = {0, 0, 1};
  const int k = problem.addContactPair(pair);
  TEST_EQUALITY(k, 0);
  Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  const double scale = kPressure * 1.0 / kE;
  TEST_COMPARE(exactError(app, *solver.getDisplacement(), scale), <, 1e-8);
  // The traction p at every slave node, the symmetry planes free of
  // reactions (sigma_xx = sigma_yy = 0).
  const auto state = solver.getContactState();
  const auto traction = state->getData(Assembled::NormalTraction), status = state->getData(Assembled::Status);
  int contactNodes = 0;
  for (size_t l = 0; l < state->getLocalLength(); ++l) {
    if (status[l] < 0) continue;
    ++contactNodes;
    TEST_FLOATING_EQUALITY(traction[l], kPressure, 1e-8);
    TEST_ASSERT(status[l] > 0);
  }
  int all = 0;
  Teuchos::reduceAll(*app.comm, Teuchos::REDUCE_SUM, contactNodes, Teuchos::outArg(all));
  TEST_EQUALITY(all, 7 * 3);
  TEST_COMPARE(solver.getReaction()->normInf(), <, 1e-8 * kPressure);
  TEST_EQUALITY(solver.getSummary().step, 1);
  TEST_ASSERT(solver.getSummary().rebuilt);

  // Twice the load, through the reuse path: twice the displacement, and
  // nothing built again.
  problem.setLoad(app.topPressure(app.boxes[0], 2 * kPressure));
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  TEST_ASSERT(!solver.getSummary().rebuilt);
  TEST_EQUALITY(solver.getSummary().step, 2);
  Vector half(*solver.getDisplacement(), Teuchos::Copy);
  half.scale(0.5);
  TEST_COMPARE(exactError(app, half, scale), <, 1e-8);
  // The slip of the step is half the slip (frictionless, the load doubled).
  {
    const auto twice = solver.getContactState();
    const auto st = twice->getData(Assembled::Status);
    for (int d = 0; d < 3; ++d) {
      const auto slip = twice->getData(Assembled::SlipX + d), step = twice->getData(Assembled::SlipIncrementX + d);
      for (size_t l = 0; l < twice->getLocalLength(); ++l)
        if (st[l] >= 0) TEST_COMPARE(std::abs(step[l] - 0.5 * slip[l]), <=, 1e-8 * scale);
    }
  }

  // A stiffer material (a new K of the same pattern) in the middle of the
  // history: a numeric refactorization, the history goes on.
  App stiffer;
  stiffer.boxes = app.boxes;
  stiffer.E_ = 2 * kE;
  stiffer.assemble();
  problem.setStiffness(stiffer.K);
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  TEST_ASSERT(!solver.getSummary().rebuilt);
  TEST_ASSERT(solver.getSummary().refactored);
  TEST_EQUALITY(solver.getSummary().step, 3);
  TEST_COMPARE(exactError(app, *solver.getDisplacement(), scale), <, 1e-8);
}

// Two blocks of non-matching meshes, the upper one on the lower one, the
// lower one on the rigid plane z = 0, symmetry planes x = 0 and y = 0 in
// both, the pressure p on the top: the uniform state of exactError in both.
App twoBlocks(std::array<int, 3> lowerCells, std::array<int, 3> upperCells) {
  App app;
  Box lower, upper;
  lower.size = {1, 1, 0.5};
  lower.cells = lowerCells;
  upper.origin = {0, 0, 0.5};
  upper.size = {1, 1, 0.5};
  upper.cells = upperCells;
  upper.firstNode = 100000;
  app.boxes = {lower, upper};
  app.assemble();
  return app;
}

void stateTwoBlocks(const App& app, Assembled::ContactProblem& problem, Teuchos::FancyOStream& out, bool& success) {
  problem.setLoad(app.topPressure(app.boxes[1], kPressure));
  std::vector<std::pair<GO, double>> fixed;
  for (const Box& b : app.boxes)
    for (int c = 0; c < 2; ++c) {
      const auto p = app.plane(b, c, 0.0);
      fixed.insert(fixed.end(), p.begin(), p.end());
    }
  problem.setDirichlet(fixed);
  Assembled::ContactPair ground;
  ground.name = "ground";
  ground.slave = app.face(app.boxes[0], 2, 0);
  problem.addContactPair(ground);
  Assembled::ContactPair interface;
  interface.name = "interface";
  interface.slave = app.face(app.boxes[1], 2, 0);  // the coarser side
  interface.master = app.face(app.boxes[0], 2, 1);
  interface.discretization = Contact::ContactDiscretization::Mortar;
  const int k = problem.addContactPair(interface);
  TEST_EQUALITY(k, 1);
}

// The uniform state of p / E = kPressure / kE, and the traction p at every
// slave node.
void requireUniformState(const App& app, const Assembled::ContactSolver& solver, double p, Teuchos::FancyOStream& out,
                         bool& success) {
  TEST_COMPARE(exactError(app, *solver.getDisplacement(), kPressure / kE), <, 1e-8);
  const auto state = solver.getContactState();
  const auto traction = state->getData(Assembled::NormalTraction), status = state->getData(Assembled::Status);
  for (size_t l = 0; l < state->getLocalLength(); ++l)
    if (status[l] >= 0) TEST_FLOATING_EQUALITY(traction[l], p, 1e-8);
}

TEUCHOS_UNIT_TEST(Assembled, MortarPatchTestBetweenTwoBodies) {
  const App app = twoBlocks({3, 3, 2}, {2, 2, 2});
  Assembled::ContactProblem problem(app.K, app.owned, app.coords);
  stateTwoBlocks(app, problem, out, success);
  Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  requireUniformState(app, solver, kPressure, out, success);
  TEST_COMPARE(solver.getSummary().subdomains, >=, 2);
}

// The element path: the rank's cells as element matrices, split by METIS
// into subdomains of about 8 nodes (several per rank): the mortar patch
// test again, and a stiffer material as new element matrices of the same
// pattern (a numeric refactorization).
TEUCHOS_UNIT_TEST(Assembled, ElementMatricesSplitIntoSubdomains) {
  const App app = twoBlocks({4, 3, 2}, {3, 2, 2});
  Assembled::ContactProblem problem(app.elementMatrices(1), app.owned, app.coords);
  stateTwoBlocks(app, problem, out, success);
  Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  requireUniformState(app, solver, kPressure, out, success);
  TEST_COMPARE(solver.getSummary().subdomains, >=, 4 * app.comm->getSize());

  App stiffer;
  stiffer.boxes = app.boxes;
  stiffer.E_ = 2 * kE;
  problem.setElementMatrices(stiffer.elementMatrices(1));
  problem.setLoad(app.topPressure(app.boxes[1], 2 * kPressure));
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  TEST_ASSERT(solver.getSummary().refactored);
  TEST_ASSERT(!solver.getSummary().rebuilt);
  requireUniformState(app, solver, 2 * kPressure, out, success);
}

// "Friction"/"Pair 0" alone: pair 1 takes the list's own friction. Two
// blocks on the plane z = 0 (pair 0: Coefficient 0.2 by its sublist; pair
// 1: the list's 0.4), pressed by p and dragged along x by their top faces
// (u_x = delta there) until the whole bottom slips: at every slipping node
// the tangential traction is the pair's coefficient times the normal one.
TEUCHOS_UNIT_TEST(Assembled, PairSublistLeavesOtherPairsTheListsFriction) {
  App app;
  Box A, B;
  A.cells = B.cells = {2, 2, 2};
  B.origin = {3, 0, 0};
  B.firstNode = 100000;
  app.boxes = {A, B};
  app.assemble();
  Assembled::ContactProblem problem(app.K, app.owned, app.coords);
  auto f = app.topPressure(app.boxes[0], kPressure);
  f->update(1.0, *app.topPressure(app.boxes[1], kPressure), 1.0);
  problem.setLoad(f);
  const double delta = 0.05;
  std::vector<std::pair<GO, double>> fixed;
  for (const Box& b : app.boxes) {
    for (const auto& [dof, value] : app.plane(b, 2, 1.0)) fixed.push_back({dof - 2, delta});  // u_x on the top
    const auto y = app.plane(b, 1, 0.0);
    fixed.insert(fixed.end(), y.begin(), y.end());
    Assembled::ContactPair bottom;
    bottom.slave = app.face(b, 2, 0);
    problem.addContactPair(bottom);
  }
  problem.setDirichlet(fixed);
  auto p = tightParameters();
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", 0.4);
  p->sublist("Friction").sublist("Pair 0").set("Coefficient", 0.2);
  Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), p);
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  const auto state = solver.getContactState();
  const auto n = state->getData(Assembled::NormalTraction), st = state->getData(Assembled::Status);
  int slipping[2] = {0, 0}, all[2];
  for (size_t l = 0; l < state->getLocalLength(); ++l) {
    if (st[l] != 2 || n[l] <= 0) continue;
    const int pair = state->getMap()->getGlobalElement(static_cast<LO>(l)) >= 100000 ? 1 : 0;
    double t = 0;
    for (int d = 0; d < 3; ++d) t += std::pow(state->getData(Assembled::TangentialTractionX + d)[l], 2);
    TEST_FLOATING_EQUALITY(std::sqrt(t) / n[l], pair == 0 ? 0.2 : 0.4, 1e-6);
    ++slipping[pair];
  }
  Teuchos::reduceAll(*app.comm, Teuchos::REDUCE_SUM, 2, slipping, all);
  TEST_EQUALITY(all[0], 9);
  TEST_COMPARE(all[1], >=, 3);  // the larger coefficient holds some nodes
}

TEUCHOS_UNIT_TEST(Assembled, ReactionsBalanceTheLoad) {
  App app;
  Box B;
  B.size = {1, 2, 1};
  B.cells = {3, 2, 2};
  app.boxes = {B};
  app.assemble();
  Assembled::ContactProblem problem(app.K, app.owned, app.coords);
  problem.setLoad(app.topPressure(app.boxes[0], kPressure));
  problem.setDirichlet(app.plane(app.boxes[0], 2, 0.0, 3));  // clamped bottom
  Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
  TEST_ASSERT(solver.solve() == Contact::SolveStatus::Converged);
  // The support pushes up with the whole load p A, and nothing sideways.
  const auto r = solver.getReaction()->getData();
  double sum[3] = {0, 0, 0}, all[3];
  for (size_t l = 0; l < app.owned->getNodeNumElements(); ++l) sum[app.owned->getGlobalElement(l) % 3] += r[l];
  Teuchos::reduceAll(*app.comm, Teuchos::REDUCE_SUM, 3, sum, all);
  TEST_FLOATING_EQUALITY(all[2], kPressure * 2.0, 1e-9);
  TEST_COMPARE(std::abs(all[0]) + std::abs(all[1]), <, 1e-9 * kPressure);
}

TEUCHOS_UNIT_TEST(Assembled, Refusals) {
  App app;
  Box B;
  B.cells = {3, 1, 1};
  app.boxes = {B};
  auto solveError = [&](Assembled::ContactProblem& problem) {
    Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
    return errorOf([&] { solver.solve(); });
  };
  if (app.comm->getSize() > 1) {
    App closed;
    closed.boxes = {B};
    closed.assemble(true);
    Assembled::ContactProblem problem(closed.K, closed.owned, closed.coords);
    problem.setDirichlet(closed.plane(closed.boxes[0], 2, 0.0, 3));
    TEST_ASSERT(contains(solveError(problem), "summed over the ranks"));
  }
  app.assemble();
  const auto clamp = app.plane(app.boxes[0], 2, 0.0, 3);
  {
    Assembled::ContactProblem problem(app.K, app.owned, app.coords);
    auto twice = clamp;
    if (app.comm->getRank() == 0) twice.push_back({twice.front().first, 1.0});
    problem.setDirichlet(twice);
    TEST_ASSERT(contains(solveError(problem), "two Dirichlet values"));
  }
  {
    Assembled::ContactProblem problem(app.K, app.owned, app.coords);
    problem.setDirichlet(clamp);
    Assembled::ContactPair pair;
    pair.slave = app.face(app.boxes[0], 2, 0);
    if (app.comm->getRank() == 0) pair.slave.nodes.front() = 5;  // no node of the mesh
    problem.addContactPair(pair);
    TEST_ASSERT(contains(solveError(problem), "names node 5"));
  }
  {
    // Nothing holds the body: refused, naming the free motions.
    Assembled::ContactProblem problem(app.K, app.owned, app.coords);
    problem.setLoad(app.topPressure(app.boxes[0], kPressure));
    Assembled::ContactSolver solver(Teuchos::rcpFromRef(problem), tightParameters());
    const std::string error = errorOf([&] {
      if (solver.solve() != Contact::SolveStatus::Converged) throw Error(solver.getSummary().reason);
    });
    out << error << "\n";
    TEST_ASSERT(contains(error, "translation") || contains(error, "rigid"));
  }
  {
    // A choice this path cannot take is refused when the list is set.
    auto p = tightParameters();
    p->sublist("FETI").set("Formulation", "FETI-1");
    Assembled::ContactSolver solver;
    TEST_ASSERT(contains(errorOf([&] { solver.setParameterList(p); }), "TFETI"));
    // An outer algorithm that does not solve the pairs' law: refused once
    // both the list and a problem with pairs are set.
    Assembled::ContactProblem problem(app.K, app.owned, app.coords);
    Assembled::ContactPair pair;
    pair.slave = app.face(app.boxes[0], 2, 0);
    problem.addContactPair(pair);
    auto coulomb = tightParameters();
    coulomb->set("Outer Algorithm", "Algorithm1");
    coulomb->sublist("Friction").set("Law", "Coulomb").set("Coefficient", 0.3);
    solver.setParameterList(coulomb);
    TEST_ASSERT(contains(errorOf([&] { solver.setProblem(Teuchos::rcpFromRef(problem)); }), "does not solve Coulomb"));
  }
  {
    Assembled::ContactProblem problem(app.K, app.owned, app.coords);
    problem.setDirichlet(clamp);
    problem.setLoad(rcp(new Vector(app.overlapNodes)));
    TEST_ASSERT(contains(solveError(problem), "neither ownedMap nor K's row map"));
  }
}

}  // namespace
