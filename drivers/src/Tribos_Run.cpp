#include "Tribos_Run.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_ArrayScan.hpp"
#include "Tribos_Assembly.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_CleanupOnSignal.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FetiContact.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_FileDigest.hpp"
#include "Tribos_FileKind.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_GmshReader.hpp"
#include "Tribos_History.hpp"
#include "Tribos_MeshBroadcast.hpp"
#include "Tribos_GeoScript.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_InputXml.hpp"
#include "Tribos_MemoryEstimate.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ParameterReader.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_ResultReader.hpp"
#include "Tribos_ResultSet.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_RigidMotions.hpp"
#include "Tribos_RunReport.hpp"
#include "Tribos_SolveMethod.hpp"
#include "Tribos_StepSeries.hpp"

namespace Tribos {

namespace {

int requestedSubdomains(const Mesh::DecompositionSpec& d) {
  return d.partitioner == "METIS" ? d.subdomains : d.grid[0] * d.grid[1] * d.grid[2];
}

// The principal stresses of a symmetric stress tensor s (xx, yy, zz, yz,
// xz, xy), largest first: its eigenvalues, in closed form (the
// trigonometric solution of the characteristic cubic).
std::array<double, 3> principalStresses(const std::array<double, 6>& s) {
  const double mean = (s[0] + s[1] + s[2]) / 3;
  const double off = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  const double dev = (s[0] - mean) * (s[0] - mean) + (s[1] - mean) * (s[1] - mean) + (s[2] - mean) * (s[2] - mean);
  std::array<double, 3> e;
  if (!(off > 1e-30 * dev)) {  // diagonal (a hydrostatic state included)
    e = {s[0], s[1], s[2]};
  } else {
    const double p = std::sqrt((dev + 2 * off) / 6);
    // B = (s - mean I) / p; r = det(B) / 2 in [-1, 1].
    const double b00 = (s[0] - mean) / p, b11 = (s[1] - mean) / p, b22 = (s[2] - mean) / p;
    const double b12 = s[3] / p, b02 = s[4] / p, b01 = s[5] / p;
    const double det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
    const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
    const double pi = std::acos(-1.0);
    e[0] = mean + 2 * p * std::cos(phi);
    e[2] = mean + 2 * p * std::cos(phi + 2 * pi / 3);
    e[1] = 3 * mean - e[0] - e[2];
  }
  std::sort(e.begin(), e.end(), std::greater<double>());
  return e;
}

// The Voigt components (xx, yy, zz, yz, xz, xy) in the order of XDMF's
// Tensor6 (xx, xy, xz, yy, yz, zz), which ParaView reads as a symmetric tensor.
constexpr int kTensor6FromVoigt[6] = {0, 5, 4, 1, 3, 2};

// Every local cell's stress tensor (at its centre: constant in a
// tetrahedron) with its von Mises stress and principal stresses derived
// from it, and its subdomain, rank and body.
std::vector<IO::Field> cellFields(const Mesh::Discretization& disc, const Fem::BodyMaterials& mat,
                                  const Fem::NodalVector& u) {
  IO::Field vm{"von_mises", 1, {}}, stress{"stress", 6, {}, IO::FieldShape::SymmetricTensor},
      principal{"principal_stress", 3, {}, IO::FieldShape::Matrix},  // three numbers, not a vector
      sub{"subdomain", 1, {}}, rank{"rank", 1, {}}, body{"body", 1, {}};
  const Mesh::Mesh& part = disc.part;
  std::vector<double> ue;
  for (int c = 0; c < part.numCells(); ++c) {
    ue.resize(3 * part.cellSize(c));
    for (int a = 0; a < part.cellSize(c); ++a)
      for (int d = 0; d < 3; ++d) ue[3 * a + d] = u.at(disc.meshNode(part.cell(c)[a]))[d];
    const auto sigma = Fem::cellStress(part.cellType(c), Fem::cellCoordinates(part, c), ue, mat.ofCell(part, c));
    vm.values.push_back(Fem::vonMises(sigma));
    for (int k : kTensor6FromVoigt) stress.values.push_back(sigma[k]);
    const auto e = principalStresses(sigma);
    principal.values.insert(principal.values.end(), e.begin(), e.end());
    sub.values.push_back(disc.cellPart[c]);
    rank.values.push_back(disc.myRank);
    body.values.push_back(part.bodyOf(c));
  }
  return {vm, stress, principal, sub, rank, body};
}

// What friction leaves at each contact node over a load history, carried
// from step to step (and read back from its last step file by a restart):
// the energy friction has dissipated there since the start of the history,
// and the slip amplitude, the largest |slip| so far (the slip, w_T, is 0 at
// the start: the unloaded body).
class FrictionMemory {
 public:
  struct Node {
    double dissipatedEnergy = 0, slipAmplitude = 0;
  };
  // Adds the step whose contact nodes (this rank's) are r.
  void advance(const Contact::ContactNodeResults& r) {
    for (size_t k = 0; k < r.nodes.size(); ++k) {
      Node& m = nodes_[r.nodes[k]];
      m.dissipatedEnergy += r.frictionDissipation(k);
      const double* s = &r.slip[3 * k];
      m.slipAmplitude = std::max(m.slipAmplitude, std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
    }
  }
  // What a restart read back for mesh node n.
  void set(int node, const Node& m) { nodes_[node] = m; }
  Node at(int node) const {
    const auto it = nodes_.find(node);
    return it == nodes_.end() ? Node() : it->second;
  }
  // The energy dissipated so far per pair 0..numPairs-1 at the contact nodes r
  // (this rank's), summed over the ranks. Collective.
  std::vector<double> pairEnergies(const Contact::ContactNodeResults& r, int numPairs, const Comm& comm) const {
    std::vector<double> local(static_cast<size_t>(numPairs), 0.0), global(local.size(), 0.0);
    for (size_t k = 0; k < r.nodes.size(); ++k) {
      const int pair = r.constraint[k].pair;
      if (pair >= 0 && pair < numPairs) local[pair] += at(r.nodes[k]).dissipatedEnergy;
    }
    if (numPairs > 0) Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, numPairs, local.data(), global.data());
    return global;
  }

 private:
  std::map<int, Node> nodes_;  // mesh node -> its memory
};

// Contact nodes with their forces, slip and status, as a ParaView point set.
// The rows in /nodes and the coordinates of the nodes (slave and master
// nodes may lie in other ranks' parts) are asked of their owners. Collective.
IO::PointSet contactPointSet(const Mesh::Discretization& disc, const Contact::ContactNodeResults& r,
                             const FrictionMemory& memory, const Comm& comm) {
  IO::PointSet ps;
  ps.name = "contact";
  IO::Field normal{"normal_force", 1, r.normalForce}, tangential{"tangential_force", 3, r.tangentialForce},
      slip{"slip", 3, r.slip}, status{"status", 1, {}}, gap{"gap", 1, r.gap}, direction{"normal", 3, {}},
      pair{"pair", 1, {}}, node{"node", 1, {}};
  IO::Field normalTraction{"normal_traction", 1, {}}, tangentialTraction{"tangential_traction", 3, {}},
      slipIncrement{"slip_increment", 3, {}}, slipAmplitude{"slip_amplitude", 1, {}},
      dissipatedEnergy{"dissipated_energy", 1, {}};
  for (size_t k = 0; k < r.nodes.size(); ++k) {
    normalTraction.values.push_back(r.normalTraction(k));
    const auto t = r.tangentialTraction(k), s = r.slipIncrement(k);
    tangentialTraction.values.insert(tangentialTraction.values.end(), t.begin(), t.end());
    slipIncrement.values.insert(slipIncrement.values.end(), s.begin(), s.end());
    const auto m = memory.at(r.nodes[k]);
    slipAmplitude.values.push_back(m.slipAmplitude);
    dissipatedEnergy.values.push_back(m.dissipatedEnergy);
  }
  // As many master columns as the widest partner on any rank: a facet's 4
  // nodes for node-to-segment, all the nodes a mortar row couples.
  int widthHere = 4, width = 4;
  for (const auto& c : r.constraint) widthHere = std::max(widthHere, static_cast<int>(c.master.size()));
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, widthHere, Teuchos::outArg(width));
  IO::Field masterNode{"master_node", width, {}, IO::FieldShape::Matrix},
      masterWeight{"master_weight", width, {}, IO::FieldShape::Matrix};
  for (int s : r.status) status.values.push_back(s);
  // The slave side of rows on second-order surfaces (a mid-edge node's
  // transformed value, three slave nodes): written when a row of the run has one.
  int slaveSideHere = 0, slaveSide = 0;
  for (const auto& c : r.constraint) slaveSideHere = std::max(slaveSideHere, static_cast<int>(c.slave.size()));
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, slaveSideHere, Teuchos::outArg(slaveSide));
  IO::Field slaveNode{"slave_node", slaveSide, {}, IO::FieldShape::Matrix},
      slaveWeight{"slave_weight", slaveSide, {}, IO::FieldShape::Matrix};
  std::vector<int> asked(r.nodes);
  for (const auto& c : r.constraint)
    for (const auto& [n, weight] : c.terms()) asked.push_back(n);
  const auto answers = disc.askOwners(asked, 4,
                                      [&](int n, double* out) {
                                        out[0] = static_cast<double>(disc.nodeIndex()[n]);
                                        for (int d = 0; d < 3; ++d) out[1 + d] = disc.part.coords[n][d];
                                      },
                                      comm);
  std::map<int, const double*> known;  // mesh node -> row, x, y, z
  for (size_t i = 0; i < asked.size(); ++i) known[asked[i]] = &answers[4 * i];
  for (int n : r.nodes) {
    node.values.push_back(known.at(n)[0]);  // its row in /nodes
    ps.coords.push_back({known.at(n)[1], known.at(n)[2], known.at(n)[3]});
  }
  // The partner of each slave node: its master nodes and their weights, -1
  // and 0 where there are fewer (none: a rigid plane).
  for (const auto& c : r.constraint) {
    direction.values.insert(direction.values.end(), c.normal.begin(), c.normal.end());
    pair.values.push_back(c.pair);
    for (size_t i = 0; i < static_cast<size_t>(width); ++i) {
      masterNode.values.push_back(i < c.master.size() ? known.at(c.master[i].first)[0] : -1);
      masterWeight.values.push_back(i < c.master.size() ? c.master[i].second : 0.0);
    }
    for (size_t i = 0; i < static_cast<size_t>(slaveSide); ++i) {
      slaveNode.values.push_back(i < c.slave.size() ? known.at(c.slave[i].first)[0] : -1);
      slaveWeight.values.push_back(i < c.slave.size() ? c.slave[i].second : 0.0);
    }
  }
  ps.fields = {normal,        normalTraction, tangential,       tangentialTraction, slip,
               slipIncrement, slipAmplitude,  dissipatedEnergy, status,             gap,
               direction,     pair,           node,             masterNode,         masterWeight};
  if (slaveSide > 0) ps.fields.insert(ps.fields.end(), {slaveNode, slaveWeight});
  return ps;
}

