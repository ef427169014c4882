#include "Tribos_MemoryEstimate.hpp"

#include <mpi.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "Tribos_Decomposition.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FetiOperators.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Reduce.hpp"

namespace Tribos {

namespace {

constexpr double kMB = 1024.0 * 1024.0, kGB = 1024.0 * kMB;

std::string bytes(double b) {
  std::ostringstream os;
  os.precision(b >= kGB ? 3 : 2);
  if (b >= kGB) os << b / kGB << " GB";
  else os << std::fixed << b / kMB << " MB";
  return os.str();
}

// Nonzeros of a sparse Cholesky factor of a 3D elasticity matrix with d dofs
// under nested dissection grow like d^(4/3); 150 bytes per unit fits CHOLMOD.
double factorBytes(double dofs) { return 150.0 * std::pow(dofs, 4.0 / 3.0); }

// One subdomain of the FETI run: a box of a x b x c cells (structured), or
// the average METIS part, which has about the surface of a cube.
struct SubdomainShape {
  double nodes = 0, surfaceNodes = 0;
};

// The nodes of a box face of a x b cells of the type's: the corners' lattice,
// the lattice of half cells (Tet10), or the corners and the edges' middles
// (Hex20).
double faceNodeCount(Mesh::CellType type, double a, double b) {
  switch (type) {
    case Mesh::CellType::Tet10: return (2 * a + 1) * (2 * b + 1);
    case Mesh::CellType::Hex20: return (a + 1) * (b + 1) + a * (b + 1) + (a + 1) * b;
    default: return (a + 1) * (b + 1);
  }
}

SubdomainShape subdomainShape(const Mesh::BoxSpec& spec, double totalNodes, const Mesh::DecompositionSpec& dec, int S) {
  SubdomainShape s;
  if (dec.partitioner == "Structured") {
    Mesh::BoxSpec sub = spec;  // one subdomain's box: the grid divides the cells
    for (int a = 0; a < 3; ++a) sub.cells[a] = spec.cells[a] / dec.grid[a];
    const double n[3] = {double(sub.cells[0]), double(sub.cells[1]), double(sub.cells[2])};
    s.nodes = Mesh::boxNodeCount(sub);
    s.surfaceNodes = 2.0 * (faceNodeCount(spec.type, n[0], n[1]) + faceNodeCount(spec.type, n[1], n[2]) +
                            faceNodeCount(spec.type, n[0], n[2]));
  } else {
    s.nodes = 1.1 * totalNodes / S;  // interface nodes are copied
    s.surfaceNodes = 6.0 * std::pow(s.nodes, 2.0 / 3.0);
  }
  return s;
}

// Semismooth Newton holds the dual densely on every rank: the dual, the
// reduction's blocks and the Newton matrix, about 24 n^2 bytes measured, for
// n dual rows (0.65 S b on box decompositions), at most its Dense Limit;
// above it (Linear Solver = Auto) or matrix-free it holds vectors only.
double newtonBytes(const Teuchos::ParameterList& params, int S, double b) {
  const auto& solver = params.sublist("Solver");
  if (solver.get<std::string>("Outer Algorithm") != "Semismooth Newton") return 0.0;
  const auto& list = solver.isSublist("Semismooth Newton") ? solver.sublist("Semismooth Newton") : solver;
  const double limit = list.isParameter("Dense Limit") ? list.get<int>("Dense Limit") : 5000.0;
  const std::string linear = list.isParameter("Linear Solver") ? list.get<std::string>("Linear Solver") : "Auto";
  const double n = 0.65 * S * b;
  if (linear == "Projected CG" || (linear == "Auto" && n > limit)) return 0.0;
  return 24.0 * std::min(limit, n) * std::min(limit, n);
}

double fetiBytes(const Teuchos::ParameterList& params, const Mesh::BoxSpec& spec, double nodes, int numRanks, int rank,
                 const MeshSize* meshSize) {
  const auto dec = Input::decompositionSpec(params, numRanks, meshSize);
  const int S = dec.partitioner == "METIS" ? dec.subdomains : dec.grid[0] * dec.grid[1] * dec.grid[2];
  const auto layout = Mesh::makeRankLayout(S, numRanks);
  const int mine = layout.firstSubdomain(rank + 1) - layout.firstSubdomain(rank);
  const SubdomainShape s = subdomainShape(spec, nodes, dec, S);
  const double d = 3.0 * s.nodes, b = 1.5 * s.surfaceNodes;
  const std::string op = params.sublist("Solver").sublist("FETI").get<std::string>("Dual Operator");
  const bool contact = Input::fetiContact(params);
  const bool explicitF = op == "Explicit" || (op == "Auto" && contact && b <= Feti::FetiProblem::kAutoExplicitRows);
  // A packed block holds b^2/2 values; while it is formed, the full b x b
  // double inverse and its packed copy coexist (counted as 16 b^2 per
  // subdomain in double, 12 b^2 when the copy is rounded to float).
  const bool single = params.sublist("Solver").sublist("FETI").get<std::string>("Dense Block Precision") == "Single";
  // The coarse problem: two sparse Cholesky factors (GG' and G_E G_E') of
  // order 6S; their fill was measured as 4.8 (6S)^1.5 values each on box
  // decompositions (docs/scaling.md). Split among the ranks (Coarse Problem,
  // docs/feti.md) a rank holds its part and the separator's dense blocks:
  // 0.52-0.6 of the whole on 2 ranks at S = 5184, taken as 1/ranks + 0.1.
  const std::string coarse = params.sublist("Solver").sublist("FETI").get<std::string>("Coarse Problem");
  const bool split =
      numRanks > 1 && (coarse == "Split" || (coarse == "Auto" && 6 * S >= Feti::CoarseSpace::kAutoSplitRows));
  const double coarseBytes =
      2.0 * 8.0 * 4.8 * std::pow(6.0 * S, 1.5) * (split ? std::min(1.0, 1.0 / numRanks + 0.1) : 1.0);
  // CHOLMOD factors small subdomains densely when it forms their blocks
  // (packed: d^2/2 doubles).
  const bool denseFactor = explicitF && d <= kDenseFactorRows &&
                           params.sublist("Solver").sublist("FETI").get<std::string>("Local Solver") == "CHOLMOD";
  const double factor = denseFactor ? 4.0 * d * d : factorBytes(d);
  return mine * (4000.0 * s.nodes + factor + (explicitF ? (single ? 12.0 : 16.0) * b * b : 0.0)) + coarseBytes +
         newtonBytes(params, S, b);
}

double monolithicBytes(const Teuchos::ParameterList& params, double nodes, int numRanks) {
  const bool direct = params.sublist("Solver").sublist("Monolithic").get<std::string>("Linear Solver") == "Direct";
  return 8000.0 * nodes / numRanks + (direct ? 2.0 * factorBytes(3.0 * nodes) : 0.0);
}

// Reads "Key: value kB" from /proc/meminfo.
double meminfo(const char* key) {
  std::ifstream in("/proc/meminfo");
  for (std::string k; in >> k;) {
    double v = 0;
    std::string unit;
    in >> v >> unit;
    if (k == std::string(key) + ":") return v * 1024.0;
  }
  return 0;
}

// The cgroup (v2 or v1) memory limit of this process, 0 when none.
double cgroupLimit() {
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    std::string v;
    if (in >> v && v != "max") {
      const double limit = std::strtod(v.c_str(), nullptr);
      if (limit > 0 && limit < 1e18) return limit;
    }
  }
  return 0;
}

}  // namespace

