// assembled: a Trilinos finite element application with a mesh and an
// assembly of its own. It meshes two bodies, assembles their stiffness the Tpetra way (one
// Tpetra::FECrsGraph and FECrsMatrix over the ranks, cells split in slabs
// along x) and solves their frictional contact through Tribos' assembled
// API (Tribos::Assembled::ContactProblem and ContactSolver, #include
// <Tribos.hpp>), in a short load history on the reuse path.
//
// The problem (SI units, a half model about the plane y = 0):
//   lower block  [0, 2] x [0, 1] x [0, 1], steel (E = 210 GPa, nu = 0.3),
//                8m x 4m x 4m Hex8 cells;
//   upper block  [0.5, 1.5] x [0, 0.75] x [1, 1.6], aluminium (E = 70 GPa,
//                nu = 0.33), 3m x 2m x 2m Hex8 cells: its bottom lies on the
//                lower block's top, the meshes do not match there;
//   symmetry     u_y = 0 on y = 0 of both blocks;
//   Dirichlet    u_x = 0 on the lower block's face x = 0 (a wall);
//   contact      pair 0 "interface": the upper block's bottom (slave) on the
//                lower block's top (master), mortar, Coulomb F = 0.3; pair 1
//                "ground": the lower block's bottom on the rigid plane z = 0,
//                Coulomb F = 0.5 ("Friction"/"Pair 1");
//   loads        on the upper block's top, at the step times t = 1, 2, 3, 4:
//                the pressure p = 1e8 Pa ramped to t = 1 and held (min(t, 1)),
//                and the tangential traction q = 2e7 Pa along x times the
//                curve through (0, 0), (1, 0), (2, 0.5), (3, 1), (4, -1):
//                pressed, sheared out in two steps, then reversed.
// The upper block is held along x by friction alone. Each step is
// problem.setLoad(...) then solver.solve(): the factors of the first step
// serve every step, and friction acts on the slip since the previous step.
//
// Every step must converge with every KKT residual of its result within the
// summary's limit, and the results must balance the load (the ground's
// normal forces from getContactState() carry the pressure; the wall's
// reactions from getReaction() and the ground's friction hold the shear),
// to 1e-6 of the load; exit 1 otherwise. One line per step is printed. Rank 0
// writes, in the output directory (--out, default assembled_output):
//   assembled.msh              the mesh as Gmsh 4.1 ASCII: physical volumes
//                              "lower" and "upper", physical surfaces
//                              lower_bottom, lower_top, lower_wall,
//                              upper_bottom, upper_top, symmetry_y; node
//                              tags are the application's node ids;
//   assembled.xml              the same problem as an input of the tribos
//                              driver (bodies, materials, loads as a load
//                              history with its curve, Dirichlet and
//                              symmetry conditions, contact pairs, friction,
//                              the solver's tolerance);
//   assembled.stepNNNN.csv     per step: node id, x, y, z, ux, uy, uz of
//                              every node (gathered on rank 0);
//   assembled.steps.csv        per step: what the summary reports, with the
//                              setup and solve seconds.
//
//   mpirun -np 2 assembled [--size m] [--out DIR] [--tolerance t] [--timings] [--no-fields]
//
// --size m refines both blocks m times (default 1), --tolerance sets
// Algorithm 2's relative tolerance (default 1e-10), --timings prints the
// assembly, setup and solve seconds, --no-fields skips the per-step CSV
// files of the displacement (large meshes).
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_FECrsGraph.hpp>
#include <Tpetra_FECrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <Tribos.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

using namespace Tribos;