// The decomposition of the run. The semismooth* method is serial: subdomains
// only spread the output over the ranks, so a decomposition coarser than the
// run is refined by METIS.
// A mesh file sized by Mesh/Subdomain Size is decomposed once its counts
// are known (meshSize); before, its subdomain count is 0.
Mesh::DecompositionSpec decompositionFor(const Teuchos::ParameterList& params, int numRanks,
                                         const MeshSize* meshSize = nullptr) {
  auto decomposition = Input::decompositionSpec(params, numRanks, meshSize);
  if (requestedSubdomains(decomposition) == 0) return decomposition;
  if (Input::method(params) == Input::Method::Semismooth && requestedSubdomains(decomposition) < numRanks) {
    decomposition.partitioner = "METIS";
    decomposition.subdomains = numRanks;
  }
  return decomposition;
}

// The displacement and the KKT figures of the result must be finite, and the
// work of the forces on it (at most dofs U P) representable: values beyond
// double precision (a modulus of 1e-299, loads of 1e308) are a numerical
// breakdown, not a result.
void requireRepresentable(const Fem::NodalVector& u, const Contact::ResultKKT& kkt, const std::string& method) {
  int finiteHere = allFinite(u.values()), finiteEverywhere = 0;
  Teuchos::reduceAll(*u.layout().comm(), Teuchos::REDUCE_MIN, finiteHere, Teuchos::outArg(finiteEverywhere));
  const bool finite = finiteEverywhere && std::isfinite(kkt.worst()) && std::isfinite(kkt.displacementScale) &&
                      std::isfinite(kkt.forceScale);
  const double work = 3.0 * u.layout().numNodes() * kkt.displacementScale * kkt.forceScale;
  if (finite && std::isfinite(work)) return;
  std::ostringstream os;
  os << method << " produced " << (finite ? "values whose products overflow" : "non-finite values")
     << " (largest displacement " << kkt.displacementScale << ", largest nodal force " << kkt.forceScale
     << "): the problem's scales are beyond double precision; check Material/Young's Modulus and the loads. "
        "No result is written";
  throw RunFailure(os.str());
}

std::string outputDirectory(const Teuchos::ParameterList& params, const RunOptions& options) {
  return options.outputDir.empty() ? params.sublist("Output").get<std::string>("Directory") : options.outputDir;
}

// The files of a result set in Output/Directory, in the order they are
// committed (the summary, the marker of a complete set, last).
struct ResultNames {
  std::string h5, xmf, parameters, history, steps, summary;
  explicit ResultNames(const std::string& base)
      : h5(base + ".h5"), xmf(base + ".xmf"), parameters(base + ".parameters.xml"), history(base + ".history.csv"),
        steps(base + ".steps.jsonl"), summary(base + ".json") {}
  std::vector<std::string> all() const { return {h5, xmf, parameters, history, steps, summary}; }
};

// Every file the run reads or writes, by the name messages give it.
std::vector<IO::RunFile> runFiles(const Teuchos::ParameterList& params, const RunOptions& options) {
  std::vector<IO::RunFile> files = {{"--summary", options.summaryFile, true},
                                    {"--export-fclib", options.exportFclib, true},
                                    {"Mesh/File", Input::meshFile(params), false}};
  std::string rerun;  // the parameters file of a result, when the input is one
  if (params.sublist("Output").get<bool>("Write Results")) {
    const std::string dir = outputDirectory(params, options);
    const ResultNames names(params.sublist("Output").get<std::string>("Base Name"));
    for (const auto& name : names.all()) files.push_back({"the result file " + name, dir + "/" + name, true});
    files.push_back({"the output directory's lock file", dir + "/" + IO::OutputDirectory::lockName(), true});
    rerun = dir + "/" + names.parameters;
  }
  // A result's parameters file run again (README) is rewritten with the
  // effective parameters of the new result: the one input a run may replace
  // (it was read whole before). Every other output is still kept from it,
  // being kept from the parameters file.
  if (!options.inputName.empty() && (rerun.empty() || !sameFile(options.inputName, rerun)))
    files.push_back({"the input file", options.inputName, false});
  return files;
}