std::string MemoryEstimate::describe() const {
  return bytes(total()) + " (mesh and vectors " + bytes(mesh) + ", solver " + bytes(solver) + ")";
}

namespace {

// The counts of the mesh: the box's, or those of the mesh read from Mesh/File.
MeshSize meshCounts(const Mesh::BoxSpec& spec, const MeshSize* meshSize) {
  if (meshSize) return *meshSize;
  MeshSize m;
  m.nodes = Mesh::boxNodeCount(spec);
  m.cells = Mesh::boxCellCount(spec);
  m.nodesPerCell = Mesh::nodesPerCell(spec.type);
  return m;
}

}  // namespace

double outputBytesPerStep(const Teuchos::ParameterList& params, const MeshSize* meshSize) {
  const Mesh::BoxSpec spec = Input::boxSpec(params);
  const MeshSize m = meshCounts(spec, meshSize);
  // HDF5's metadata, then the datasets: geometry, displacement and reaction
  // (3 doubles per node), topology (8-byte indices: one per node of a cell),
  // the cell fields (13 numbers: von Mises, the stress tensor, the principal
  // stresses, subdomain, rank, body).
  const double nodesPerCell = m.nodesPerCell;
  double bytes = 16e3 + 72.0 * m.nodes + (8.0 * nodesPerCell + 104.0) * m.cells;
  // The contact point set: about 42 numbers per contact node, the nodes of
  // a face or two of the bodies.
  if (params.sublist("Contact").get<bool>("Enabled")) bytes += 336.0 * 2.0 * std::pow(m.nodes, 2.0 / 3.0);
  // The step's part of the index, its row of the steps table, its history rows.
  return bytes + 6e3;
}

namespace {

// What a history holds in memory for each of its steps: its time in the
// parameter list, the run's list of times and the validated copy; and the
// step's row of the summary when no steps table takes it (no results written).
double historyBytes(const Teuchos::ParameterList& params) {
  const double steps = static_cast<double>(Input::loadStepTimes(params).size());
  return steps * (100.0 + (params.sublist("Output").get<bool>("Write Results") ? 0.0 : 2000.0));
}

}  // namespace