namespace {

using FEGraph = Tpetra::FECrsGraph<LO, GO, Node>;
using FEMatrix = Tpetra::FECrsMatrix<SC, LO, GO, Node>;

// ---------------------------------------------------------------------------
// The model

// A block of Hex8 cells; node (i, j, k) has the id firstId + i + (nx + 1)
// (j + (ny + 1) k).
struct Block {
  std::string name;
  std::array<double, 3> origin{0, 0, 0}, size{1, 1, 1};
  std::array<int, 3> cells{1, 1, 1};
  GO firstId = 1;
  Fem::Material material;
  GO id(int i, int j, int k) const { return firstId + i + (cells[0] + 1) * (j + GO(cells[1] + 1) * k); }
  GO numNodes() const { return GO(cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1); }
  long numCells() const { return long(cells[0]) * cells[1] * cells[2]; }
  Fem::Point x(int i, int j, int k) const {
    return {origin[0] + size[0] * i / cells[0], origin[1] + size[1] * j / cells[1], origin[2] + size[2] * k / cells[2]};
  }
  // The rank whose cells are those of slab i (along x).
  int rankOfSlab(int i, int ranks) const { return static_cast<int>((long(i) * ranks) / cells[0]); }
  // The 8 corners of cell (i, j, k) in Hex8 order (Tribos' and Gmsh's).
  std::array<std::array<int, 3>, 8> corners(int i, int j, int k) const {
    return {{{i, j, k}, {i + 1, j, k}, {i + 1, j + 1, k}, {i, j + 1, k},
             {i, j, k + 1}, {i + 1, j, k + 1}, {i + 1, j + 1, k + 1}, {i, j + 1, k + 1}}};
  }
};

// A face of a block: the cells' sides on its first (side 0) or last (side
// 1) plane across the axis.
struct Face {
  int block, axis, side;
};

// The corners of a cell's side on (axis, side), counter-clockwise seen from
// outside the cell.
const int kSide[3][2][4] = {{{0, 4, 7, 3}, {1, 2, 6, 5}}, {{0, 1, 5, 4}, {3, 7, 6, 2}}, {{0, 3, 2, 1}, {4, 5, 6, 7}}};

// A piecewise-linear load curve, as the driver's Load Curves.
struct Curve {
  std::vector<double> times, values;
  double operator()(double t) const {
    for (size_t a = 0; a + 1 < times.size(); ++a)
      if (t <= times[a + 1]) {
        const double s = (t - times[a]) / (times[a + 1] - times[a]);
        return values[a] + s * (values[a + 1] - values[a]);
      }
    return values.back();
  }
};

struct Model {
  std::vector<Block> blocks;  // 0: lower, 1: upper
  double pressure = 1e8, shear = 2e7;
  double frictionInterface = 0.3, frictionGround = 0.5;
  std::vector<double> stepTimes{1, 2, 3, 4};
  Curve shearCurve{{0, 1, 2, 3, 4}, {0, 0, 0.5, 1, -1}};
  double tolerance = 1e-10;
  // Named faces (the physical surfaces of the mesh file).
  std::vector<std::pair<std::string, std::vector<Face>>> faces;

  explicit Model(int m) {
    Block lower, upper;
    lower.name = "lower";
    lower.size = {2, 1, 1};
    lower.cells = {8 * m, 4 * m, 4 * m};
    lower.firstId = 1;
    lower.material.E = 210e9;
    lower.material.nu = 0.3;
    upper.name = "upper";
    upper.origin = {0.5, 0, 1};
    upper.size = {1, 0.75, 0.6};
    upper.cells = {3 * m, 2 * m, 2 * m};
    upper.firstId = lower.firstId + lower.numNodes();
    upper.material.E = 70e9;
    upper.material.nu = 0.33;
    blocks = {lower, upper};
    faces = {{"lower_bottom", {{0, 2, 0}}}, {"lower_top", {{0, 2, 1}}},   {"lower_wall", {{0, 0, 0}}},
             {"upper_bottom", {{1, 2, 0}}}, {"upper_top", {{1, 2, 1}}},   {"symmetry_y", {{0, 1, 0}, {1, 1, 0}}}};
  }
  // The loads at time t: the pressure ramped, the shear on its curve.
  double pressureAt(double t) const { return pressure * std::min(t, 1.0); }
  double shearAt(double t) const { return shear * shearCurve(t); }

  // Calls f(block, i, j, k) for every cell of block b that rank holds (rank
  // < 0: every cell).
  template <class F>
  void forCells(int b, int rank, int ranks, F&& f) const {
    const Block& B = blocks[b];
    for (int i = 0; i < B.cells[0]; ++i) {
      if (rank >= 0 && B.rankOfSlab(i, ranks) != rank) continue;
      for (int j = 0; j < B.cells[1]; ++j)
        for (int k = 0; k < B.cells[2]; ++k) f(B, i, j, k);
    }
  }
  // Calls f(block, corners[4]) for every cell side on face F of the cells
  // rank holds (rank < 0: all), outward.
  template <class G>
  void forSides(const Face& F, int rank, int ranks, G&& g) const {
    forCells(F.block, rank, ranks, [&](const Block& B, int i, int j, int k) {
      const int ijk[3] = {i, j, k};
      if (ijk[F.axis] != (F.side == 0 ? 0 : B.cells[F.axis] - 1)) return;
      const auto c = B.corners(i, j, k);
      std::array<std::array<int, 3>, 4> side;
      for (int a = 0; a < 4; ++a) side[a] = c[kSide[F.axis][F.side][a]];
      g(B, side);
    });
  }
};

// ---------------------------------------------------------------------------
// The application's assembly: one FECrsMatrix over the ranks

struct Assembly {
  RCP<const Comm> comm;
  RCP<const Map> owned, overlap, overlapNodes;
  RCP<FEGraph> graph;
  RCP<FEMatrix> K;
  RCP<MultiVector> coordinates;
  std::vector<GO> ownedNodes;                  // ascending
  std::map<GO, Fem::Point> position;           // the nodes this rank holds
  std::vector<std::pair<GO, double>> dirichlet;
  double seconds = 0;
};

RCP<const Map> dofMap(const std::vector<GO>& nodes, const RCP<const Comm>& comm) {
  std::vector<GO> dofs;
  dofs.reserve(3 * nodes.size());
  for (GO n : nodes)
    for (int c = 0; c < 3; ++c) dofs.push_back(3 * n + c);
  return rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), Teuchos::ArrayView<const GO>(dofs), 0,
                     comm));
}