// --summary and --export-fclib must not name a data file of the result
// series, links and ".." seen through: a step file the run writes, or one of
// its Base Name that the run's first step removes (BASE.h5 and every
// BASE.step<digits>.h5 of the directory: what an earlier run left). The
// other files of the set are compared by requireDistinctFiles.
void requireOutsideSeries(const Teuchos::ParameterList& params, const RunOptions& options, const Comm& comm) {
  std::string error;
  const auto& output = params.sublist("Output");
  if (comm.getRank() == 0 && output.get<bool>("Write Results")) {
    const std::string dir = outputDirectory(params, options), base = output.get<std::string>("Base Name");
    const long long numSteps = static_cast<long long>(Input::loadStepTimes(params).size());
    for (const auto& [role, path] : {std::pair<std::string, std::string>{"--summary", options.summaryFile},
                                     {"--export-fclib", options.exportFclib}}) {
      if (path.empty() || !error.empty()) continue;
      std::error_code ec;
      const auto resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
      if (ec || !sameFile(resolved.parent_path().string(), dir)) continue;
      const long long step = IO::StepSeries::stepOfDataFileName(base, resolved.filename().string());
      if (step < 0) continue;
      const std::string series = dir + "/" + base + ".json";
      error = role + " " + path + " is " +
              (numSteps > 1 && step >= 1 && step <= numSteps
                   ? "the data file of load step " + std::to_string(step) + " of the result " + series
                   : numSteps == 1 && step == 0 ? "the data file of the result " + series
                                                : "a data file of Output/Base Name = " + base + " in " + dir +
                                                      ", which the run removes when it writes its first step") +
              "; the run would overwrite it";
    }
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError(error);
}

// Two results of one directory must not share a file: Base Name P and
// P.step<digits> do (P's load step file P.step0001.h5 is the data file of
// the one-step result P.step0001, and a run of either removes or overwrites
// the other's). Rank 0 looks for the summary of such a result, under the
// directory's lock; the refusal names both.
void requireNoNameClash(const IO::OutputDirectory& dir, const std::string& base, const Comm& comm) {
  std::string error;
  if (comm.getRank() == 0) {
    std::string listError;
    for (const std::string& name : directoryEntries(dir.path(), listError)) {
      const std::string suffix = ".json";
      if (!error.empty() || name.size() <= suffix.size() || name.compare(name.size() - 5, 5, suffix) != 0) continue;
      const std::string other = name.substr(0, name.size() - suffix.size());
      if (other == base) continue;
      const std::string mine = dir.path() + "/" + base, theirs = dir.path() + "/" + other;
      if (IO::StepSeries::stepOfDataFileName(other, base + ".h5") > 0)
        error = "Output/Base Name = " + base + ": the directory holds the result " + theirs + ".json, whose load step file " +
                mine + ".h5 would be this run's data file; choose another Base Name or Output/Directory";
      else if (IO::StepSeries::stepOfDataFileName(base, other + ".h5") > 0)
        error = "Output/Base Name = " + base + ": the directory holds the result " + theirs + ".json, whose data file " +
                theirs + ".h5 has the name of a load step file of " + mine +
                " (the run would remove or overwrite it); choose another Base Name or Output/Directory";
    }
    if (error.empty()) error = listError;
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError("output directory " + dir.path() + ": " + error);
}

// The output of the whole history must fit in the output directory's file
// system: its steps' files (outputBytesPerStep) against the space free there.
// The estimate is meant to be right within a factor of two: a history is
// refused when half of it does not fit (what surely cannot be written); one
// that fits the estimate but not the disk still ends cleanly (exit 3,
// docs/exit_codes.md, disk full).
void requireDiskSpace(const IO::OutputDirectory& dir, const Teuchos::ParameterList& params, const MeshSize* meshSize,
                      const Comm& comm) {
  // The steps written: every k-th and the last.
  const double steps = std::ceil(static_cast<double>(Input::loadStepTimes(params).size()) / Input::stepStride(params));
  const double perStep = outputBytesPerStep(params, meshSize), needed = steps * perStep;
  std::string error;
  struct statvfs fs;
  if (comm.getRank() == 0 && ::statvfs(dir.path().c_str(), &fs) == 0) {
    const double free = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    if (0.5 * needed > free) {
      std::ostringstream os;
      os.precision(3);
      os << "the results of the " << static_cast<long long>(steps) << " steps "
         << (Input::stepStride(params) > 1 ? "written (Output/Step Stride) " : "") << "of \"Load Steps/Times\" need about " << needed / 1e9
         << " GB (" << perStep / 1e6 << " MB a step, within a factor of two), and the file system of " << dir.path()
         << " has " << free / 1e9
         << " GB free; write fewer steps, a coarser mesh, or into another Output/Directory";
      error = os.str();
    }
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError(error);
}

// Everything the run will write is checked before any work: the output
// directory (created, locked for this run, probed; no other result there
// that shares a file with this one; room for the whole history) and the
// files named on the command line.
std::unique_ptr<IO::OutputDirectory> prepareOutput(const Teuchos::ParameterList& params, const RunOptions& options,
                                                   const MeshSize* meshSize, const RCP<const Comm>& comm) {
  std::unique_ptr<IO::OutputDirectory> dir;
  if (params.sublist("Output").get<bool>("Write Results")) {
    dir = std::make_unique<IO::OutputDirectory>(outputDirectory(params, options), comm);
    requireNoNameClash(*dir, params.sublist("Output").get<std::string>("Base Name"), *comm);
    requireDiskSpace(*dir, params, meshSize, *comm);
  }
  if (!options.summaryFile.empty()) IO::requireWritableFile(options.summaryFile, "--summary", comm);
  if (!options.exportFclib.empty()) IO::requireWritableFile(options.exportFclib, "--export-fclib", comm);
  return dir;
}

// What the writing of a load history carries from step to step: the rows
// not yet written (a restart's kept rows first), and whether this run has
// committed a step (after that the texts that grow are appended to).
struct StepOutput {
  IO::IterationHistory history;  // the rows not written yet
  std::string stepLines;         // the steps table's lines not written yet
  bool committed = false;
};

// Step "write": load step `step` of the run as the next step of the result
// series (Tribos_StepSeries.hpp): one run of one step writes Base Name .h5
// (with the verdict as root attributes) and .xmf as always, a history
// BASE.step0001.h5, ... and an .xmf that plays them in time; with them, as
// one set, .parameters.xml (the effective parameters, defaults filled and
// the directory the run wrote to: the run again; written at the run's first
// step), .history.csv (one row per outer iteration of every step so far,
// Tribos_History.hpp, appended step by step), .steps.jsonl (one row per
// step with its data file's digest, appended) and .json (the summary of the
// steps so far, written last: a set without it is incomplete).
void writeStep(const Teuchos::ParameterList& params, const IO::OutputDirectory& outputDir, IO::StepSeries& series,
               int step, double time, const Discretized& d, const StepSolution& sol, const FrictionMemory& memory,
               StepOutput& output, RunReport& report, const RCP<const Comm>& comm) {
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::output"));
  Progress::stage("writing results");
  const auto& disc = d.disc;
  const std::string& dir = outputDir.path();
  const ResultNames names(params.sublist("Output").get<std::string>("Base Name"));
  report.output = dir + "/" + names.xmf;
  report.parameters = dir + "/" + names.parameters;
  report.historyFile = dir + "/" + names.history;
  report.stepsFile = names.steps;
  IO::StepResult result;
  if (params.sublist("Contact").get<bool>("Enabled"))
    result.pointSets.push_back(contactPointSet(disc, sol.result.contact, memory, *comm));
  result.attributes.numbers = {{"converged", report.converged ? 1.0 : 0.0},
                               {"solver_converged", report.solverConverged ? 1.0 : 0.0}};
  result.attributes.text = {{"problem", report.problem}, {"stop_reason", report.stopReason}};
  // A Dynamics step's running sums, which a restart continues from: to the
  // bit (the steps table has 10 digits) and under the file's digest.
  if (sol.dynamics) {
    result.attributes.numbers.push_back({"external_work", sol.dynamics->externalWork});
    result.attributes.numbers.push_back({"friction_dissipation", sol.dynamics->frictionDissipation});
  }
  IO::Field reaction{"reaction", 3, {}};
  for (int n : disc.ownedNodes()) {
    const double* un = sol.result.u.at(disc.meshNode(n));
    result.uOwned.insert(result.uOwned.end(), un, un + 3);
    if (sol.result.reaction.empty()) continue;
    const double* rn = sol.result.reaction.at(disc.meshNode(n));
    reaction.values.insert(reaction.values.end(), rn, rn + 3);
  }
  if (!sol.result.reaction.empty()) result.nodeFields.push_back(reaction);
  if (!sol.velocity.empty()) {
    IO::Field velocity{"velocity", 3, {}};
    for (int n : disc.ownedNodes()) {
      const double* vn = sol.velocity.at(disc.meshNode(n));
      velocity.values.insert(velocity.values.end(), vn, vn + 3);
    }
    result.nodeFields.push_back(velocity);
  }
  result.cellFields = cellFields(disc, d.materials, sol.result.u);
  const bool first = !output.committed;
  series.writeStep(step, time, disc, result, [&](const IO::StepFile& file) {
    std::vector<IO::TextFile> texts;
    if (first) {
      Teuchos::ParameterList effective = params;
      effective.sublist("Output").set("Directory", dir);
      texts.push_back({names.parameters, Input::toXml(effective)});
    }
    texts.push_back({names.history, (first ? IO::IterationHistory::csvHeader() : "") + output.history.csvRows(), true});
    texts.push_back({names.steps, output.stepLines + stepRow(*report.lastStep, file.name, file.sha256).toJsonLine() + "\n", true});
    texts.push_back({names.summary, report.toSummary().toJson() + "\n"});
    return texts;
  });
  output.history.rows.clear();
  output.stepLines.clear();
  output.committed = true;
}

// The mesh of Mesh/File, read on rank 0 (and held there only) and checked
// before any work: the
// faces the input names exist (the message lists the file's names), the
// contact face is planar, there are enough cells for the subdomains. The
// read may use the run's memory limit (maxMemory, --max-memory, at most the
// machine's available memory): a .geo is meshed by a Gmsh process limited
// to it, a file larger than it is refused. A refusal is the same
// CollectiveError on every rank (exit 1).
Mesh::Mesh readMeshFile(const Teuchos::ParameterList& params, const Mesh::DecompositionSpec& decomposition,
                        double maxMemory, const Comm& comm) {
  Mesh::Mesh mesh;
  std::vector<std::string> warnings;
  // A stop signal reaches every rank: the others give rank 0 the time to end
  // the Gmsh child of a .geo and remove its directory before mpirun, once a
  // rank has died, kills rank 0 by SIGKILL.
  std::optional<SignalGrace> grace;
  if (comm.getRank() != 0 && Mesh::isGeoScript(Input::meshFile(params))) grace.emplace(Mesh::kGeoSignalGraceSeconds);
  checkOnEveryRank(comm, [&] {
    if (comm.getRank() == 0) {
      mesh = Input::mesh(params, &warnings, memoryLimit(maxMemory));
      Input::checkMeshFaces(mesh, params);
      Input::checkBondedVelocities(mesh, params);  // (the box is one body)
      const auto& contact = params.sublist("Contact");
      if (contact.get<bool>("Enabled") && contact.sublist("Pairs").numParams() == 0)
        Contact::faceNormal(mesh, contact.get<std::string>("Face"));
      // S = 0: sized by Subdomain Size from the mesh, at least one per
      // body and at most one per cell.
      const int S = requestedSubdomains(decomposition);
      TRIBOS_REQUIRE(S <= mesh.numCells(), "Mesh asks for " << S << " subdomains but mesh file \""
                                                            << Input::meshFile(params) << "\" has " << mesh.numCells()
                                                            << " cells");
      // METIS cuts each body on its own (partitionMetisByBody).
      TRIBOS_REQUIRE(S == 0 || S >= mesh.numBodies(),
                     "Mesh asks for " << S << " subdomain(s) but mesh file \"" << Input::meshFile(params) << "\" has "
                                      << mesh.numBodies() << " bodies, each of which needs at least one of its own "
                                      << "(Mesh/Subdomains, or Mesh/Subdomain Size)");
    }
  });
  for (const auto& w : warnings) std::cerr << "tribos: warning: " << w << std::endl;
  return mesh;
}

// Everything the whole mesh decides, checked on rank 0 (which alone holds
// it) before any work; a refusal is the same CollectiveError on every rank
// (exit 1):
//  - the problem's scales (Input::checkScales);
//  - Dirichlet conditions that disagree at a node;
//  - a monolithic solve of a body they do not hold; bodies that nothing
//    holds (Contact::requireEveryBodyHeld), named with the pairs on them;
//  - the contact constraints of the run's pairs (node-to-segment search on
//    the whole mesh): a pair the mesh cannot make (no partner for any slave
//    node, a node in two pairs), prescribed sliding against friction.
// Slave nodes left out are warned of. Returns the constraints on rank 0.
// Rank 0's search figures (the left-out nodes and the counts of each pair)
// on every rank: each checks the left-out nodes it holds, and the summary
// is the same on every rank.
void broadcastSearch(Contact::ContactSearch& search, const Comm& comm) {
  ByteBuffer buffer;
  if (comm.getRank() == 0) {
    buffer.put(search.leftOut);
    buffer.put(static_cast<long long>(search.pairs.size()));
    for (const auto& p : search.pairs) {
      buffer.put(p.name), buffer.put(p.master), buffer.put(p.planeNormal), buffer.put(p.searchDistance);
      buffer.put(p.automatic), buffer.put(p.slaveNodes), buffer.put(p.rows), buffer.put(p.leftOut);
      buffer.put(p.nodeToSegment);
    }
  }
  broadcastBuffer(buffer, 0, comm);
  if (comm.getRank() == 0) return;
  buffer.read(search.leftOut);
  search.pairs.resize(static_cast<size_t>(buffer.get<long long>()));
  for (auto& p : search.pairs) {
    buffer.read(p.name), buffer.read(p.master), buffer.read(p.planeNormal), buffer.read(p.searchDistance);
    buffer.read(p.automatic), buffer.read(p.slaveNodes), buffer.read(p.rows), buffer.read(p.leftOut);
    buffer.read(p.nodeToSegment);
  }
}

std::vector<Feti::ContactConstraint> validateOnRoot(const Teuchos::ParameterList& params, const Mesh::Mesh* whole,
                                                    const Fem::LoadCase& loads, Input::Method method, const Comm& comm,
                                                    Contact::ContactSearch& search) {
  std::vector<Feti::ContactConstraint> constraints;
  checkOnEveryRank(comm, [&] {
    if (comm.getRank() == 0) {
      Input::checkScales(params, *whole);
      const auto dirichlet = Fem::constrainedDofs(*whole, loads.dirichlet);
      if (method == Input::Method::Monolithic)
        Fem::requireRigidMotionsHeld(whole->coords, dirichlet, "Solver/Type = Monolithic",
                                     "a body that Dirichlet conditions do not hold has no unique displacement; hold "
                                     "it, or use Solver/Type = FETI, which finds the equilibrium of a floating body");
      // In a Dynamics run the mass holds every body.
      const bool dynamics = method == Input::Method::FetiDynamics;
      if (Input::fetiContact(params)) {
        Progress::stage("contact search");
        const auto pairs = Input::contactPairs(params, *whole);
        try {
          constraints = Contact::contactConstraints(*whole, pairs, search);
        } catch (const Error& e) {
          throw Error(std::string("Contact: ") + e.what());
        }
        if (!dynamics) Contact::requireEveryBodyHeld(*whole, dirichlet, pairs, Input::pairFriction(params), constraints);
        // Before the FETI setup: no prescribed sliding against friction.
        Contact::requireNoPrescribedSlip(constraints, Input::pairFriction(params), dirichlet,
                                         [&](int node) { return whole->coords.at(node); });
      } else if (method != Input::Method::Semismooth && !dynamics) {
        Contact::requireEveryBodyHeld(*whole, dirichlet, {}, {}, {});
      }
    }
  });
  for (const auto& n : search.notes) std::cerr << "tribos: warning: " << n << std::endl;
  if (Input::fetiContact(params)) broadcastSearch(search, comm);
  return constraints;
}

// Step "read": the mesh file, when there is one, read and checked on rank 0
// before any work (the memory estimate needs its size); the decomposition
// sized from it. The box is generated in the mesh step.
std::unique_ptr<Mesh::Mesh> readStep(const Teuchos::ParameterList& params, const RunOptions& options,
                                     Mesh::DecompositionSpec& decomposition, MeshSize& fileSize, const Comm& comm) {
  decomposition = decompositionFor(params, comm.getSize());
  if (Input::meshFile(params).empty()) return nullptr;
  Progress::stage("reading the mesh");
  auto whole = std::make_unique<Mesh::Mesh>(readMeshFile(params, decomposition, options.maxMemory, comm));
  double counts[4] = {double(whole->numNodes()), double(whole->numCells()), double(whole->numBodies()),
                       std::ceil(double(whole->connectivity.size()) / std::max(whole->numCells(), 1))};
  Teuchos::broadcast(comm, 0, 4, counts);
  fileSize = {counts[0], counts[1], static_cast<int>(counts[2]), static_cast<int>(counts[3])};
  decomposition = decompositionFor(params, comm.getSize(), &fileSize);
  return whole;
}

// The cell types of the whole mesh from every rank's part: "Tet10", or
// "Tet4, Tet10" for bodies of different types.
std::string cellTypeNames(const Mesh::Mesh& part, const Comm& comm) {
  constexpr int kTypes = 4;  // Mesh::CellType's values
  int mine[kTypes] = {0, 0, 0, 0}, all[kTypes];
  for (Mesh::CellType t : part.cellTypesPresent()) mine[static_cast<int>(t)] = 1;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, kTypes, mine, all);
  std::string names;
  for (int t = 0; t < kTypes; ++t)
    if (all[t]) names += (names.empty() ? "" : ", ") + Mesh::cellTypeName(static_cast<Mesh::CellType>(t));
  return names;
}

// Step "mesh": the box generated (rank 0), the whole mesh checked against the
// problem (validateOnRoot), cut into the ranks' parts with their contact
// constraints, and the materials of this rank's part.
Discretized meshStep(const Teuchos::ParameterList& params, const RunOptions& options, std::unique_ptr<Mesh::Mesh> whole,
                     const Mesh::DecompositionSpec& decomposition, const Comm& comm, RunReport& report) {
  Progress::stage("mesh and decomposition");
  const bool fromFile = whole != nullptr;
  const Input::Method method = Input::method(params);
  if (!fromFile) {
    whole = std::make_unique<Mesh::Mesh>();
    if (comm.getRank() == 0) *whole = Mesh::generateBox(Input::boxSpec(params));
    // The box's names were validated with the input.
    checkOnEveryRank(comm, [&] { if (comm.getRank() == 0) Input::checkMeshFaces(*whole, params); });
  }
  // A mesh from a file is described by its bounding box where a BoxSpec is
  // asked for (one structured subdomain, e.g. the FCLIB export's); root's
  // goes with every part.
  const auto spec = fromFile ? (comm.getRank() == 0 ? Mesh::boundingBox(*whole) : Mesh::BoxSpec())
                             : Input::boxSpec(params);
  auto loads = Input::loadCase(params);
  Contact::ContactSearch search;
  auto rootConstraints = validateOnRoot(params, whole.get(), loads, method, comm, search);
  auto disc = Mesh::Discretization::scatter(*whole, spec, decomposition, comm);
  auto constraints = Input::fetiContact(params)
                         ? Feti::scatterContactConstraints(rootConstraints, disc, comm)
                         : std::vector<Feti::ContactConstraint>();
  std::vector<Feti::ContactConstraint>().swap(rootConstraints);
  if (method == Input::Method::Semismooth)
    Mesh::broadcastMesh(*whole, comm);
  else if (options.exportFclib.empty() || comm.getRank() != 0)
    whole = std::make_unique<Mesh::Mesh>();
  auto materials = Input::materials(params, disc.part);
  Discretized d{std::move(whole), std::move(disc), std::move(materials), std::move(loads), std::move(constraints),
                 std::move(search)};
  report.contactSearch = d.search.pairs;
  report.algorithm = solveMethodName(method);
  report.ranks = comm.getSize();
  report.subdomains = d.disc.numSubdomains();
  report.subdomainSize = decomposition.size;
  report.element = cellTypeNames(d.disc.part, comm);
  if (fromFile) report.meshFile = Input::meshFile(params);
  report.nodes = d.disc.numMeshNodes();
  report.cells = d.disc.numMeshCells();
  return d;
}

// The names of the run's contact pairs in the order of their numbers
// (ContactConstraint::pair): Contact/Pairs in order, or the one face.
std::vector<std::string> pairNames(const Teuchos::ParameterList& params) {
  const auto& contact = params.sublist("Contact");
  if (!contact.get<bool>("Enabled")) return {};
  const auto& pairs = contact.sublist("Pairs");
  if (pairs.numParams() == 0) return {contact.get<std::string>("Face")};
  std::vector<std::string> names;
  for (auto it = pairs.begin(); it != pairs.end(); ++it) names.push_back(pairs.name(it));
  return names;
}

// The input's Dirichlet conditions as the reactions are reported: each
// dof of the supports counted once, for the first condition (in the order
// of Boundary Conditions/Dirichlet) that fixes it, so that the resultants
// of all conditions sum to the whole reaction. Built once for the run.
class SupportGroups {
 public:
  SupportGroups(const Teuchos::ParameterList& params, const Mesh::Discretization& disc,
                const std::vector<Fem::DirichletCondition>& conditions)
      : disc_(disc) {
    const auto& items = params.sublist("Boundary Conditions").sublist("Dirichlet");
    for (auto it = items.begin(); it != items.end(); ++it) names_.push_back(items.name(it));
    TRIBOS_REQUIRE(names_.size() == conditions.size(), "SupportGroups: " << names_.size() << " names for "
                                                                         << conditions.size() << " conditions");
    condition_.assign(3 * static_cast<size_t>(disc.part.numNodes()), -1);
    for (size_t i = 0; i < conditions.size(); ++i) {
      faces_.push_back(conditions[i].face);
      for (int n : disc.part.faceNodes(conditions[i].face))
        for (int c = 0; c < 3; ++c)
          if (conditions[i].fix[c] && condition_[3 * n + c] < 0) condition_[3 * n + c] = static_cast<int>(i);
    }
  }
  // The resultant of reaction (on a layout holding the rank's owned nodes)
  // over each condition, summed over the ranks. Collective.
  std::vector<ReactionReport> resultants(const Fem::NodalVector& reaction, const Comm& comm) const {
    const size_t count = names_.size();
    std::vector<double> local(3 * count, 0.0), global(local.size(), 0.0);
    if (!reaction.empty())
      for (int n : disc_.ownedNodes())
        for (int c = 0; c < 3; ++c)
          if (condition_[3 * n + c] >= 0) local[3 * condition_[3 * n + c] + c] += reaction.at(disc_.meshNode(n))[c];
    if (count > 0) Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(3 * count), local.data(), global.data());
    std::vector<ReactionReport> out(count);
    for (size_t i = 0; i < count; ++i) out[i] = {names_[i], faces_[i], {global[3 * i], global[3 * i + 1], global[3 * i + 2]}};
    return out;
  }

 private:
  const Mesh::Discretization& disc_;
  std::vector<std::string> names_, faces_;
  std::vector<int> condition_;  // 3 per part node: the condition its dof is reported under, -1 for none
};

// The summary row of a checked load step (report holds its verdict; memory
// has the step added).
StepReport stepReport(const Teuchos::ParameterList& params, int step, double time, const StepSolution& sol,
                      const SupportGroups& supports, const FrictionMemory& memory, const RunReport& report,
                      const Comm& comm) {
  StepReport s;
  s.step = step;
  s.time = time;
  s.dynamics = sol.dynamics;
  s.iterations = sol.result.iterations;
  s.n_A = sol.result.n_A;
  s.kkt = sol.result.kkt;
  if (report.outer) {
    s.outerAlgorithm = report.outer->name;
    s.handover = report.outer->handover;
    s.preconditioner = report.outer->preconditioner;
  }
  if (params.sublist("Contact").get<bool>("Enabled")) {
    const auto& c = sol.result.counts;
    s.contact = ContactCountReport{c.nodes, c.active, c.stick, c.slip};
    const auto names = pairNames(params);
    const int numPairs = static_cast<int>(names.size());
    const auto forces = Contact::pairForces(sol.result.contact, numPairs, comm);
    const auto motions = Contact::pairMotions(sol.result.contact, numPairs, comm);
    const auto energies = memory.pairEnergies(sol.result.contact, numPairs, comm);
    for (size_t p = 0; p < names.size(); ++p) s.pairs.push_back({names[p], forces[p], motions[p], energies[p]});
  }
  s.reactions = supports.resultants(sol.result.reaction, comm);
  s.converged = report.converged;
  s.stopReason = report.stopReason;
  s.solveSeconds = maxOver(sol.result.solveSeconds, comm);
  return s;
}

// The nodes an automatic search distance left out (Contact::ContactSearch)
// must have stayed out of contact: a lower bound of each one's gap after
// the step (Contact::leftOutMargin, with the largest displacement of its
// pair's master surface) must stay positive. Returns "" when it does, else
// why the step is not converged, naming the pair, the node and the
// distance to set. Collective (the left-out list is every rank's).
std::string leftOutCheck(const Discretized& d, const Fem::NodalVector& u, const Comm& comm) {
  const auto& leftOut = d.search.leftOut;
  if (leftOut.empty()) return "";
  const auto& pairs = d.search.pairs;
  // The largest displacement of each master surface, over the ranks.
  std::vector<double> motion(pairs.size(), 0.0), motionAll(pairs.size(), 0.0);
  for (size_t k = 0; k < pairs.size(); ++k)
    if (!pairs[k].master.empty())
      for (int n : d.disc.part.faceNodes(pairs[k].master)) {
        const double* v = u.at(d.disc.meshNode(n));
        motion[k] = std::max(motion[k], norm(Vec3{v[0], v[1], v[2]}));
      }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, static_cast<int>(motion.size()), motion.data(), motionAll.data());
  double worst = std::numeric_limits<double>::infinity();
  int worstIndex = -1;
  for (size_t i = 0; i < leftOut.size(); ++i) {
    const auto& n = leftOut[i];
    if (u.layout().index(n.node) < 0) continue;
    const double* v = u.at(n.node);
    const double margin = Contact::leftOutMargin(n, Vec3{v[0], v[1], v[2]}, pairs[n.pair].master.empty(),
                                                 pairs[n.pair].planeNormal, motionAll[n.pair]);
    if (margin < worst) worst = margin, worstIndex = static_cast<int>(i);
  }
  const double worstAll = -maxOver(-worst, comm);
  if (worstAll > 0) return "";
  int which = worst == worstAll ? worstIndex : -1, whichAll = -1;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, which, Teuchos::outArg(whichAll));
  const auto& n = leftOut[whichAll];
  const auto& pair = pairs[n.pair];
  std::ostringstream os;
  os << "contact pair '" << pair.name << "': slave node " << n.node << ", left out by the automatic search distance "
     << pair.searchDistance << " (its gap " << n.gap << "), may have come into contact: the displacements may have "
     << "closed its gap (margin " << worstAll << "); set Contact/Pairs/" << pair.name << "/Search Distance larger than "
     << n.gap << " (docs/contact.md)";
  return os.str();
}

