#include "Tribos_Run.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <sys/stat.h>

#include <chrono>

#include "Tribos_Assembly.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FetiDual.hpp"
#include "Tribos_ProjectedCG.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_ResultWriter.hpp"

namespace Tribos {

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double maxOverRanks(double v, const Comm& comm) {
  double out = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, v, Teuchos::outArg(out));
  return out;
}

void makeDirectory(const std::string& dir) {
  std::string partial;
  for (size_t i = 0; i <= dir.size(); ++i) {
    if (i == dir.size() || dir[i] == '/') {
      if (!partial.empty()) mkdir(partial.c_str(), 0755);
    }
    if (i < dir.size()) partial += dir[i];
  }
  struct stat st;
  TRIBOS_REQUIRE(stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode), "cannot create output directory " << dir);
}

// Von Mises stress, subdomain and rank of every local cell.
std::vector<IO::Field> cellFields(const Mesh::Discretization& disc, const Fem::Material& mat,
                                  const std::vector<double>& u) {
  IO::Field vm{"von_mises", 1, {}}, sub{"subdomain", 1, {}}, rank{"rank", 1, {}};
  const int npc = disc.mesh.nodesPerCell();
  for (int c : disc.localCells()) {
    std::vector<double> ue(3 * npc);
    for (int a = 0; a < npc; ++a)
      for (int d = 0; d < 3; ++d) ue[3 * a + d] = u[3 * disc.mesh.cell(c)[a] + d];
    vm.values.push_back(Fem::vonMises(Fem::cellStress(disc.mesh.type, Fem::cellCoordinates(disc.mesh, c), ue, mat)));
    sub.values.push_back(disc.cellPart[c]);
    rank.values.push_back(disc.myRank);
  }
  return {vm, sub, rank};
}

}  // namespace

IO::Summary run(const Teuchos::ParameterList& params, const RunOptions& options, const RCP<const Comm>& comm) {
  const auto t0 = std::chrono::steady_clock::now();
  IO::Summary summary;
  summary.set("problem", params.get<std::string>("Problem Name"));
  if (!options.inputName.empty()) summary.set("input", options.inputName);
  const auto spec = Input::boxSpec(params);
  const auto mat = Input::material(params);
  const auto loads = Input::loadCase(params);
  Mesh::Discretization disc(Mesh::generateBox(spec), spec, Input::decompositionSpec(params), comm->getSize(),
                            comm->getRank());
  // Faces named by conditions must exist: check before any solve.
  for (const auto& d : loads.dirichlet) disc.mesh.face(d.face);
  for (const auto& t : loads.tractions) disc.mesh.face(t.face);
  const std::string type = params.sublist("Solver").get<std::string>("Type");
  summary.set("algorithm", type);
  summary.set("ranks", comm->getSize());
  summary.set("subdomains", disc.numSubdomains());
  summary.set("element", Mesh::cellTypeName(spec.type));
  summary.set("nodes", disc.mesh.numNodes());
  summary.set("cells", disc.mesh.numCells());

  std::vector<double> u;
  const auto t1 = std::chrono::steady_clock::now();
  double setupTime = 0, solveTime = 0;
  if (type == "Monolithic") {
    Fem::MonolithicSystem system(disc, mat, loads, comm);
    setupTime = seconds(t0);
    const auto t2 = std::chrono::steady_clock::now();
    const auto res = system.solve(params.sublist("Solver").sublist("Monolithic"));
    solveTime = seconds(t2);
    u = res.u;
    summary.set("primal_dofs", static_cast<long long>(system.matrix()->getGlobalNumRows()));
    summary.set("dual_dofs", 0);
    summary.set("outer_iterations", res.iterations);
    summary.set("n_A", static_cast<long long>(res.iterations));
    summary.set("relative_residual", res.relativeResidual);
    summary.set("converged", res.converged);
  } else {
    const auto& fetiParams = params.sublist("Solver").sublist("FETI");
    Teuchos::ParameterList problemParams;
    problemParams.set("Local Solver", fetiParams.get<std::string>("Local Solver"));
    problemParams.set("Gluing", fetiParams.get<std::string>("Gluing"));
    auto problem = rcp(new Feti::FetiProblem(disc, mat, loads, Feti::ContactSpec{}, problemParams, comm));
    Feti::FetiDual dual(problem);
    setupTime = seconds(t0);
    const auto t2 = std::chrono::steady_clock::now();
    Feti::ProjectedCG pcg(fetiParams.sublist("Projected CG"));
    Vector lambda(problem->dualMap());
    const auto st = pcg.solve(dual, lambda);
    u = problem->nodalDisplacement(*dual.recoverPrimal(lambda));
    solveTime = seconds(t2);
    summary.set("primal_dofs", static_cast<long long>(problem->primalMap()->getGlobalNumElements()));
    summary.set("dual_dofs", static_cast<long long>(problem->dualMap()->getGlobalNumElements()));
    summary.set("outer_iterations", st.iterations);
    summary.set("n_A", st.n_A);
    summary.set("relative_residual", st.relativeResidual);
    summary.set("converged", st.converged);
    summary.set("local_solver", problem->localSolverName());
    summary.set("time_factor_s", maxOverRanks(problem->factorTime(), *comm));
    summary.set("factor_memory_mb", maxOverRanks(problem->factorMemoryMb(), *comm));
  }
  (void)t1;
  if (options.verify) {
    Fem::MonolithicSystem reference(disc, mat, loads, comm);
    const auto ref = reference.solve(params.sublist("Solver").sublist("Monolithic"));
    double diff = 0, norm = 0;
    for (size_t i = 0; i < u.size(); ++i) diff += (u[i] - ref.u[i]) * (u[i] - ref.u[i]), norm += ref.u[i] * ref.u[i];
    summary.set("verify_rel_diff_u", std::sqrt(diff / std::max(norm, 1e-300)));
  }
  summary.set("time_setup_s", maxOverRanks(setupTime, *comm));
  summary.set("time_solve_s", maxOverRanks(solveTime, *comm));

  const auto& out = params.sublist("Output");
  if (out.get<bool>("Write Results")) {
    const std::string dir = options.outputDir.empty() ? out.get<std::string>("Directory") : options.outputDir;
    if (comm->getRank() == 0) makeDirectory(dir);
    comm->barrier();
    IO::ResultWriter writer(disc, comm);
    writer.write(dir, out.get<std::string>("Base Name"), u, {}, cellFields(disc, mat, u));
    summary.set("output", dir + "/" + out.get<std::string>("Base Name") + ".xmf");
  }
  double maxU = 0;
  for (double v : u) maxU = std::max(maxU, std::abs(v));
  summary.set("max_abs_displacement", maxU);
  summary.set("peak_rss_mb", maxOverRanks(IO::peakRssMb(), *comm));
  return summary;
}

}  // namespace Tribos
