// Tribos_RunReport.hpp: what a run found, step by step, in one typed record.
// Each step of Tribos::run (read, mesh, assemble, solve, check, write) fills
// its part; the JSON summary (stdout and BASE.json) is made from it in one
// place, toSummary(), so that no solver writes into the summary and a load
// history can report each step alike.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_SolveResult.hpp"
#include "Tribos_Summary.hpp"

namespace Tribos {

// Contact nodes by status, over all ranks.
struct ContactCountReport {
  long long nodes = 0, active = 0, stick = 0, slip = 0;
};

// The FETI machinery of a run: local factorizations, the dual operator F and
// the coarse problem (maxima over the ranks where a rank has its own).
struct FetiReport {
  std::string localSolver;
  double factorSeconds = 0, factorMemoryMb = 0, denseBlockMemoryMb = 0;
  long long F_applications = 0;
  double F_seconds = 0;
  long long coarseSize = 0;
  double coarseFactorMb = 0;
};

// The outer contact algorithm of a FETI run.
struct OuterAlgorithmReport {
  std::string name;
  std::string handover;  // why Auto's Newton solve handed over to Algorithm2 (empty: it did not)
  std::string preconditioner;  // the Newton method's CG preconditioner at the end (empty: another method)
  int resultCheckRounds = 1;
  long long msaIterations = 0, innerIterations = 0, n_A_qpp = 0, n_A_qpq = 0;
  double slipBoundChange = 0;
  std::vector<double> history;  // per outer step: the change of g (Coulomb) or ||g^P|| (Tresca)
};

// The semismooth* Newton method (a serial method on rank 0).
struct SemismoothReport {
  long long newtonIterations = 0, cgIterations = 0;
  std::vector<double> residuals;
  double assemblySeconds = 0, reductionSeconds = 0, newtonSeconds = 0, preconditionerSeconds = 0;
};

// The resultant of the reaction of the supports (Contact::supportReactions)
// over one Dirichlet condition of the input: the force the support exerts
// on the body there.
struct ReactionReport {
  std::string name, face;  // Boundary Conditions/Dirichlet/NAME and its Face
  std::array<double, 3> force{0, 0, 0};
};

// A contact pair in a step: the resultant of its contact forces on the
// slave side, how far the slave side moved against the master
// (Contact::PairMotion: the relative tangential displacement, the
// dissipation of the step) and the energy its friction dissipated over the
// history up to this step.
struct PairReport {
  std::string name;
  Contact::PairForce force;
  Contact::PairMotion motion;
  double dissipatedEnergy = 0;
};

// One load step: its pseudo-time, the solve's work, the KKT residuals of its
// result and the verdict, the contact nodes by status, the reactions of the
// supports and each pair's resultant and motion (the load-displacement
// curves of a history).
// A Dynamics step (docs/dynamics.md): the energies of the state after it,
// the work of the loads and the energy friction dissipated since t = 0, and
// the resultant of the normal contact forces, their mean over the step.
struct DynamicsStepReport {
  double kineticEnergy = 0, strainEnergy = 0, externalWork = 0, frictionDissipation = 0, contactForce = 0;
};

struct StepReport {
  int step = 1;
  double time = 1;
  std::optional<DynamicsStepReport> dynamics;
  long long iterations = 0, n_A = 0;
  Contact::ResultKKT kkt;
  std::optional<ContactCountReport> contact;
  std::vector<ReactionReport> reactions;  // per Dirichlet condition of the input, in its order
  std::vector<PairReport> pairs;          // per contact pair, in the order of their numbers
  std::string outerAlgorithm, handover, preconditioner;  // contact: the method that solved the step; OuterAlgorithmReport's
  bool converged = false;
  std::string stopReason;
  double solveSeconds = 0;
};

// Steps whose dual solve took far more work than a well-conditioned dual
// problem needs, whatever its size: more than kSlowIterations outer
// iterations (Algorithm 2 takes 30-120 on the shipped examples, the Newton
// method 10-40; 470-750 where the dual problem was ill-conditioned, and
// where the Newton method stopped short and Algorithm 2 finished), or more
// applications of F than twice the dual unknowns and kSlowApplications
// (more than CG would need on any SPD matrix of that size). The first such
// step, how many there were, and what to try instead.
struct SlowConvergenceReport {
  static constexpr long long kSlowIterations = 300, kSlowApplications = 2000;
  int firstStep = 0;
  long long n_A = 0, iterations = 0, dualDofs = 0;  // the first such step's
  int steps = 0;                                    // steps of this run so slow
  std::string advice;
};
// Steps where Auto's Newton solve stopped short and Algorithm 2 solved the
// step: the first, why, and how many.
struct HandoverReport {
  int firstStep = 0, steps = 0;
  std::string reason;
};

// Whether a step of that many outer iterations and applications of F on a
// dual of dualDofs unknowns is slow in that sense.
bool slowConvergence(long long iterations, long long n_A, long long dualDofs);

struct RunReport {
  // Read: the problem and where it came from.
  std::string problem, input;
  // Mesh: the discretization and its decomposition.
  std::string algorithm, element, meshFile;
  int ranks = 1, subdomains = 0, subdomainSize = 0;  // subdomainSize: H, 0 when not sized
  long long nodes = 0, cells = 0;
  // Solve: the sizes, the work, and the method's own figures.
  long long primalDofs = 0, dualDofs = 0, n_A = 0;
  long long outerIterations = 0;
  std::optional<double> relativeResidual;  // projected CG and the monolithic CG
  std::string frictionLaw;                 // contact runs
  std::optional<OuterAlgorithmReport> outer;
  std::optional<ContactCountReport> contact;
  std::optional<SemismoothReport> semismooth;
  std::optional<FetiReport> feti;
  std::string fclibExport;
  // Check: the KKT residuals of the result and the verdict on them.
  Contact::ResultKKT kkt;
  double tolerance = 0, limit = 0;
  bool solverConverged = false, converged = false;
  std::string stopReason;
  std::optional<double> verifyRelativeDifference;  // --verify
  std::string verifyNote;
  std::optional<SlowConvergenceReport> slow;
  std::optional<HandoverReport> handover;
  std::vector<Contact::PairSearch> contactSearch;  // per contact pair: its search distance and counts
  // The load steps: how many are complete (those of the run a restart
  // continues included) and the last one; the fields above are its. Each
  // step's row (stepRow) goes to the steps table as the step is written:
  // the summary, rewritten at every step, keeps the same size at step 10 and
  // at step 10^5.
  int stepsCompleted = 0;
  std::optional<StepReport> lastStep;
  // The work of the whole history (every step's, those a restart continues
  // included): the method's iterations and the applications of F.
  long long iterationsTotal = 0, n_A_total = 0;
  std::string stepsFile;  // the steps table, a file name beside the summary
  // A run that writes no result set has no steps table: its summary, written
  // once at the end (--summary, stdout), holds the step rows.
  std::vector<IO::Summary> unwrittenSteps;
  int numSteps = 1;
  // The run's cost.
  double setupSeconds = 0, solveSeconds = 0, maxAbsDisplacement = 0, memoryEstimateMb = 0, peakRssMb = 0;
  // Write: the files of the result set.
  std::string output, parameters, historyFile;

  // The summary: every field that the run filled, under its JSON name.
  IO::Summary toSummary() const;
};

// A step's row of the steps table: its figures and verdict (StepReport), and
// the data file that holds its result with that file's SHA-256 digest.
IO::Summary stepRow(const StepReport& step, const std::string& file, const std::string& sha256);
// The row of a step that no file holds (a run that writes no results).
IO::Summary stepRow(const StepReport& step);

}  // namespace Tribos