// Step "check": the result must be representable, and `converged` is a
// promise about it: the solver stopped on its own test AND every KKT residual
// of the result (Contact::resultKKT) is within Result Check Factor times the
// requested tolerance. With --verify, the monolithic reference solve.
void checkStep(const Teuchos::ParameterList& params, const RunOptions& options, const Discretized& d,
               const Fem::LoadCase& loads, StepSolution& sol, const RCP<const Comm>& comm, RunReport& report) {
  const Input::Method method = Input::method(params);
  const Contact::SolveResult& r = sol.result;
  requireRepresentable(r.u, r.kkt,
                       method == Input::Method::Semismooth ? "the semismooth* method" : "the " + report.algorithm + " solve");
  // A solver that stopped before its first step still has a history: the
  // solve as one row, so that every result's file has a row to read.
  if (sol.history.rows.empty()) {
    IO::HistoryRow row;
    row.seconds = r.solveSeconds;
    sol.history.rows.push_back(row);
  }
  // The verdict of the method's result (Contact::resultVerdict, computed once).
  report.tolerance = r.tolerance;
  report.kkt = r.kkt;
  report.limit = r.verdict.limit;
  report.solverConverged = r.solverConverged;
  report.converged = r.verdict.converged;
  report.stopReason = r.verdict.stopReason;
  if (Input::fetiContact(params)) {
    const std::string leftOut = leftOutCheck(d, r.u, *comm);
    if (!leftOut.empty()) {
      report.converged = false;
      report.stopReason = leftOut;
    }
  }
  if (!options.verify) return;
  if (method == Input::Method::FetiContact || method == Input::Method::Semismooth) {
    report.verifyNote = "--verify compares with the monolithic linear solve; it does not apply to contact problems";
    return;
  }
  Progress::stage("monolithic reference solve (--verify)");
  Fem::MonolithicSystem reference(d.disc, d.materials, loads, comm);
  const auto ref = reference.solve(params.sublist("Solver").sublist("Monolithic"));
  // Both hold the nodes of the rank's part.
  Fem::NodalVector difference(r.u.layoutPtr());
  for (int node : difference.layout().nodes())
    for (int c = 0; c < 3; ++c) difference.at(node)[c] = ref.u.at(node)[c] - r.u.at(node)[c];
  report.verifyRelativeDifference = difference.norm2() / std::max(ref.u.norm2(), 1e-300);
}

