// Tribos_ImplicitDynamics.hpp: implicit time stepping of elastic bodies in
// contact through FETI (docs/dynamics.md). Every step is a contact problem
// of the effective stiffness K + M / (beta dt^2) (trapezoidal rule, beta =
// 1/4) on positive definite subdomains: no kernel, no coarse space, the
// factorizations made once for the fixed step.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "Tribos_FetiSolve.hpp"
#include "Tribos_Mass.hpp"

namespace Tribos {
namespace Contact {

// The schemes (docs/dynamics.md, "Schemes at contact"), chosen by name:
//   "Newmark"  the trapezoidal rule with the contact conditions on u_{n+1};
//   "Contact-Stabilized Newmark"  Deuflhard, Krause and Ertel (2008): the
//       free flight u_n + dt v_n first projected onto the admissible set in
//       the mass norm, then the trapezoidal step from there.
enum class TimeScheme { Newmark, ContactStabilizedNewmark };
std::string timeSchemeName(TimeScheme scheme);
// The scheme of a name; throws naming the valid names.
TimeScheme timeSchemeFromName(const std::string& name);

struct DynamicsSpec {
  double timeStep = 0;                              // dt > 0, fixed
  TimeScheme scheme = TimeScheme::ContactStabilizedNewmark;
  std::array<double, 3> initialVelocity{0, 0, 0};  // of every node not fixed by a Dirichlet condition
  // Per body of the mesh (Mesh::bodyOf), in place of initialVelocity on its
  // nodes; empty: initialVelocity everywhere. Bodies that share nodes must
  // have the same (the constructor refuses them, naming a node).
  std::vector<std::array<double, 3>> bodyVelocity;
};

// What a step leaves: the time reached, the energies of the state after it
// (summed over the subdomains, each cell once), the contact force of the
// step, and the step's contact solve. Contact forces are the means over the
// step, impulse / dt: the trapezoidal rule's momentum balance
// M (v_{n+1} - v_n) = dt/2 (r_n + r_{n+1} + ...) gives the impulse
// dt/2 (lambda_n + lambda_{n+1}) (Newmark: lambda the multipliers of the
// steps, the forces at t_n and t_{n+1}) and dt/2 lambda (the
// contact-stabilized scheme, whose one multiplier carries both ends). The
// solve's contact node forces are replaced by these means; its KKT figures
// and verdict are those of the step problem's multipliers.
// Since t = 0: the work of the loads, sum over the steps of
// (f_n + f_{n+1})' (u_{n+1} - u_n) / 2, and the energy friction dissipated,
// the sum over the steps and contact nodes of the mean friction force of the
// step against the node's slip in it (>= 0). With the energies they balance,
// kinetic + strain = initial kinetic + work - dissipated, up to what the
// scheme itself dissipates at contact.
struct DynamicStep {
  double time = 0;
  double kineticEnergy = 0;        // v' M v / 2
  double strainEnergy = 0;         // u' K u / 2
  double externalWork = 0;         // since t = 0
  double frictionDissipation = 0;  // since t = 0
  double contactForce = 0;         // the resultant of the normal contact forces, all ranks
  FetiSolveResult solve;
};

// The state of a step an earlier run completed, for a run that continues
// from it (ImplicitDynamics::resumeFrom): the time t_n, the nodal
// displacement and velocity on problem().nodalLayout(), and the running
// sums since t = 0.
struct DynamicState {
  double time = 0;
  Fem::NodalVector u, v;
  double externalWork = 0, frictionDissipation = 0;
};

// The bodies of a decomposed mesh from the reference configuration (u = 0)
// with an initial velocity uniform on each body, under loads given at t = 0 and, step by
// step, at the step's end (constant loads: the same at every time), in
// contact through `contact` (the constraints of FetiProblem's mesh
// constructor) with the friction of each pair. The initial state carries no
// contact force. The discretization must outlive the object.
class ImplicitDynamics {
 public:
  // feti: FetiProblem's parameters (TFETI); solver: solveFeti's. Collective.
  ImplicitDynamics(const Mesh::Discretization& disc, const Fem::BodyMaterials& mat, const Fem::BodyDensities& density,
                   const Fem::LoadCase& loads, const std::vector<Feti::ContactConstraint>& contact,
                   const PairFriction& friction, const DynamicsSpec& spec, const Teuchos::ParameterList& feti,
                   const Teuchos::ParameterList& solver, const RCP<const Comm>& comm);

