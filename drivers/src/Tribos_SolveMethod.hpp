// Tribos_SolveMethod.hpp: the step "solve" of a run, by the method the
// parameters choose (Input::method, the one place that reads Solver/Type,
// Contact/Enabled and Solver/Outer Algorithm together), each registered by
// name in Belos' factory style:
//   "Monolithic"            the assembled global problem by CG + MueLu (no contact)
//   "FETI"                  Total FETI: projected CG, or with contact the outer
//                           algorithm of Solver/Outer Algorithm
//   "SemismoothStarNewton"  one face on a rigid plane, Tresca or frictionless,
//                           by the semismooth* Newton method (serial)
//   "FETI Dynamics"         implicit time steps of K + 4 M / dt^2 through FETI
//                           (Dynamics/Enabled, Contact::ImplicitDynamics)
// Every method returns the shared result (Contact::SolveResult: the nodal
// displacement, the contact nodes, the KKT residuals of that result and the
// verdict on them, computed once by Contact::resultVerdict) with its history
// rows, and fills its own part of the run report.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Tribos_ContactConstraint.hpp"
#include "Tribos_ContactSearch.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_History.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_Registry.hpp"
#include "Tribos_Run.hpp"
#include "Tribos_RunReport.hpp"
#include "Tribos_SolveResult.hpp"

namespace Tribos {

// The mesh step's result: the whole mesh on rank 0 (on every rank for the
// semismooth* method, a serial method; kept on rank 0 for the FCLIB export,
// a global problem; else released once cut), this rank's part, its
// materials, the loads, and the contact constraints of its slave nodes.
struct Discretized {
  std::unique_ptr<Mesh::Mesh> whole;
  Mesh::Discretization disc;
  Fem::BodyMaterials materials;
  Fem::LoadCase loads;
  std::vector<Feti::ContactConstraint> constraints;
  Contact::ContactSearch search;  // the pairs' search figures and left-out nodes (every rank)
};

// What a method leaves for the result check and the files.
struct StepSolution {
  Contact::SolveResult result;
  // A Dynamics step: the velocity (on result.u's layout) and the step's figures.
  Fem::NodalVector velocity;
  std::optional<DynamicsStepReport> dynamics;
  double setupSeconds = 0;       // the method's setup (assembly, factorization); result.solveSeconds: its iterations
  IO::IterationHistory history;  // BASE.history.csv
};

// The last step an earlier run completed, read back from its step file by
// a restarted run (tribos --restart), for the method to continue from.
// Values per node are 3 per node of disc.ownedNodes(), in its order (as the
// step file has them).
struct ResumedStep {
  double time = 0;             // the step's time
  std::vector<double> uOwned;  // its displacement
  // A Dynamics step's velocity (empty for a load history), the work of the
  // loads and the energy friction dissipated since t = 0.
  std::vector<double> vOwned;
  double externalWork = 0, frictionDissipation = 0;
};

// One method object serves every load step of a run, keeping what the
// steps share (FETI: K, its factors, F, the coarse space and the previous
// step's solution, the origin of the next step's slip).
class SolveMethod {
 public:
  virtual ~SolveMethod() = default;
  // Solves d at the loads of the next load step, assembling what the method
  // needs; fills the method's part of report (sizes, iterations, its own
  // sublist). Collective.
  virtual StepSolution solve(const Discretized& d, const Fem::LoadCase& loads, RunReport& report) = 0;
  // A restarted history (tribos --restart): the next solve continues from a
  // step an earlier run completed. Call it before the first solve. A method
  // without memory between steps (the monolithic solve of a linear problem)
  // has nothing to take from it.
  virtual void resumeFrom(ResumedStep step) { (void)step; }
};

// Makers take the validated parameters, the run's options and communicator.
using SolveMethodRegistry =
    Registry<SolveMethod, const Teuchos::ParameterList&, const RunOptions&, const RCP<const Comm>&>;
const SolveMethodRegistry& solveMethods();

// The registered name of a method.
const char* solveMethodName(Input::Method method);

}  // namespace Tribos