MemoryEstimate estimateMemory(const Teuchos::ParameterList& params, int numRanks, int rank, bool verify,
                              const MeshSize* meshSize) {
  const Mesh::BoxSpec spec = Input::boxSpec(params);
  const MeshSize counts = meshCounts(spec, meshSize);
  const double nodes = counts.nodes, cells = counts.cells;
  MemoryEstimate e;
  const Input::Method m = Input::method(params);
  // Rank 0 holds the whole mesh while it is read, checked and cut, and every
  // rank its part; the semismooth* method (serial) keeps it on every rank.
  const double whole = 400.0 * nodes + 50.0 * cells;
  e.mesh = 80.0 * kMB + whole / numRanks + (rank == 0 || m == Input::Method::Semismooth ? whole : 0.0) +
           historyBytes(params);
  if (m == Input::Method::Semismooth)
    e.solver = rank == 0 ? 28000.0 * nodes + factorBytes(3.0 * nodes) : 0.0;
  else if (m == Input::Method::Monolithic)
    e.solver = monolithicBytes(params, nodes, numRanks);
  else
    e.solver = fetiBytes(params, spec, nodes, numRanks, rank, meshSize);
  if (verify && (m == Input::Method::Monolithic || m == Input::Method::FetiLinear)) e.solver += monolithicBytes(params, nodes, numRanks);
  return e;
}

double availableMemory() {
  const double available = meminfo("MemAvailable"), limit = cgroupLimit();
  if (available > 0 && limit > 0) return std::min(available, limit);
  return std::max(available, limit);
}

double memoryLimit(double maxMemory) {
  const double available = availableMemory();
  return maxMemory > 0 && (available <= 0 || maxMemory < available) ? maxMemory : available;
}

double parseMemorySize(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  std::string unit(end ? end : "");
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() == 2 && unit[1] == 'B') unit.pop_back();
  const double scale = unit.empty() ? 1.0 : unit == "K" ? 1024.0 : unit == "M" ? kMB : unit == "G" ? kGB
                                                                    : unit == "T" ? 1024.0 * kGB : -1.0;
  TRIBOS_REQUIRE(end != text.c_str() && scale > 0 && std::isfinite(v) && v > 0,
                 what << " \"" << text << "\": expected a positive size such as 4G, 500M or 2.5GB");
  return v * scale;
}

MemoryEstimate requireMemory(const Teuchos::ParameterList& params, double limit, bool verify, const RCP<const Comm>& comm,
                             const MeshSize* meshSize) {
  const MemoryEstimate mine = estimateMemory(params, comm->getSize(), comm->getRank(), verify, meshSize);
  const MPI_Comm world = rawComm(*comm);
  MPI_Comm machine;
  MPI_Comm_split_type(world, MPI_COMM_TYPE_SHARED, comm->getRank(), MPI_INFO_NULL, &machine);
  double parts[2] = {mine.mesh, mine.solver}, sum[2] = {0, 0};
  MPI_Allreduce(parts, sum, 2, MPI_DOUBLE, MPI_SUM, machine);
  int ranksHere = 1;
  MPI_Comm_size(machine, &ranksHere);
  MPI_Comm_free(&machine);
  // --max-memory may only lower what the machine has (memoryLimit).
  const double allowed = memoryLimit(limit);
  const bool userBound = limit > 0 && allowed == limit;
  // The machine that is shortest of memory speaks for all.
  struct {
    double ratio;
    int rank;
  } worst{allowed > 0 ? (sum[0] + sum[1]) / allowed : 0.0, comm->getRank()}, global{};
  MPI_Allreduce(&worst, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (global.ratio <= 1.0) return mine;
  double report[5] = {sum[0], sum[1], allowed, double(ranksHere), userBound ? 1.0 : 0.0};
  MPI_Bcast(report, 5, MPI_DOUBLE, global.rank, world);
  const bool bound = report[4] != 0;  // the short machine's limit is --max-memory
  MemoryEstimate need;
  need.mesh = report[0];
  need.solver = report[1];
  std::ostringstream os;
  os << "the run needs about " << need.describe() << " on a machine running " << report[3] << " of its ranks, but "
     << bytes(report[2]) << (bound ? " are allowed (--max-memory)" : " are available there")
     << "; use a coarser mesh (" << (meshSize ? "Mesh/File" : "Mesh/Level, Mesh/Cells")
     << "), more subdomains or more machines"
     << (bound ? ", or raise --max-memory" : "")
     << (limit > 0 && !bound ? " (--max-memory " + bytes(limit) + " is above what the machine has and cannot raise it)" : "");
  throw CollectiveError(os.str());
}

}  // namespace Tribos
