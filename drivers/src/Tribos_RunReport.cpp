#include "Tribos_RunReport.hpp"

#include <algorithm>
#include <cmath>

#include "Tribos_BlasKernels.hpp"

namespace Tribos {

namespace {

IO::Summary kktFigures(const Contact::ResultKKT& kkt) {
  IO::Summary k;
  k.set("equilibrium", kkt.equilibrium).set("dirichlet", kkt.dirichlet).set("nonpenetration", kkt.nonpenetration);
  k.set("complementarity", kkt.complementarity).set("friction_law", kkt.frictionLaw);
  return k;
}

IO::Summary kktSummary(const RunReport& r) {
  IO::Summary k = kktFigures(r.kkt);
  k.set("displacement_scale", r.kkt.displacementScale).set("force_scale", r.kkt.forceScale);
  k.set("tolerance", r.tolerance).set("limit", r.limit);
  return k;
}

void setOuter(const OuterAlgorithmReport& o, IO::Summary& s) {
  s.set("outer_algorithm", o.name);
  if (!o.handover.empty()) s.set("handover", o.handover);
  if (!o.preconditioner.empty()) s.set("newton_preconditioner", o.preconditioner);
  s.set("result_check_rounds", o.resultCheckRounds);
  s.set("msa_iterations", o.msaIterations);
  s.set("inner_iterations", o.innerIterations);
  s.set("n_A_qpp", o.n_A_qpp);
  s.set("n_A_qpq", o.n_A_qpq);
  s.set("slip_bound_change", o.slipBoundChange);
  s.set("history", o.history);
}

void setSemismooth(const SemismoothReport& m, IO::Summary& s) {
  s.set("newton_iterations", m.newtonIterations);
  s.set("residuals", m.residuals);
  s.set("time_assembly_s", m.assemblySeconds);
  s.set("time_reduction_s", m.reductionSeconds);
  s.set("time_newton_s", m.newtonSeconds);
  s.set("cg_iterations", m.cgIterations);
  s.set("time_preconditioner_setup_s", m.preconditionerSeconds);
}

void setFeti(const FetiReport& f, IO::Summary& s) {
  s.set("local_solver", f.localSolver);
  s.set("time_factor_s", f.factorSeconds);
  s.set("factor_memory_mb", f.factorMemoryMb);
  s.set("dense_block_memory_mb", f.denseBlockMemoryMb);
  s.set("F_applications", f.F_applications);
  s.set("time_F_apply_s", f.F_seconds);
  s.set("coarse_size", f.coarseSize);
  s.set("coarse_factor_mb", f.coarseFactorMb);
}

std::vector<double> vector3(const std::array<double, 3>& v) { return {v.begin(), v.end()}; }

// The reactions of the supports per Dirichlet condition and the figures of
// each contact pair of a step.
void setReactionsAndPairs(const StepReport& r, IO::Summary& s) {
  if (!r.reactions.empty()) {
    std::vector<IO::Summary> reactions;
    for (const auto& reaction : r.reactions) {
      IO::Summary c;
      c.set("name", reaction.name).set("face", reaction.face).set("force", vector3(reaction.force));
      reactions.push_back(c);
    }
    s.set("reactions", reactions);
  }
  if (!r.pairs.empty()) {
    std::vector<IO::Summary> pairs;
    for (const auto& pair : r.pairs) {
      IO::Summary p;
      p.set("name", pair.name).set("normal_force", pair.force.normal);
      p.set("tangential_force", vector3(pair.force.tangential));
      p.set("relative_tangential_displacement", vector3(pair.motion.relativeTangentialDisplacement));
      p.set("dissipation", pair.motion.dissipation).set("dissipated_energy", pair.dissipatedEnergy);
      pairs.push_back(p);
    }
    s.set("pairs", pairs);
  }
}

IO::Summary stepSummary(const StepReport& r) {
  IO::Summary s;
  s.set("step", r.step).set("time", r.time).set("iterations", r.iterations).set("n_A", r.n_A);
  s.set("kkt", kktFigures(r.kkt));
  if (r.contact) {
    IO::Summary c;
    c.set("nodes", r.contact->nodes).set("active", r.contact->active).set("stick", r.contact->stick);
    c.set("slip", r.contact->slip);
    s.set("contact", c);
  }
  setReactionsAndPairs(r, s);
  if (r.dynamics) {
    IO::Summary d;
    d.set("kinetic_energy", r.dynamics->kineticEnergy).set("strain_energy", r.dynamics->strainEnergy);
    d.set("external_work", r.dynamics->externalWork).set("friction_dissipation", r.dynamics->frictionDissipation);
    d.set("contact_force", r.dynamics->contactForce);
    s.set("dynamics", d);
  }
  if (!r.outerAlgorithm.empty()) s.set("outer_algorithm", r.outerAlgorithm);
  if (!r.handover.empty()) s.set("handover", r.handover);
  if (!r.preconditioner.empty()) s.set("newton_preconditioner", r.preconditioner);
  s.set("converged", r.converged).set("stop_reason", r.stopReason).set("time_solve_s", r.solveSeconds);
  return s;
}

}  // namespace

IO::Summary stepRow(const StepReport& step) { return stepSummary(step); }

IO::Summary stepRow(const StepReport& step, const std::string& file, const std::string& sha256) {
  return stepSummary(step).set("file", file).set("sha256", sha256);
}

bool slowConvergence(long long iterations, long long n_A, long long dualDofs) {
  return iterations > SlowConvergenceReport::kSlowIterations ||
         n_A > std::max(SlowConvergenceReport::kSlowApplications, 2 * dualDofs);
}

IO::Summary RunReport::toSummary() const {
  IO::Summary s;
  s.set("problem", problem);
  if (!input.empty()) s.set("input", input);
  // Mesh.
  s.set("algorithm", algorithm);
  s.set("ranks", ranks);
  // The BLAS kernel set ("" for a BLAS other than OpenBLAS), since dense
  // factorizations depend on it (Tribos_BlasKernels.hpp).
  s.set("blas_kernels", blasKernelName());
  s.set("subdomains", subdomains);
  if (subdomainSize > 0) s.set("subdomain_size", subdomainSize);
  s.set("element", element);
  if (!meshFile.empty()) s.set("mesh_file", meshFile);
  s.set("nodes", nodes);
  s.set("cells", cells);
  // Solve.
  s.set("primal_dofs", primalDofs);
  s.set("dual_dofs", dualDofs);
  s.set("n_A", n_A);
  s.set("outer_iterations", outerIterations);
  s.set("n_A_total", n_A_total);
  s.set("outer_iterations_total", iterationsTotal);
  if (relativeResidual) s.set("relative_residual", *relativeResidual);
  if (!frictionLaw.empty()) s.set("friction_law", frictionLaw);
  if (outer) setOuter(*outer, s);
  if (semismooth) setSemismooth(*semismooth, s);
  if (contact) {
    IO::Summary c;
    c.set("nodes", contact->nodes).set("active", contact->active).set("stick", contact->stick).set("slip", contact->slip);
    s.set("contact", c);
  }
  if (!fclibExport.empty()) s.set("fclib_export", fclibExport);
  if (feti) setFeti(*feti, s);
  // Check.
  s.set("kkt", kktSummary(*this));
  s.set("solver_converged", solverConverged);
  s.set("converged", converged);
  s.set("stop_reason", stopReason);
  // The last step's reactions of the supports and contact pairs.
  if (lastStep) setReactionsAndPairs(*lastStep, s);
  s.set("load_steps", numSteps);
  s.set("steps_completed", stepsCompleted);
  if (!stepsFile.empty()) s.set("steps_file", stepsFile);
  else s.set("steps", unwrittenSteps);
  if (slow) {
    IO::Summary w;
    w.set("first_step", slow->firstStep).set("n_A", slow->n_A).set("iterations", slow->iterations);
    w.set("dual_dofs", slow->dualDofs);
    w.set("steps", slow->steps).set("advice", slow->advice);
    s.set("slow_convergence", w);
  }
  if (!contactSearch.empty()) {
    std::vector<IO::Summary> pairs;
    for (const auto& p : contactSearch) {
      IO::Summary c;
      c.set("name", p.name).set("automatic", p.automatic);
      if (std::isfinite(p.searchDistance)) c.set("search_distance", p.searchDistance);  // none: no limit
      c.set("slave_nodes", p.slaveNodes).set("rows", p.rows).set("left_out", p.leftOut);
      c.set("node_to_segment", p.nodeToSegment);
      pairs.push_back(c);
    }
    s.set("contact_search", pairs);
  }
  if (handover) {
    IO::Summary h;
    h.set("first_step", handover->firstStep).set("steps", handover->steps).set("reason", handover->reason);
    s.set("newton_handover", h);
  }
  if (!verifyNote.empty()) s.set("verify_note", verifyNote);
  if (verifyRelativeDifference) s.set("verify_rel_diff_u", *verifyRelativeDifference);
  // Cost.
  s.set("time_setup_s", setupSeconds);
  s.set("time_solve_s", solveSeconds);
  s.set("max_abs_displacement", maxAbsDisplacement);
  s.set("memory_estimate_mb", memoryEstimateMb);
  s.set("peak_rss_mb", peakRssMb);
  // Write.
  if (!output.empty()) {
    s.set("output", output);
    s.set("parameters", parameters);
    s.set("history_file", historyFile);
  }
  return s;
}

}  // namespace Tribos