// A restarted run (tribos --restart DIR, docs/load_history.md): what it
// continues from. The steps 1..completed of the run in DIR are done: their
// files, their rows of its steps table and history are kept as they are, and
// the next step starts from the state of the last of them.
struct Restart {
  bool dynamics = false;              // a Dynamics run: its state holds the velocity too
  std::string summaryFile;            // DIR/BASE.json: how many steps are complete
  std::string stepsFile;              // DIR/BASE.steps.jsonl: their rows
  int completed = 0;
  std::vector<IO::Summary> stepRows;  // the rows of steps 1..completed
  std::vector<bool> written;          // which of them wrote a data file (Output/Step Stride; the last did)
  std::string stepLines;              // the same, as the table's text
  IO::IterationHistory history;       // the history's rows of those steps
  long long iterationsTotal = 0, n_A_total = 0;  // the work of those steps (their rows' sums)
  ResumedStep last;                   // the last one's state, read from its file (after the mesh)
  // The last one's friction memory at this rank's contact nodes (after the mesh).
  std::vector<std::pair<int, FrictionMemory::Node>> contactMemory;
};

// The whole text of a file, or an error naming it.
std::string readText(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot read " + path + " (" + systemReason(errno) + ")";
    return "";
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The first `count` lines of a text (fewer when it has fewer complete lines).
std::vector<std::string> firstLines(const std::string& text, int count) {
  std::vector<std::string> lines;
  for (size_t at = 0; static_cast<int>(lines.size()) < count;) {
    const size_t end = text.find('\n', at);
    if (end == std::string::npos) break;  // a line a killed run left half written
    lines.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  return lines;
}

// Why `dir` cannot be the result directory of a restart ("" when it can):
// it must exist and be a directory, and hold the summary of Base Name.
std::string restartDirectoryError(const std::string& dir, const std::string& summaryFile, const std::string& base) {
  struct stat st;
  if (::stat(dir.c_str(), &st) != 0)
    return errno == ENOENT ? "the directory does not exist"
                           : "cannot access the directory (" + systemReason(errno) + ")";
  if (!S_ISDIR(st.st_mode)) return "it is not a directory (" + fileKind(st.st_mode) + ")";
  if (::stat(summaryFile.c_str(), &st) == 0) return "";
  const auto names = ResultNames(base).all();
  std::string ignored;
  bool resultFiles = false;
  for (const std::string& name : directoryEntries(dir, ignored))
    resultFiles = resultFiles || IO::StepSeries::isDataFileName(base, name) ||
                  std::find(names.begin(), names.end(), name) != names.end();
  return resultFiles ? "there is no summary " + summaryFile +
                           ": the run there completed no step (run the input again without --restart)"
                     : "it is not a result directory of Output/Base Name = " + base + ": it holds no " +
                           fileNameOf(summaryFile) + " and no other file of such a result";
}

// A value of a validated list in words, for a message.
std::string valueText(const Teuchos::ParameterEntry& entry) {
  std::ostringstream os;
  os.precision(15);
  os << entry.getAny(false);
  return os.str();
}

// The first entry (in the order of `here`, then the entries only `there`
// has) in which two validated lists differ, as a sentence; "" when they
// agree. `skip`: the full names of entries not compared.
std::string firstDifference(const Teuchos::ParameterList& here, const Teuchos::ParameterList& there,
                            const std::string& prefix, const std::vector<std::string>& skip) {
  const auto skipped = [&](const std::string& full) { return std::find(skip.begin(), skip.end(), full) != skip.end(); };
  for (auto it = here.begin(); it != here.end(); ++it) {
    const std::string& name = here.name(it);
    const std::string full = prefix + name;
    if (skipped(full)) continue;
    const auto& entry = here.entry(it);
    if (!there.isParameter(name)) return "\"" + full + "\" is " + valueText(entry) + " here and absent there";
    if (entry.isList() != there.isSublist(name)) return "\"" + full + "\" is a sublist in one and a value in the other";
    if (entry.isList()) {
      const std::string d = firstDifference(here.sublist(name), there.sublist(name), full + "/", skip);
      if (!d.empty()) return d;
    } else if (!(entry.getAny(false) == there.getEntry(name).getAny(false))) {
      return "\"" + full + "\" is " + valueText(entry) + " here and " + valueText(there.getEntry(name)) + " there";
    }
  }
  for (auto it = there.begin(); it != there.end(); ++it)
    if (!here.isParameter(there.name(it)) && !skipped(prefix + there.name(it)))
      return "\"" + prefix + there.name(it) + "\" is " + valueText(there.entry(it)) + " there and absent here";
  return "";
}

// The result in DIR that --restart continues, checked before the mesh is
// read: DIR is a directory that holds a result of this input (its
// parameters file, Output/Directory aside, holds the input's effective
// parameters; a Dynamics run's may end at another Dynamics/End Time, its
// steps at the same times: a run stopped early continues to this End Time)
// whose summary says steps 1..k of its Load Steps are complete,
// with steps left to do, written on as many ranks as this run has (the rows
// of a step file follow the ranks' ownership of the nodes); whose steps
// table has those k rows in order, at the input's times, each naming its
// step file and that file's digest, the last one converged; and a history
// whose rows read. Every rank reads the same texts (rank 0's), so that every
// refusal is the same CollectiveError on every rank. The step files
// themselves are checked once the directory is locked (readRestartState).
Restart readRestart(const Teuchos::ParameterList& params, const RunOptions& options, const std::vector<double>& times,
                    const Comm& comm) {
  const std::string dir = outputDirectory(params, options);
  const auto& output = params.sublist("Output");
  const std::string base = output.get<std::string>("Base Name");
  const ResultNames names(base);
  Restart restart;
  restart.summaryFile = dir + "/" + names.summary;
  restart.stepsFile = dir + "/" + names.steps;
  const std::string parametersFile = dir + "/" + names.parameters, historyFile = dir + "/" + names.history;
  if (!output.get<bool>("Write Results"))
    throw CollectiveError("--restart " + dir + ": Output/Write Results is false; a restart continues the result files");
  // Rank 0 reads, every rank checks the same texts.
  std::string error, summaryText, stepsText, historyText;
  if (comm.getRank() == 0) {
    error = restartDirectoryError(dir, restart.summaryFile, base);
    if (!error.empty()) error = "--restart " + dir + ": " + error;
    if (error.empty()) summaryText = readText(restart.summaryFile, error);
    if (error.empty()) stepsText = readText(restart.stepsFile, error);
    if (error.empty()) historyText = readText(historyFile, error);
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError(error);
  summaryText = broadcastFromRoot(comm, summaryText);
  stepsText = broadcastFromRoot(comm, stepsText);
  historyText = broadcastFromRoot(comm, historyText);

  // The same input: its parameters file read as an input is read.
  RCP<Teuchos::ParameterList> earlier;
  error.clear();
  try {
    earlier = Input::read(parametersFile, {});
  } catch (const std::exception& e) {
    error = e.what();
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError("--restart " + dir + ": " + error);
  const bool dynamics = restart.dynamics = Input::dynamics(params);
  std::vector<std::string> free{"Output/Directory"};
  if (dynamics) free.push_back("Dynamics/End Time");
  // Which steps get a file is the output's choice, not the run's: its rows
  // say which did.
  free.push_back("Output/Step Stride");
  const std::string difference = firstDifference(params, *earlier, "", free);
  if (!difference.empty())
    throw CollectiveError("--restart " + dir + ": the result there is not of this input: its parameters (" +
                          parametersFile + ") differ: " + difference);
  // Its steps are this run's first ones (the same times; a Dynamics run's
  // may be fewer or more), their files named as this run names them.
  const int numSteps = static_cast<int>(times.size());
  const int earlierSteps = static_cast<int>(Input::loadStepTimes(*earlier).size());
  const std::string ours = IO::StepSeries::dataFileName(base, numSteps, 1),
                    theirs = IO::StepSeries::dataFileName(base, earlierSteps, 1);
  if (ours != theirs)
    throw CollectiveError("--restart " + dir + ": the run there names its " + std::to_string(earlierSteps) +
                          " steps' files " + theirs + ", ..., this run of " + std::to_string(numSteps) + " steps " +
                          ours + ", ...: give a Dynamics/End Time whose steps' numbers have as many digits");

  // How many steps its summary says are complete.
  auto refuse = [&](const std::string& file, const std::string& why) {
    throw CollectiveError("--restart " + dir + ": " + file + ": " + why);
  };
  IO::Summary summary;
  try {
    summary = IO::Summary::fromJson(summaryText);
  } catch (const Error& e) {
    refuse(restart.summaryFile, std::string("not a summary of a run: ") + e.what());
  }
  if (summary.json("load_steps") != std::to_string(earlierSteps))
    refuse(restart.summaryFile, "it has load_steps " + summary.json("load_steps") + ", its parameters " +
                                    std::to_string(earlierSteps));
  if (summary.json("ranks") != std::to_string(comm.getSize()))
    refuse(restart.summaryFile, "the run ran on " + summary.json("ranks") +
                                    " ranks; restart it on as many (its step files' node rows follow them), not " +
                                    std::to_string(comm.getSize()));
  if (summary.json("steps_file") != "\"" + names.steps + "\"")
    refuse(restart.summaryFile, "it names no steps table " + names.steps + " (steps_file is " +
                                    (summary.json("steps_file").empty() ? "absent" : summary.json("steps_file")) + ")");
  const std::string completed = summary.json("steps_completed");
  char* end = nullptr;
  const long k = std::strtol(completed.c_str(), &end, 10);
  if (completed.empty() || *end != '\0' || k < 0 || k > earlierSteps)
    refuse(restart.summaryFile, "steps_completed is not a step count of its " + std::to_string(earlierSteps) + " steps");
  restart.completed = static_cast<int>(k);
  if (restart.completed == 0) refuse(restart.summaryFile, "it lists no complete step (run the input again without --restart)");
  if (restart.completed >= numSteps)
    refuse(restart.summaryFile,
           (restart.completed == numSteps ? "it lists all " + std::to_string(numSteps) + " steps"
                                          : "it lists " + completed + " steps, this input has " + std::to_string(numSteps)) +
               ": the run is complete, nothing is left to do" +
               (dynamics ? " (a later Dynamics/End Time continues it)" : ""));

  // Their rows: a killed run may have appended the row of the next step, or
  // part of it, before its summary said so.
  const auto lines = firstLines(stepsText, restart.completed);
  if (static_cast<int>(lines.size()) < restart.completed)
    refuse(restart.stepsFile, "it has " + std::to_string(lines.size()) + " complete rows; " + restart.summaryFile +
                                  " says " + std::to_string(restart.completed) + " steps are complete");
  for (int i = 0; i < restart.completed; ++i) {
    const std::string step = std::to_string(i + 1);
    IO::Summary row;
    try {
      row = IO::Summary::fromJson(lines[i]);
    } catch (const Error& e) {
      refuse(restart.stepsFile, "row " + step + " is not a step's row: " + e.what());
    }
    const double time = std::strtod(row.json("time").c_str(), nullptr);
    // The table writes 10 significant digits.
    if (row.json("step") != step || !(std::abs(time - times[i]) <= 1e-9 * std::abs(times[i])))
      refuse(restart.stepsFile, "its row " + step + " is not step " + step + " at t = " + row.json("time") +
                                    " of Load Steps/Times");
    const std::string file = "\"" + IO::StepSeries::dataFileName(base, numSteps, i + 1) + "\"";
    const std::string sha = row.json("sha256");
    // A step between two written ones (Output/Step Stride) has no file; the
    // last complete step has one, the state the run continues from.
    const bool unwritten = row.json("file").empty() && sha.empty() && i + 1 < restart.completed;
    if (!unwritten && (row.json("file") != file || sha.size() != 66 || sha.find_first_not_of("0123456789abcdef", 1) != 65))
      refuse(restart.stepsFile, "its row " + step + " does not name the file " + file + " with its SHA-256 digest");
    restart.written.push_back(!unwritten);
    restart.stepRows.push_back(row);
    restart.stepLines += lines[i] + "\n";
    restart.iterationsTotal += std::strtoll(row.json("iterations").c_str(), nullptr, 10);
    restart.n_A_total += std::strtoll(row.json("n_A").c_str(), nullptr, 10);
  }
  if (restart.stepRows.back().json("converged") != "true")
    refuse(restart.stepsFile, "its last step " + std::to_string(restart.completed) + " did not converge (" +
                                  restart.stepRows.back().json("stop_reason") +
                                  "): the run stopped there and would stop there again");

  // Their history rows; a run killed while it committed a step may have
  // appended the history of the next step before the summary said so.
  try {
    for (const IO::HistoryRow& row : IO::IterationHistory::fromCsv(historyText).rows)
      if (row.step <= restart.completed) restart.history.rows.push_back(row);
  } catch (const Error& e) {
    throw CollectiveError("--restart " + dir + ": " + historyFile + ": " + e.what());
  }
  return restart;
}

// Each step file the restart continues from is the file its step wrote:
// there, and with the SHA-256 digest the steps table recorded when the step
// was written (a file replaced, truncated or edited since is refused). Rank 0
// reads them; the verdict is the same on every rank.
void verifyStepFiles(const Restart& restart, const IO::StepSeries& series, const IO::OutputDirectory& dir,
                     const Comm& comm) {
  std::string error;
  if (comm.getRank() == 0)
    for (int k = 1; k <= restart.completed && error.empty(); ++k) {
      if (!restart.written[k - 1]) continue;
      Progress::stage("checking step file " + std::to_string(k) + " of " + std::to_string(restart.completed));
      struct stat st;
      const std::string file = dir.path() + "/" + series.dataFileName(k);
      const std::string recorded = restart.stepRows[k - 1].json("sha256");
      if (::stat(file.c_str(), &st) != 0) {
        error = file + " is missing, though " + restart.summaryFile + " lists its step " + std::to_string(k);
        continue;
      }
      const std::string digest = IO::sha256OfFile(file, error);
      if (error.empty() && "\"" + digest + "\"" != recorded)
        error = file + " is not the file step " + std::to_string(k) + " wrote: its SHA-256 is " + digest + ", " +
                restart.stepsFile + " records " + recorded + " (the file was replaced or changed since)";
    }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError("--restart " + dir.path() + ": " + error);
}

// The friction memory of the contact nodes `nodes` (this rank's, mesh
// nodes) in the step file `file`: the rows of /points/contact whose `node`
// (the node's row in /nodes) is theirs, read whole by every rank (a
// surface's nodes). Collective; throws Tribos::Error naming the file.
std::vector<std::pair<int, FrictionMemory::Node>> readFrictionMemory(const std::string& file,
                                                                    const std::vector<int>& nodes,
                                                                    const Mesh::Discretization& disc,
                                                                    const Comm& comm) {
  // The rows of this rank's contact nodes, asked of their owners (collective).
  const auto rows = disc.askOwners(nodes, 1, [&](int n, double* out) { out[0] = static_cast<double>(disc.nodeIndex()[n]); },
                                   comm);
  std::map<long long, FrictionMemory::Node> byRow;
  std::string error;
  try {
    const long long count = IO::readDatasetRows(file, "/points/contact/node", 0, 0).rows;
    const auto node = IO::readDatasetRows(file, "/points/contact/node", 0, count);
    const auto energy = IO::readDatasetRows(file, "/points/contact/dissipated_energy", 0, count);
    const auto amplitude = IO::readDatasetRows(file, "/points/contact/slip_amplitude", 0, count);
    if (node.columns != 1 || energy.columns != 1 || amplitude.columns != 1 || energy.rows != count ||
        amplitude.rows != count)
      throw Error(file + ": /points/contact/node, dissipated_energy and slip_amplitude are not one value per contact node");
    for (long long i = 0; i < count; ++i) byRow[std::llround(node.values[i])] = {energy.values[i], amplitude.values[i]};
  } catch (const Error& e) {
    error = e.what();
  }
  // A node of the constraints that the file has no row of took no part in
  // the solve (the file is the one its step wrote: verifyStepFiles).
  std::vector<std::pair<int, FrictionMemory::Node>> out;
  for (size_t i = 0; i < nodes.size() && error.empty(); ++i) {
    const auto it = byRow.find(std::llround(rows[i]));
    if (it == byRow.end()) continue;
    if (!std::isfinite(it->second.dissipatedEnergy) || !std::isfinite(it->second.slipAmplitude))
      error = file + ": /points/contact/dissipated_energy or slip_amplitude holds values that are not finite";
    else out.emplace_back(nodes[i], it->second);
  }
  if (!error.empty()) throw Error(error);
  return out;
}

// Rows [first, first + count) of a step file's node field /nodes/NAME, 3
// values per node, finite; throws Tribos::Error naming the file.
std::vector<double> readNodeRows(const std::string& file, const std::string& name, long long first, long long count,
                                 const Mesh::Discretization& disc) {
  const std::string dataset = "/nodes/" + name;
  const auto rows = IO::readDatasetRows(file, dataset, first, count);
  if (rows.columns != 3 || rows.rows != disc.numMeshNodes()) throw Error(file + ": " + dataset + " is not one row of 3 per node");
  if (!allFinite(rows.values)) throw Error(file + ": " + dataset + " holds values that are not finite");
  return rows.values;
}

// A finite number attribute of a step file's root group; throws
// Tribos::Error naming the file.
double finiteRootNumber(const std::string& file, const std::string& name) {
  const double value = IO::readRootNumber(file, name);
  if (!std::isfinite(value)) throw Error(file + ": the root attribute " + name + " is not finite");
  return value;
}

// The state of the last step the restart continues from, after checking
// every step file (verifyStepFiles) and that the last one holds this mesh
// (as many nodes, each at the place this run has it): its displacement (a
// Dynamics run's velocity, work of the loads and friction dissipation too),
// each rank reading the rows of the nodes it owns from its step file (rows
// in the rank-contiguous numbering, Discretization::nodeIndex), and the
// friction memory of the rank's contact nodes (`constraints`, glued ones
// aside). A refusal is the same CollectiveError on every rank.
void readRestartState(Restart& restart, const IO::StepSeries& series, const IO::OutputDirectory& dir,
                      const Mesh::Discretization& disc, const std::vector<Feti::ContactConstraint>& constraints,
                      const Comm& comm) {
  verifyStepFiles(restart, series, dir, comm);
  std::string error;
  const std::string file = dir.path() + "/" + series.dataFileName(restart.completed);
  const auto& owned = disc.ownedNodes();
  const long long count = static_cast<long long>(owned.size());
  const long long first = owned.empty() ? 0 : disc.nodeIndex()[owned.front()];
  try {
    const auto geometry = IO::readDatasetRows(file, "/mesh/geometry", 0, 0);
    if (geometry.rows != disc.numMeshNodes() || geometry.columns != 3) {
      std::ostringstream os;
      os << file << " holds " << geometry.rows << " nodes, the mesh of this input " << disc.numMeshNodes();
      throw Error(os.str());
    }
    const auto xyz = IO::readDatasetRows(file, "/mesh/geometry", first, count);
    double scale = 0;
    for (int n : owned)
      for (int c = 0; c < 3; ++c) scale = std::max(scale, std::abs(disc.part.coords[n][c]));
    for (long long i = 0; i < count; ++i) {
      const auto& x = disc.part.coords[owned[i]];
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(xyz.values[3 * i + c] - x[c]) <= 1e-12 * scale)) {
          std::ostringstream os;
          os.precision(15);
          os << file << ": node row " << first + i << " lies at (" << xyz.values[3 * i] << ", " << xyz.values[3 * i + 1]
             << ", " << xyz.values[3 * i + 2] << "), in this run's mesh at (" << x[0] << ", " << x[1] << ", " << x[2]
             << "): not the mesh of this input";
          throw Error(os.str());
        }
    }
    restart.last.uOwned = readNodeRows(file, "displacement", first, count, disc);
    if (restart.dynamics) {
      // The rest of a Dynamics step's state (ImplicitDynamics::resumeFrom),
      // its running sums as the step file holds them: to the bit, under the
      // file's digest.
      restart.last.vOwned = readNodeRows(file, "velocity", first, count, disc);
      restart.last.externalWork = finiteRootNumber(file, "external_work");
      restart.last.frictionDissipation = finiteRootNumber(file, "friction_dissipation");
    }
  } catch (const Error& e) {
    error = e.what();
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError("--restart " + dir.path() + ": " + error);
  // Every rank of a contact run asks (askOwners is collective), with or
  // without contact nodes of its own.
  int contactHere = !constraints.empty(), contact = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, contactHere, Teuchos::outArg(contact));
  if (!contact) return;
  std::vector<int> nodes;
  for (const auto& c : constraints)
    if (!c.glued) nodes.push_back(c.node);
  try {
    restart.contactMemory = readFrictionMemory(file, nodes, disc, comm);
  } catch (const Error& e) {
    error = e.what();
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError("--restart " + dir.path() + ": " + error);
}

// A step that took far more work than a well-conditioned dual problem
// needs (slowConvergence): counted in the summary, said on stderr at the
// first one, with the parameter to change. How hard the dual problem is
// depends on the decomposition in ways its sizes do not predict
// (docs/scaling.md: Cattaneo-Mindlin Level 3 took 10x as long on parts of
// 6^3 nodes as on 5^3 or 7^3). A restart counts its own steps only.
void noteSlowStep(int step, RunReport& report, const Comm& comm) {
  if (!slowConvergence(report.lastStep->iterations, report.lastStep->n_A, report.dualDofs)) return;
  if (report.slow) {
    ++report.slow->steps;
    return;
  }
  SlowConvergenceReport slow;
  slow.firstStep = step;
  slow.n_A = report.lastStep->n_A;
  slow.iterations = report.lastStep->iterations;
  slow.dualDofs = report.dualDofs;
  slow.steps = 1;
  std::ostringstream advice;
  advice << "the dual problem converged slowly: on " << report.subdomains << " subdomains (";
  if (report.subdomainSize > 0) {
    advice << "Mesh/Subdomain Size = " << report.subdomainSize << ") another size can be several times faster: try ";
    std::vector<int> others;
    for (int H : {4, 5, 6, 8})
      if (H != report.subdomainSize) others.push_back(H);
    advice << others[0] << ", " << others[1] << " or " << others[2];
  } else {
    advice << "the input's Subdomain Grid or Subdomains) another decomposition can be several times faster: try "
              "Mesh/Subdomain Size = Auto, 5, 6 or 8";
  }
  advice << " (docs/scaling.md); a tolerance tighter than the default costs iterations too";
  slow.advice = advice.str();
  if (comm.getRank() == 0)
    std::cerr << "tribos: warning: load step " << step << ": " << slow.iterations << " iterations and " << slow.n_A
              << " applications of F for a dual problem of " << slow.dualDofs << " unknowns: " << slow.advice
              << std::endl;
  report.slow = slow;
}

// A step that Auto's Newton solve handed to Algorithm 2: counted in the
// summary with the first step's reason (each step's row says its own).
void noteHandover(int step, RunReport& report) {
  if (!report.lastStep || report.lastStep->handover.empty()) return;
  if (!report.handover) report.handover = HandoverReport{step, 0, report.lastStep->handover};
  ++report.handover->steps;
}

}  // namespace

void checkRunnable(const Teuchos::ParameterList& params, const RunOptions& options, int numRanks) {
  // Paths from the command line and the mesh path made absolute (from the
  // working directory) end up in BASE.parameters.xml and the summary: held
  // to the text an input file may hold (IO::checkText), refused otherwise.
  for (const auto& [what, path] : {std::pair<std::string, std::string>{"--output", options.outputDir},
                                   {"--summary", options.summaryFile},
                                   {"--export-fclib", options.exportFclib},
                                   {"Mesh/File", Input::meshFile(params)}})
    IO::checkText(path, what + " \"" + IO::visibleText(path) + "\"");
  const auto decomposition = decompositionFor(params, numRanks);
  const int S = requestedSubdomains(decomposition);
  // S = 0: a mesh file sized by Subdomain Size, at least one subdomain per rank.
  TRIBOS_REQUIRE(S >= numRanks || S == 0, "the run has " << numRanks << " MPI ranks but Mesh asks for " << S
                                               << " subdomains; use at most as many ranks as subdomains (Mesh/"
                                               << (decomposition.partitioner == "METIS" ? "Subdomains" : "Subdomain Grid") << ")");
  const auto spec = Input::boxSpec(params);
  if (decomposition.partitioner == "Structured")
    for (int a = 0; a < 3; ++a)
      TRIBOS_REQUIRE(spec.cells[a] % decomposition.grid[a] == 0,
                     "Mesh/Subdomain Grid: " << decomposition.grid[a] << " boxes along " << "xyz"[a]
                                             << " do not divide the " << spec.cells[a] << " cells of the mesh");
  if (!options.exportFclib.empty() && Input::method(params) == Input::Method::FetiContact) {
    // FCLIB has one coefficient per contact and no bonded contact: one
    // friction for all pairs, none glued.
    const auto& pairs = params.sublist("Contact").sublist("Pairs");
    const auto friction = Input::pairFriction(params);
    for (auto it = pairs.begin(); it != pairs.end(); ++it)
      TRIBOS_REQUIRE(pairs.sublist(pairs.name(it)).get<std::string>("Type") != "Glued",
                     "--export-fclib: Contact/Pairs/" << pairs.name(it) << " is glued; FCLIB problems have contacts only");
    for (const auto& f : friction)
      TRIBOS_REQUIRE(f.law == friction[0].law && f.coefficient == friction[0].coefficient,
                     "--export-fclib: the contact pairs differ in friction; the export takes one law and coefficient");
  }
  // A contact-stabilized step depends on u_n, v_n and the loads, which a step
  // file gives; a Newmark step on M a_n and the contact forces of t_n too.
  TRIBOS_REQUIRE(!Input::dynamics(params) || options.restartDir.empty() ||
                     Input::dynamicsSpec(params).scheme == Contact::TimeScheme::ContactStabilizedNewmark,
                 "--restart: \"Dynamics/Scheme\" = "
                     << Contact::timeSchemeName(Input::dynamicsSpec(params).scheme)
                     << " continues from M a_n and the contact forces at t_n, which its step files do not hold (they "
                        "hold u, v and the contact forces averaged over the step); a run of Contact-Stabilized Newmark "
                        "restarts");
  TRIBOS_REQUIRE(!Input::dynamics(params) || !options.verify,
                 "--verify compares with the monolithic static solve; a Dynamics run has none");
  TRIBOS_REQUIRE(options.exportFclib.empty() || !Input::dynamics(params),
                 "--export-fclib writes one static contact problem; this run is a Dynamics run");
  TRIBOS_REQUIRE(options.exportFclib.empty() || Input::method(params) == Input::Method::FetiContact,
                 "--export-fclib writes a FETI contact problem; this run is "
                     << (params.sublist("Contact").get<bool>("Enabled") ? "solved by the semismooth* method"
                                                                        : "a linear problem without contact"));
  // An FCLIB file holds one problem, without the state a step hands to the next.
  const size_t steps = Input::loadStepTimes(params).size();
  TRIBOS_REQUIRE(options.exportFclib.empty() || steps == 1,
                 "--export-fclib writes one contact problem; \"Load Steps/Times\" has " << steps
                                                                                        << " steps (export one step)");
}

// The run in its steps: read, mesh, solve (assembling what the method
// needs), check, write; before the first, the paths; before the mesh, the
// memory and the output directory.
RunResult run(const Teuchos::ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm) {
  const auto t0 = std::chrono::steady_clock::now();
  RunReport report;
  report.problem = params.get<std::string>("Problem Name");
  report.input = options.inputName;
  // No output may be an input or another output: checked before the mesh is read.
  IO::requireDistinctFiles(runFiles(params, options), comm);
  requireOutsideSeries(params, options, *comm);
  const std::vector<double> times = Input::loadStepTimes(params);
  std::optional<Restart> restart;
  if (!options.restartDir.empty()) restart = readRestart(params, options, times, *comm);

  Mesh::DecompositionSpec decomposition;
  MeshSize fileSize;
  auto whole = readStep(params, options, decomposition, fileSize, *comm);
  Progress::stage("memory estimate");
  const MemoryEstimate memory = requireMemory(params, options.maxMemory, options.verify, comm, whole ? &fileSize : nullptr);
  Progress::stage("checking output paths");
  const auto outputDir = prepareOutput(params, options, whole ? &fileSize : nullptr, comm);

  const Discretized d = meshStep(params, options, std::move(whole), decomposition, *comm, report);
  const double meshSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // The load history: solve, check and write at each step time (one step at
  // t = 1 without Load Steps), until the history ends or a step fails.
  const int numSteps = static_cast<int>(times.size());
  report.numSteps = numSteps;
  auto method = solveMethods().create(report.algorithm, params, options, comm);
  std::unique_ptr<IO::StepSeries> series;
  if (outputDir)
    series = std::make_unique<IO::StepSeries>(*outputDir, params.sublist("Output").get<std::string>("Base Name"),
                                              numSteps, comm);
  StepOutput output;
  FrictionMemory friction;  // the contact nodes' dissipated energy and slip amplitude so far
  const SupportGroups supports(params, d.disc, d.loads.dirichlet);
  int first = 0;  // the first step this run solves
  if (restart) {
    // The steps done stay as they are: their files, table rows and history
    // rows; the method continues from the last one's displacement.
    readRestartState(*restart, *series, *outputDir, d.disc, d.constraints, *comm);
    first = restart->completed;
    series->continueAfter(std::vector<double>(times.begin(), times.begin() + first), restart->written);
    restart->last.time = times[first - 1];
    method->resumeFrom(std::move(restart->last));
    output.history = std::move(restart->history);
    output.stepLines = std::move(restart->stepLines);
    report.stepsCompleted = first;
    report.iterationsTotal = restart->iterationsTotal;
    report.n_A_total = restart->n_A_total;
    for (const auto& [node, m] : restart->contactMemory) friction.set(node, m);
  }
  double setupSeconds = meshSeconds, solveSeconds = 0;
  // The loads and their curves, read once: a step costs the same whatever
  // the length of the history and of its curves.
  const Fem::LoadHistory loadHistory = Input::loadHistory(params);
  const int stride = Input::stepStride(params);
  for (int k = first; k < numSteps; ++k) {
    Progress::setStep(k + 1, numSteps);
    // The input's loads as they are at t = 1 without Load Steps; a history
    // scales them by their curves.
    const Fem::LoadCase loads = numSteps == 1 && times[0] == 1.0 ? d.loads : Fem::loadCaseAt(loadHistory, times[k]);
    StepSolution sol = method->solve(d, loads, report);
    checkStep(params, options, d, loads, sol, comm, report);
    for (IO::HistoryRow row : sol.history.rows) {
      row.step = k + 1;
      output.history.rows.push_back(row);
    }
    if (!report.converged && numSteps > 1) {
      std::ostringstream os;
      os << (Input::dynamics(params) ? "time step " : "load step ") << k + 1 << " of " << numSteps << " (t = "
         << times[k] << "): " << report.stopReason;
      report.stopReason = os.str();
    }
    friction.advance(sol.result.contact);
    report.lastStep = stepReport(params, k + 1, times[k], sol, supports, friction, report, *comm);
    report.iterationsTotal += report.lastStep->iterations;
    report.n_A_total += report.lastStep->n_A;
    noteSlowStep(k + 1, report, *comm);
    noteHandover(k + 1, report);
    report.stepsCompleted = k + 1;
    // Setup: from the start to a solver ready to iterate; solve: its iterations.
    setupSeconds += sol.setupSeconds;
    solveSeconds += sol.result.solveSeconds;
    report.setupSeconds = maxOver(setupSeconds, *comm);
    report.solveSeconds = maxOver(solveSeconds, *comm);
    report.maxAbsDisplacement = sol.result.u.normInf();
    report.memoryEstimateMb = maxOver(memory.total() / (1024.0 * 1024.0), *comm);
    report.peakRssMb = maxOver(IO::peakRssMb(), *comm);
    // Every stride-th step is written, the last, and a step that fails
    // (the run ends there); a step between waits in memory for the next
    // written one, whose commit appends its row and history rows.
    const bool written = (k + 1) % stride == 0 || k + 1 == numSteps || !report.converged;
    if (series && written) {
      writeStep(params, *outputDir, *series, k + 1, times[k], d, sol, friction, output, report, comm);
    } else if (series) {
      output.stepLines += stepRow(*report.lastStep).toJsonLine() + "\n";
    } else {
      report.unwrittenSteps.push_back(stepRow(*report.lastStep));
      output.history.rows.clear();
    }
    if (!report.converged) break;
  }
  Progress::setStep(1, 1);
  return {report.toSummary(), report, report.converged, report.stopReason, outputDir != nullptr};
}

}  // namespace Tribos