Assembly assemble(const Model& model, const RCP<const Comm>& comm) {
  Assembly a;
  a.comm = comm;
  const double t0 = MPI_Wtime();
  const int rank = comm->getRank(), ranks = comm->getSize();
  // The nodes of this rank's cells; each is owned by the lowest rank whose
  // cells touch it.
  std::set<GO> held, ownedSet;
  for (size_t b = 0; b < model.blocks.size(); ++b) {
    const Block& B = model.blocks[b];
    for (int i = 0; i <= B.cells[0]; ++i) {
      const int lowest = B.rankOfSlab(std::max(i - 1, 0), ranks);
      const int highest = B.rankOfSlab(std::min(i, B.cells[0] - 1), ranks);
      if (rank != lowest && rank != highest) continue;
      for (int j = 0; j <= B.cells[1]; ++j)
        for (int k = 0; k <= B.cells[2]; ++k) {
          const GO id = B.id(i, j, k);
          held.insert(id);
          a.position[id] = B.x(i, j, k);
          if (rank == lowest) ownedSet.insert(id);
          // The symmetry plane y = 0 of both blocks, the wall x = 0 of the lower one.
          if (j == 0) a.dirichlet.push_back({3 * id + 1, 0.0});
          if (b == 0 && i == 0) a.dirichlet.push_back({3 * id + 0, 0.0});
        }
    }
  }
  // Tpetra's FECrsGraph takes the owned rows first in its owned+shared map.
  a.ownedNodes.assign(ownedSet.begin(), ownedSet.end());
  std::vector<GO> all = a.ownedNodes;
  for (GO n : held)
    if (!ownedSet.count(n)) all.push_back(n);
  a.owned = dofMap(a.ownedNodes, comm);
  a.overlap = dofMap(all, comm);
  a.overlapNodes = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                               Teuchos::ArrayView<const GO>(all), 0, comm));
  a.coordinates = rcp(new MultiVector(a.overlapNodes, 3));
  for (size_t l = 0; l < all.size(); ++l)
    for (int d = 0; d < 3; ++d) a.coordinates->replaceLocalValue(static_cast<LO>(l), d, a.position[all[l]][d]);

  auto cellDofs = [](const Block& B, int i, int j, int k) {
    std::array<GO, 24> dofs;
    const auto c = B.corners(i, j, k);
    for (int n = 0; n < 8; ++n)
      for (int d = 0; d < 3; ++d) dofs[3 * n + d] = 3 * B.id(c[n][0], c[n][1], c[n][2]) + d;
    return dofs;
  };
  a.graph = rcp(new FEGraph(a.owned, a.overlap, 81));
  a.graph->beginAssembly();
  for (size_t b = 0; b < model.blocks.size(); ++b)
    model.forCells(static_cast<int>(b), rank, ranks, [&](const Block& B, int i, int j, int k) {
      const auto dofs = cellDofs(B, i, j, k);
      for (GO r : dofs) a.graph->insertGlobalIndices(r, Teuchos::ArrayView<const GO>(dofs.data(), 24));
    });
  a.graph->endAssembly();
  // K is left between beginAssembly() and endAssembly(): each rank's rows
  // hold the sums of its own elements' matrices, which is what Tribos takes.
  a.K = rcp(new FEMatrix(a.graph));
  a.K->beginAssembly();
  for (size_t b = 0; b < model.blocks.size(); ++b)
    model.forCells(static_cast<int>(b), rank, ranks, [&](const Block& B, int i, int j, int k) {
      const auto c = B.corners(i, j, k);
      std::vector<Fem::Point> X(8);
      for (int n = 0; n < 8; ++n) X[n] = B.x(c[n][0], c[n][1], c[n][2]);
      const auto Ke = Fem::elementStiffness(Mesh::CellType::Hex8, X, B.material);
      const auto dofs = cellDofs(B, i, j, k);
      for (int r = 0; r < 24; ++r)
        a.K->sumIntoGlobalValues(dofs[r], Teuchos::ArrayView<const GO>(dofs.data(), 24),
                                 Teuchos::ArrayView<const SC>(&Ke[24 * r], 24));
    });
  double seconds = MPI_Wtime() - t0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &seconds, &a.seconds);
  return a;
}