  // One step t -> t + dt under the loads of the constructor. A step whose
  // contact solve misses its result check comes back with that verdict
  // (solve.verdict.converged false, the stop reason saying which solve):
  // the state is then that solve's, and the caller stops. Collective.
  DynamicStep step();
  // The same, the loads at t + dt being `atNext` (the same conditions,
  // other values: a load history's curves at t + dt).
  DynamicStep step(const Fem::LoadCase& atNext);

  // Continues from a state an earlier run reached (a restart), before the
  // first step; loadsAtTime: the loads at state.time, f_n of the next step.
  // Every subdomain copy of a node takes the node's value (the copies of a
  // solved step agree to the gluing tolerance). The contact-stabilized
  // scheme only: Newmark's step also needs M a_n and the contact forces of
  // t_n, which u and v do not give. Collective.
  void resumeFrom(const DynamicState& state, const Fem::LoadCase& loadsAtTime);

  double time() const { return time_; }
  // The step's problem, K + M / (beta dt^2).
  const Feti::FetiProblem& problem() const { return *problem_; }
  // The energies of the current state, over all ranks. Collective.
  double kineticEnergy() const;
  double strainEnergy() const;
  // The nodal displacement and velocity of the current state. Collective.
  Fem::NodalVector displacement() const { return problem_->nodalDisplacement(*primal(u_)); }
  Fem::NodalVector velocity() const { return problem_->nodalDisplacement(*primal(v_)); }

 private:
  using Subdomains = std::vector<std::vector<double>>;  // per local subdomain, 3 per local node
  // Per local subdomain: y = M x, y = K x (K of the effective matrix less
  // its mass term).
  Subdomains massTimes(const Subdomains& x) const;
  Subdomains stiffnessTimes(const Subdomains& x) const;
  RCP<Vector> primal(const Subdomains& x) const;
  Subdomains onSubdomains(const Fem::NodalVector& x) const;
  Subdomains subdomains(const Vector& primal) const;
  // The free flight u + dt v, projected onto the admissible set in the mass
  // norm (the contact-stabilized scheme's predictor), and its solve.
  Subdomains projectedPredictor(const Subdomains& flight, FetiSolveResult& solve);
  FetiSolveResult solveStep(Feti::FetiProblem& problem, FetiLoadSteps& steps, const Subdomains& rhs,
                            const std::string& what) const;
  DynamicStep advance(const Fem::LoadCase* atNext);
  // The predictor's projection is part of the step's cost: its
  // applications of F and its time are added to the step's (the
  // iterations, KKT figures and verdict stay the contact solve's).
  static void addCost(const FetiSolveResult& projection, FetiSolveResult& step);
  // The time, the energies, the work and the dissipation of the current
  // state into a step's report. Collective.
  void recordState(DynamicStep& s) const;
  // The contact node forces of the step just solved made the means over the
  // step (the multipliers halved, or averaged with the previous step's).
  void meanForces(ContactNodeResults& contact, bool stabilized);

  DynamicsSpec spec_;
  double massCoefficient_;                     // 1 / (beta dt^2) = 4 / dt^2
  // The step's problem, K + M / (beta dt^2), and the projection's, M alone
  // (contact-stabilized scheme), each solved as a sequence of right-hand
  // sides: F built once, each solve started from the last multipliers,
  // friction acting on the slip since the last solve.
  RCP<Feti::FetiProblem> problem_, projection_;
  std::unique_ptr<FetiLoadSteps> steps_, projectionSteps_;
  std::vector<LocalCsr> mass_;                 // M of each local subdomain
  Subdomains load_;                            // f of each local subdomain at t_n
  Subdomains constantLoad_;                    // ... at t = 0, the loads of step()
  Subdomains u_, v_, Ma_;                      // the state: u, v and M a (trapezoidal rule)
  // Newmark: this rank's contact nodes' multiplier forces at t_n (lambda_N,
  // and phi_T 3 each; the same nodes in the same order at every step).
  std::vector<double> lastNormal_, lastTangential_;
  double externalWork_ = 0, frictionDissipation_ = 0;
  double time_ = 0;
};

}  // namespace Contact
}  // namespace Tribos