// The load at time t: the traction (q(t), 0, -p(t)) on the upper block's top
// as consistent nodal forces of this rank's cell sides, on K's row map
// (Tribos sums the ranks' contributions).
RCP<Vector> loadAt(const Model& model, const Assembly& a, double t) {
  auto f = rcp(new Vector(a.K->getRowMap()));
  const Fem::Point traction{model.shearAt(t), 0.0, -model.pressureAt(t)};
  model.forSides(Face{1, 2, 1}, a.comm->getRank(), a.comm->getSize(), [&](const Block& B, const auto& side) {
    std::vector<Fem::Point> X(4);
    for (int n = 0; n < 4; ++n) X[n] = B.x(side[n][0], side[n][1], side[n][2]);
    const auto forces = Fem::facetTractionForces(X, traction);
    for (int n = 0; n < 4; ++n)
      for (int d = 0; d < 3; ++d) f->sumIntoGlobalValue(3 * B.id(side[n][0], side[n][1], side[n][2]) + d, forces[3 * n + d]);
  });
  return f;
}

// The sides of face F of this rank's cells, by node id.
Assembled::Surface surface(const Model& model, const Face& F, const Comm& comm) {
  Assembled::Surface s;
  s.nodesPerFacet = 4;
  model.forSides(F, comm.getRank(), comm.getSize(), [&](const Block& B, const auto& side) {
    for (int n = 0; n < 4; ++n) s.nodes.push_back(B.id(side[n][0], side[n][1], side[n][2]));
  });
  return s;
}

// Every choice in one list: Algorithm 2 to a tight tolerance, Coulomb
// friction F = 0.3 and F = 0.5 for pair 1 (the ground).
RCP<Teuchos::ParameterList> parameters(const Model& model) {
  auto p = Teuchos::parameterList("assembled");
  p->set("Outer Algorithm", "Algorithm2");
  p->sublist("Algorithm 2").set("Relative Tolerance", model.tolerance);
  p->sublist("Friction").set("Law", "Coulomb").set("Coefficient", model.frictionInterface);
  p->sublist("Friction").sublist("Pair 1").set("Coefficient", model.frictionGround);
  return p;
}

// How far the model's balance may miss (relative to the load P).
const double kBalance = 1e-6;

// ---------------------------------------------------------------------------
// Files

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string array(const std::vector<double>& v) {
  std::string s = "{";
  for (size_t a = 0; a < v.size(); ++a) s += (a ? ", " : "") + number(v[a]);
  return s + "}";
}

// The mesh as Gmsh 4.1 ASCII: one volume entity per block (its physical
// volume, the body), one surface entity per block face of a physical
// surface; node tags are the application's ids.
void writeGmsh(const Model& model, const std::string& path) {
  std::ofstream out(path);
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  // Physical tags: 1, 2 the volumes, 3... the surfaces.
  const int nb = static_cast<int>(model.blocks.size()), nf = static_cast<int>(model.faces.size());
  out << "$PhysicalNames\n" << nb + nf << "\n";
  for (int b = 0; b < nb; ++b) out << "3 " << b + 1 << " \"" << model.blocks[b].name << "\"\n";
  for (int f = 0; f < nf; ++f) out << "2 " << nb + 1 + f << " \"" << model.faces[f].first << "\"\n";
  out << "$EndPhysicalNames\n";
  // Surface entities: (face, physical tag), numbered from 1.
  std::vector<std::pair<Face, int>> surfaces;
  for (int f = 0; f < nf; ++f)
    for (const Face& F : model.faces[f].second) surfaces.push_back({F, nb + 1 + f});
  auto box = [&](const Block& B, const Face* F) {
    std::array<double, 6> r{B.origin[0], B.origin[1], B.origin[2], B.origin[0] + B.size[0], B.origin[1] + B.size[1],
                            B.origin[2] + B.size[2]};
    if (F) r[F->side == 0 ? F->axis + 3 : F->axis] = r[F->side == 0 ? F->axis : F->axis + 3];
    std::string s;
    for (double v : r) s += number(v) + " ";
    return s;
  };
  out << "$Entities\n0 0 " << surfaces.size() << " " << nb << "\n";
  for (size_t s = 0; s < surfaces.size(); ++s)
    out << s + 1 << " " << box(model.blocks[surfaces[s].first.block], &surfaces[s].first) << "1 " << surfaces[s].second
        << " 0\n";
  for (int b = 0; b < nb; ++b) {
    std::vector<size_t> bounding;
    for (size_t s = 0; s < surfaces.size(); ++s)
      if (surfaces[s].first.block == b) bounding.push_back(s + 1);
    out << b + 1 << " " << box(model.blocks[b], nullptr) << "1 " << b + 1 << " " << bounding.size();
    for (size_t s : bounding) out << " " << s;
    out << "\n";
  }
  out << "$EndEntities\n";
  // Nodes, a block per volume.
  GO numNodes = 0, maxId = 0;
  for (const Block& B : model.blocks) numNodes += B.numNodes(), maxId = std::max(maxId, B.firstId + B.numNodes() - 1);
  out << "$Nodes\n" << nb << " " << numNodes << " 1 " << maxId << "\n";
  for (int b = 0; b < nb; ++b) {
    const Block& B = model.blocks[b];
    out << "3 " << b + 1 << " 0 " << B.numNodes() << "\n";
    for (int k = 0; k <= B.cells[2]; ++k)
      for (int j = 0; j <= B.cells[1]; ++j)
        for (int i = 0; i <= B.cells[0]; ++i) out << B.id(i, j, k) << "\n";
    for (int k = 0; k <= B.cells[2]; ++k)
      for (int j = 0; j <= B.cells[1]; ++j)
        for (int i = 0; i <= B.cells[0]; ++i) {
          const auto x = B.x(i, j, k);
          out << number(x[0]) << " " << number(x[1]) << " " << number(x[2]) << "\n";
        }
  }
  out << "$EndNodes\n";
  // Elements: the hexahedra (type 5) of each volume, the quadrangles (type
  // 3) of each surface.
  long numElements = 0;
  std::vector<long> sides(surfaces.size(), 0);
  for (const Block& B : model.blocks) numElements += B.numCells();
  for (size_t s = 0; s < surfaces.size(); ++s) {
    model.forSides(surfaces[s].first, -1, 1, [&](const Block&, const auto&) { ++sides[s]; });
    numElements += sides[s];
  }
  out << "$Elements\n" << nb + surfaces.size() << " " << numElements << " 1 " << numElements << "\n";
  long tag = 0;
  for (int b = 0; b < nb; ++b) {
    out << "3 " << b + 1 << " 5 " << model.blocks[b].numCells() << "\n";
    model.forCells(b, -1, 1, [&](const Block& B, int i, int j, int k) {
      out << ++tag;
      for (const auto& c : B.corners(i, j, k)) out << " " << B.id(c[0], c[1], c[2]);
      out << "\n";
    });
  }
  for (size_t s = 0; s < surfaces.size(); ++s) {
    out << "2 " << s + 1 << " 3 " << sides[s] << "\n";
    model.forSides(surfaces[s].first, -1, 1, [&](const Block& B, const auto& side) {
      out << ++tag;
      for (const auto& c : side) out << " " << B.id(c[0], c[1], c[2]);
      out << "\n";
    });
  }
  out << "$EndElements\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

// The same problem as an input file of the tribos driver.
void writeDriverInput(const Model& model, const std::string& meshFile, const std::string& path) {
  std::ofstream out(path);
  const Block &lower = model.blocks[0], &upper = model.blocks[1];
  auto material = [&](const Block& B) {
    return "      <ParameterList name=\"Material\">\n"
           "        <Parameter name=\"Young's Modulus\" type=\"double\" value=\"" + number(B.material.E) + "\"/>\n"
           "        <Parameter name=\"Poisson's Ratio\" type=\"double\" value=\"" + number(B.material.nu) + "\"/>\n"
           "      </ParameterList>\n";
  };
  out << "<!-- Written by examples/assembled: the problem that application solves through\n"
         "     Tribos::Assembled, as an input of the tribos driver. Mesh: " << meshFile << " (lower "
      << lower.cells[0] << "x" << lower.cells[1] << "x" << lower.cells[2] << ", upper " << upper.cells[0] << "x"
      << upper.cells[1] << "x" << upper.cells[2] << " Hex8 cells).\n"
         "     The pressure is ramped to t = 1 and held, the shear follows its curve;\n"
         "     the steps t = 1, 2, 3, 4 are the application's four solves. -->\n"
      << "<ParameterList name=\"tribos\">\n"
      << "  <Parameter name=\"Problem Name\" type=\"string\" value=\"assembled\"/>\n"
      << "  <ParameterList name=\"Mesh\">\n"
      << "    <Parameter name=\"File\" type=\"string\" value=\"" << meshFile << "\"/>\n"
      << "    <Parameter name=\"Partitioner\" type=\"string\" value=\"METIS\"/>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Bodies\">\n";
  for (const Block& B : model.blocks)
    out << "    <ParameterList name=\"" << B.name << "\">\n" << material(B) << "    </ParameterList>\n";
  out << "  </ParameterList>\n"
      << "  <ParameterList name=\"Boundary Conditions\">\n"
      << "    <ParameterList name=\"Dirichlet\">\n"
      << "      <ParameterList name=\"symmetry y\">\n"
      << "        <Parameter name=\"Face\" type=\"string\" value=\"symmetry_y\"/>\n"
      << "        <Parameter name=\"Components\" type=\"string\" value=\"y\"/>\n"
      << "        <Parameter name=\"Value\" type=\"Array(double)\" value=\"{0, 0, 0}\"/>\n"
      << "      </ParameterList>\n"
      << "      <ParameterList name=\"wall\">\n"
      << "        <Parameter name=\"Face\" type=\"string\" value=\"lower_wall\"/>\n"
      << "        <Parameter name=\"Components\" type=\"string\" value=\"x\"/>\n"
      << "        <Parameter name=\"Value\" type=\"Array(double)\" value=\"{0, 0, 0}\"/>\n"
      << "      </ParameterList>\n"
      << "    </ParameterList>\n"
      << "    <ParameterList name=\"Traction\">\n"
      << "      <ParameterList name=\"pressure\">\n"
      << "        <Parameter name=\"Face\" type=\"string\" value=\"upper_top\"/>\n"
      << "        <Parameter name=\"Value\" type=\"Array(double)\" value=\"" << array({0, 0, -model.pressure}) << "\"/>\n"
      << "      </ParameterList>\n"
      << "      <ParameterList name=\"shear\">\n"
      << "        <Parameter name=\"Face\" type=\"string\" value=\"upper_top\"/>\n"
      << "        <Parameter name=\"Value\" type=\"Array(double)\" value=\"" << array({model.shear, 0, 0}) << "\"/>\n"
      << "        <Parameter name=\"Curve\" type=\"string\" value=\"shear\"/>\n"
      << "      </ParameterList>\n"
      << "    </ParameterList>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Load Steps\">\n"
      << "    <Parameter name=\"Times\" type=\"Array(double)\" value=\"" << array(model.stepTimes) << "\"/>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Load Curves\">\n"
      << "    <ParameterList name=\"shear\">\n"
      << "      <Parameter name=\"Times\" type=\"Array(double)\" value=\"" << array(model.shearCurve.times) << "\"/>\n"
      << "      <Parameter name=\"Values\" type=\"Array(double)\" value=\"" << array(model.shearCurve.values) << "\"/>\n"
      << "    </ParameterList>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Contact\">\n"
      << "    <Parameter name=\"Enabled\" type=\"bool\" value=\"true\"/>\n"
      << "    <Parameter name=\"Friction Law\" type=\"string\" value=\"Coulomb\"/>\n"
      << "    <Parameter name=\"Friction Coefficient\" type=\"double\" value=\"" << number(model.frictionInterface)
      << "\"/>\n"
      << "    <ParameterList name=\"Pairs\">\n"
      << "      <ParameterList name=\"interface\">\n"
      << "        <Parameter name=\"Slave Surface\" type=\"string\" value=\"upper_bottom\"/>\n"
      << "        <Parameter name=\"Master Surface\" type=\"string\" value=\"lower_top\"/>\n"
      << "        <Parameter name=\"Discretization\" type=\"string\" value=\"Mortar\"/>\n"
      << "      </ParameterList>\n"
      << "      <ParameterList name=\"ground\">\n"
      << "        <Parameter name=\"Slave Surface\" type=\"string\" value=\"lower_bottom\"/>\n"
      << "        <Parameter name=\"Plane Point\" type=\"Array(double)\" value=\"{0, 0, 0}\"/>\n"
      << "        <Parameter name=\"Plane Normal\" type=\"Array(double)\" value=\"{0, 0, 1}\"/>\n"
      << "        <Parameter name=\"Friction Coefficient\" type=\"double\" value=\"" << number(model.frictionGround)
      << "\"/>\n"
      << "      </ParameterList>\n"
      << "    </ParameterList>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Solver\">\n"
      << "    <Parameter name=\"Type\" type=\"string\" value=\"FETI\"/>\n"
      << "    <Parameter name=\"Outer Algorithm\" type=\"string\" value=\"Algorithm2\"/>\n"
      << "    <ParameterList name=\"Algorithm 2\">\n"
      << "      <Parameter name=\"Relative Tolerance\" type=\"double\" value=\"" << number(model.tolerance) << "\"/>\n"
      << "    </ParameterList>\n"
      << "  </ParameterList>\n"
      << "  <ParameterList name=\"Output\">\n"
      << "    <Parameter name=\"Directory\" type=\"string\" value=\"output/assembled\"/>\n"
      << "  </ParameterList>\n"
      << "</ParameterList>\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

// The displacement of every node with its coordinates, gathered on rank 0:
// node id, x, y, z, ux, uy, uz, ascending ids.
void writeDisplacement(const Assembly& a, const Vector& u, const std::string& path) {
  const auto v = u.getData();
  std::vector<double> mine;
  mine.reserve(7 * a.ownedNodes.size());
  for (size_t n = 0; n < a.ownedNodes.size(); ++n) {
    const GO id = a.ownedNodes[n];
    const auto& x = a.position.at(id);
    mine.insert(mine.end(), {double(id), x[0], x[1], x[2]});
    for (int c = 0; c < 3; ++c) mine.push_back(v[a.owned->getLocalElement(3 * id + c)]);
  }
  const int count = static_cast<int>(mine.size()), ranks = a.comm->getSize();
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<double> all;
  if (a.comm->getRank() == 0) {
    for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    all.resize(offsets.back() + counts.back());
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (a.comm->getRank() != 0) return;
  std::vector<size_t> order(all.size() / 7);
  for (size_t n = 0; n < order.size(); ++n) order[n] = n;
  std::sort(order.begin(), order.end(), [&](size_t p, size_t q) { return all[7 * p] < all[7 * q]; });
  std::ofstream out(path);
  out << "node,x,y,z,ux,uy,uz\n";
  for (size_t n : order) {
    out << static_cast<GO>(all[7 * n]);
    for (int c = 1; c < 7; ++c) out << "," << number(all[7 * n + c]);
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

// The whole model's balance, from the solver's results: the ground carries
// the load, sum t_N A = P, and along x the wall's reactions, the ground's
// friction and the shear cancel, R_x + sum t_x A + Q = 0 (A a ground node's
// share of the bottom face, the area its traction is per). Returns the two
// residuals relative to P.
std::array<double, 2> balance(const Model& model, const Assembled::ContactSolver& solver, double t, const Comm& comm) {
  const Block& lower = model.blocks[0];
  const Block& upper = model.blocks[1];
  const auto state = solver.getContactState();
  const auto nodes = solver.getNodeMap();
  const auto normal = state->getData(Assembled::NormalTraction), tx = state->getData(Assembled::TangentialTractionX),
             status = state->getData(Assembled::Status);
  const GO layer = GO(lower.cells[0] + 1) * (lower.cells[1] + 1);  // the ids of the lower block's bottom
  double local[3] = {0, 0, 0}, global[3];  // sum t_N A, sum t_x A, R_x
  for (size_t l = 0; l < state->getLocalLength(); ++l) {
    const GO index = nodes->getGlobalElement(static_cast<LO>(l)) - lower.firstId;
    if (status[l] < 0 || index < 0 || index >= layer) continue;  // not a node of the ground pair
    const int i = static_cast<int>(index % (lower.cells[0] + 1)), j = static_cast<int>(index / (lower.cells[0] + 1));
    const double area = lower.size[0] / lower.cells[0] * (i == 0 || i == lower.cells[0] ? 0.5 : 1.0) *
                        lower.size[1] / lower.cells[1] * (j == 0 || j == lower.cells[1] ? 0.5 : 1.0);
    local[0] += normal[l] * area;
    local[1] += tx[l] * area;
  }
  const auto reaction = solver.getReaction();
  const auto r = reaction->getData();
  for (size_t l = 0; l < reaction->getLocalLength(); ++l)
    if (reaction->getMap()->getGlobalElement(static_cast<LO>(l)) % 3 == 0) local[2] += r[l];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 3, local, global);
  const double area = upper.size[0] * upper.size[1];
  const double P = model.pressureAt(t) * area, Q = model.shearAt(t) * area;
  return {std::abs(global[0] - P) / P, std::abs(global[2] + global[1] + Q) / P};
}

struct Options {
  int size = 1;
  std::string out = "assembled_output";
  double tolerance = 1e-10;
  bool timings = false, fields = true;
};

bool parse(int argc, char** argv, Options& o) {
  for (int a = 1; a < argc; ++a) {
    std::string arg = argv[a], value;
    const auto eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos) value = arg.substr(eq + 1), arg = arg.substr(0, eq);
    auto next = [&]() -> bool {
      if (!value.empty()) return true;
      if (a + 1 >= argc) return false;
      value = argv[++a];
      return true;
    };
    if (arg == "--size") {
      if (!next()) return false;
      o.size = std::atoi(value.c_str());
      if (o.size < 1) return false;
    } else if (arg == "--out") {
      if (!next()) return false;
      o.out = value;
    } else if (arg == "--tolerance") {
      if (!next()) return false;
      o.tolerance = std::atof(value.c_str());
      if (!(o.tolerance > 0)) return false;
    } else if (arg == "--timings") {
      o.timings = true;
    } else if (arg == "--no-fields") {
      o.fields = false;
    } else {
      return false;
    }
  }
  return true;
}

std::string stepName(int step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "assembled.step%04d.csv", step);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Tpetra::ScopeGuard scope(&argc, &argv);
  const auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  Options opt;
  if (!parse(argc, argv, opt)) {
    if (root)
      std::cerr << "usage: mpirun -np N assembled [--size m >= 1] [--out DIR] [--tolerance t] [--timings] [--no-fields]\n";
    return 1;
  }
  try {
    Model model(opt.size);
    model.tolerance = opt.tolerance;
    if (root) {
      ::mkdir(opt.out.c_str(), 0777);
      writeGmsh(model, opt.out + "/assembled.msh");
      writeDriverInput(model, "assembled.msh", opt.out + "/assembled.xml");
    }
    const Assembly a = assemble(model, comm);

    // The problem as the application holds it.
    const RCP<const Assembled::RowMatrix> K = a.K;  // the rank's rows, still open for assembly
    auto problem = rcp(new Assembled::ContactProblem(K, a.owned, a.coordinates));
    problem->setDirichlet(a.dirichlet);
    Assembled::ContactPair interface;
    interface.name = "interface";
    interface.slave = surface(model, Face{1, 2, 0}, *comm);   // the upper block's bottom
    interface.master = surface(model, Face{0, 2, 1}, *comm);  // the lower block's top
    interface.discretization = Contact::ContactDiscretization::Mortar;
    const int k0 = problem->addContactPair(interface);
    Assembled::ContactPair ground;
    ground.name = "ground";
    ground.slave = surface(model, Face{0, 2, 0}, *comm);
    ground.planePoint = {0, 0, 0};
    ground.planeNormal = {0, 0, 1};
    const int k1 = problem->addContactPair(ground);
    if (k0 != 0 || k1 != 1) throw std::runtime_error("unexpected pair numbers");
    Assembled::ContactSolver solver(problem, parameters(model));

    GO nodes = 0;
    long cells = 0;
    for (const Block& B : model.blocks) nodes += B.numNodes(), cells += B.numCells();
    if (root)
      std::cout << "assembled: " << nodes << " nodes, " << cells << " Hex8 cells, " << comm->getSize()
                << " ranks, Coulomb F = " << model.frictionInterface << " (interface, mortar), "
                << model.frictionGround << " (ground)\n";
    std::ofstream table;
    if (root) {
      table.open(opt.out + "/assembled.steps.csv");
      table << "step,time,converged,outer_algorithm,iterations,n_A,kkt_worst,limit,contact_nodes,active,stick,slip,"
               "subdomains,primal_dofs,dual_dofs,rebuilt,assembly_s,setup_s,solve_s\n";
    }
    bool ok = true;
    double setup = 0, solve = 0;
    for (size_t s = 0; s < model.stepTimes.size(); ++s) {
      const double t = model.stepTimes[s];
      problem->setLoad(loadAt(model, a, t));
      const bool converged = solver.solve() == Contact::SolveStatus::Converged;
      const Assembled::SolveSummary& sum = solver.getSummary();
      std::string worstName;
      const double worst = sum.kkt.worst(&worstName);
      const auto balanced = balance(model, solver, t, *comm);
      const bool stepOk = converged && sum.converged && worst <= sum.limit && sum.step == static_cast<int>(s) + 1 &&
                          sum.rebuilt == (s == 0) && std::max(balanced[0], balanced[1]) <= kBalance;
      ok = ok && stepOk;
      // Seconds as the driver reports them: the largest over the ranks.
      double seconds[2] = {sum.setupSeconds, sum.solveSeconds}, slowest[2];
      Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, seconds, slowest);
      setup += slowest[0];
      solve += slowest[1];
      if (s == 0 && root)
        std::cout << "assembled: " << sum.subdomains << " subdomains, " << sum.primalDofs << " primal dofs, "
                  << sum.dualDofs << " dual\n";
      if (root) {
        std::ostringstream line;
        line << "step " << s + 1 << " t " << t << " pressure " << model.pressureAt(t) << " shear " << model.shearAt(t)
             << ": " << (sum.converged ? "converged" : "NOT converged") << ", " << sum.outerAlgorithm << " "
             << sum.iterations << " iterations, n_A " << sum.n_A << ", kkt " << worst << " (" << worstName
             << ") limit " << sum.limit << ", contact " << sum.counts.nodes << " active " << sum.counts.active
             << " stick " << sum.counts.stick << " slip " << sum.counts.slip << ", balance " << balanced[0] << " "
             << balanced[1];
        if (opt.timings) line << ", setup " << slowest[0] << " s, solve " << slowest[1] << " s";
        if (!stepOk) line << "  FAILED" << (sum.converged ? "" : ": " + sum.reason);
        std::cout << line.str() << std::endl;
        table << s + 1 << "," << number(t) << "," << (sum.converged ? "true" : "false") << "," << sum.outerAlgorithm
              << "," << sum.iterations << "," << sum.n_A << "," << number(worst) << "," << number(sum.limit) << ","
              << sum.counts.nodes << "," << sum.counts.active << "," << sum.counts.stick << "," << sum.counts.slip
              << "," << sum.subdomains << "," << sum.primalDofs << "," << sum.dualDofs << ","
              << (sum.rebuilt ? "true" : "false") << "," << number(s == 0 ? a.seconds : 0.0) << ","
              << number(slowest[0]) << "," << number(slowest[1]) << std::endl;
      }
      if (opt.fields) writeDisplacement(a, *solver.getDisplacement(), opt.out + "/" + stepName(static_cast<int>(s) + 1));
    }
    if (root) {
      if (opt.timings)
        std::cout << "assembled: assembly " << a.seconds << " s, setup " << setup << " s, solve " << solve
                  << " s (Tribos: setup + solve " << setup + solve << " s)\n";
      std::cout << "assembled: files in " << opt.out << "\n";
      if (!ok) std::cerr << "assembled: FAILED\n";
    }
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "assembled: error on rank " << comm->getRank() << ": " << e.what() << "\n";
    return 1;
  }
}
