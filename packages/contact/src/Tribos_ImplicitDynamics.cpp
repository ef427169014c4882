#include "Tribos_ImplicitDynamics.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Contact {

namespace {

constexpr TimeScheme kTimeSchemes[] = {TimeScheme::Newmark, TimeScheme::ContactStabilizedNewmark};

double sumOverRanks(double mine, const Comm& comm) {
  double all = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, mine, Teuchos::outArg(all));
  return all;
}

// The initial velocity of a subdomain's nodes: its body's (a subdomain
// holds the cells of one body).
const std::array<double, 3>& initialVelocity(const DynamicsSpec& spec, const Mesh::Discretization& disc, int subdomain) {
  return spec.bodyVelocity.empty() ? spec.initialVelocity : spec.bodyVelocity[disc.subdomainBody.at(subdomain)];
}

// One velocity per body, finite; and the copies of every node start with
// one velocity: bodies bonded through shared nodes (glued copies) with
// different velocities would start torn apart. Collective.
void checkInitialVelocities(const DynamicsSpec& spec, const Mesh::Discretization& disc, const Comm& comm) {
  TRIBOS_REQUIRE(spec.bodyVelocity.empty() || static_cast<int>(spec.bodyVelocity.size()) == disc.part.numBodies(),
                 "ImplicitDynamics: " << spec.bodyVelocity.size() << " body velocities for "
                                      << disc.part.numBodies() << " bodies");
  for (const auto& v : spec.bodyVelocity)
    for (double x : v) TRIBOS_REQUIRE(std::isfinite(x), "ImplicitDynamics: a body's initial velocity is not finite");
  std::string mine;
  for (const auto& sub : disc.localSubdomains)
    for (int n : sub.nodes)
      for (const auto& copy : disc.copies(n))
        if (mine.empty() && initialVelocity(spec, disc, copy.subdomain) != initialVelocity(spec, disc, sub.id))
          mine = "node " + std::to_string(disc.meshNode(n)) + " is shared by bodies \"" +
                 disc.part.bodyName(disc.subdomainBody[sub.id]) + "\" and \"" +
                 disc.part.bodyName(disc.subdomainBody[copy.subdomain]) + "\" with different initial velocities";
  int bad = !mine.empty(), any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, bad, Teuchos::outArg(any));
  TRIBOS_REQUIRE(!any, "ImplicitDynamics: " << (mine.empty() ? "on another rank, a node is shared by bodies with "
                                                               "different initial velocities" : mine));
}

}  // namespace

std::string timeSchemeName(TimeScheme scheme) {
  return scheme == TimeScheme::Newmark ? "Newmark" : "Contact-Stabilized Newmark";
}

TimeScheme timeSchemeFromName(const std::string& name) {
  std::string valid;
  for (TimeScheme s : kTimeSchemes) {
    if (name == timeSchemeName(s)) return s;
    valid += (valid.empty() ? "" : ", ") + timeSchemeName(s);
  }
  throw Error("time scheme \"" + name + "\" unknown; valid: " + valid);
}

ImplicitDynamics::ImplicitDynamics(const Mesh::Discretization& disc, const Fem::BodyMaterials& mat,
                                   const Fem::BodyDensities& density, const Fem::LoadCase& loads,
                                   const std::vector<Feti::ContactConstraint>& contact, const PairFriction& friction,
                                   const DynamicsSpec& spec, const Teuchos::ParameterList& feti,
                                   const Teuchos::ParameterList& solver, const RCP<const Comm>& comm)
    : spec_(spec) {
  TRIBOS_REQUIRE(std::isfinite(spec.timeStep) && spec.timeStep > 0,
                 "ImplicitDynamics: the time step must be a positive finite number, got " << spec.timeStep);
  for (double v : spec.initialVelocity)
    TRIBOS_REQUIRE(std::isfinite(v), "ImplicitDynamics: the initial velocity must be finite");
  checkInitialVelocities(spec, disc, *comm);
  // The trapezoidal rule: beta = 1/4, gamma = 1/2.
  massCoefficient_ = 4 / (spec.timeStep * spec.timeStep);
  const Feti::MassTerm effective{density, massCoefficient_, 1.0};
  problem_ = rcp(new Feti::FetiProblem(disc, mat, loads, contact, feti, comm, &effective));
  steps_ = std::make_unique<FetiLoadSteps>(problem_, friction, solver);
  if (spec.scheme == TimeScheme::ContactStabilizedNewmark) {
    const Feti::MassTerm massAlone{density, 1.0, 0.0};
    projection_ = rcp(new Feti::FetiProblem(disc, mat, loads, contact, feti, comm, &massAlone));
    const PairFriction none{FrictionSpec{FrictionLaw::Frictionless, 0.0, 0.0}};
    projectionSteps_ = std::make_unique<FetiLoadSteps>(projection_, none, solver);
  }
  const auto& fixed = problem_->dirichlet();
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) {
    const auto& sys = problem_->subdomain(k);
    mass_.push_back(Fem::assembleSubdomainMass(disc, sys.id, density));
    load_.push_back(sys.f);
    u_.emplace_back(sys.numDofs(), 0.0);
    v_.emplace_back(sys.numDofs(), 0.0);
    const auto& v0 = initialVelocity(spec, disc, sys.id);
    for (int i = 0; i < sys.numDofs(); ++i)
      if (!fixed.count(3LL * sys.nodes[i / 3] + i % 3)) v_.back()[i] = v0[i % 3];
  }
  // M a_0 = f - K u_0 + (no contact force) = f at rest in the reference state.
  Ma_ = load_;
  constantLoad_ = load_;
}

ImplicitDynamics::Subdomains ImplicitDynamics::massTimes(const Subdomains& x) const {
  Subdomains y(x.size());
  for (size_t k = 0; k < x.size(); ++k) {
    y[k].resize(x[k].size());
    mass_[k].multiply(x[k], y[k]);
  }
  return y;
}

ImplicitDynamics::Subdomains ImplicitDynamics::stiffnessTimes(const Subdomains& x) const {
  Subdomains y(x.size());
  const Subdomains Mx = massTimes(x);
  for (size_t k = 0; k < x.size(); ++k) {
    y[k].resize(x[k].size());
    problem_->subdomain(static_cast<int>(k)).K.multiply(x[k], y[k]);
    for (size_t i = 0; i < y[k].size(); ++i) y[k][i] -= massCoefficient_ * Mx[k][i];
  }
  return y;
}

RCP<Vector> ImplicitDynamics::primal(const Subdomains& x) const {
  auto p = rcp(new Vector(problem_->primalMap()));
  auto data = p->getDataNonConst();
  size_t at = 0;
  for (const auto& xs : x)
    for (double value : xs) data[at++] = value;
  return p;
}

ImplicitDynamics::Subdomains ImplicitDynamics::subdomains(const Vector& primal) const {
  const auto data = primal.getData();
  Subdomains x;
  size_t at = 0;
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) {
    const size_t n = static_cast<size_t>(problem_->subdomain(k).numDofs());
    x.emplace_back(data.begin() + at, data.begin() + at + n);
    at += n;
  }
  return x;
}

ImplicitDynamics::Subdomains ImplicitDynamics::onSubdomains(const Fem::NodalVector& x) const {
  Subdomains out;
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) {
    const auto& nodes = problem_->subdomain(k).nodes;
    out.emplace_back(3 * nodes.size());
    for (size_t a = 0; a < nodes.size(); ++a) std::copy(x.at(nodes[a]), x.at(nodes[a]) + 3, &out.back()[3 * a]);
  }
  return out;
}

// Exact for the contact-stabilized scheme: its step reads the state only
// through u_n (the free flight, K u_n, the work, the origin of the step's
// slip), v_n (the free flight and the velocity update) and f_n, and keeps
// no contact force of t_n (unlike Newmark's M a_n); the running sums only
// add to what they were. What the restarted step does not repeat bit for
// bit: the subdomain copies of a node, which agreed to the gluing tolerance,
// are made equal, and both solves (the projection and the step) start from
// zero multipliers instead of the last ones. Both change the iterations,
// not the result beyond the solvers' tolerance.
void ImplicitDynamics::resumeFrom(const DynamicState& state, const Fem::LoadCase& loadsAtTime) {
  TRIBOS_REQUIRE(spec_.scheme == TimeScheme::ContactStabilizedNewmark,
                 "ImplicitDynamics::resumeFrom: the " << timeSchemeName(spec_.scheme)
                                                      << " scheme continues from M a_n and the contact forces of t_n, "
                                                         "which a displacement and a velocity do not give");
  TRIBOS_REQUIRE(steps_->completedSteps() == 0, "ImplicitDynamics::resumeFrom: called after the first step");
  TRIBOS_REQUIRE(std::isfinite(state.time) && state.time >= 0,
                 "ImplicitDynamics::resumeFrom: the time must be finite and not negative, got " << state.time);
  u_ = onSubdomains(state.u);
  v_ = onSubdomains(state.v);
  // f_n as the step to t_n assembled it (the next step's setLoads replaces
  // the problem's loads with those of t_{n+1}).
  problem_->setLoads(loadsAtTime);
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) load_[k] = problem_->subdomain(k).f;
  // Friction acts on the slip since u_n. (The projection is frictionless:
  // its history is its last multipliers alone, a start.)
  steps_->resumeFrom(state.u);
  time_ = state.time;
  externalWork_ = state.externalWork;
  frictionDissipation_ = state.frictionDissipation;
}

FetiSolveResult ImplicitDynamics::solveStep(Feti::FetiProblem& problem, FetiLoadSteps& steps, const Subdomains& rhs,
                                            const std::string& what) const {
  problem.setRightHandSides(rhs, problem.dirichlet());
  // Friction acts on the slip since the last solve (u_n; the first from
  // the reference, u_0 = 0): the slip velocity times dt.
  FetiSolveResult r = steps.solveNext();
  if (!r.verdict.converged)
    r.verdict.stopReason = what + " of the step to t = " + std::to_string(time_ + spec_.timeStep) + ": " +
                           r.verdict.stopReason +
                           (r.handover.empty() ? "" : " (after Semismooth Newton: " + r.handover + ")");
  return r;
}

ImplicitDynamics::Subdomains ImplicitDynamics::projectedPredictor(const Subdomains& flight, FetiSolveResult& solve) {
  solve = solveStep(*projection_, *projectionSteps_, massTimes(flight), "the projection of the predictor");
  return subdomains(*solve.primal);
}

DynamicStep ImplicitDynamics::step() { return advance(nullptr); }

DynamicStep ImplicitDynamics::step(const Fem::LoadCase& atNext) { return advance(&atNext); }

DynamicStep ImplicitDynamics::advance(const Fem::LoadCase* atNext) {
  const double dt = spec_.timeStep, c = massCoefficient_;
  // The loads at t_{n+1}: f of each subdomain and the Dirichlet values (the
  // problems' own, with the partners' of their contact nodes), assembled by
  // setLoads; the constructor's without other loads. (A solve leaves the
  // step's right-hand side in the problem's f.)
  Subdomains next_f = constantLoad_;
  if (atNext) {
    problem_->setLoads(*atNext);
    if (projection_) projection_->setLoads(*atNext);
    for (int k = 0; k < problem_->numLocalSubdomains(); ++k) next_f[k] = problem_->subdomain(k).f;
  }
  Subdomains flight = u_;  // u_n + dt v_n
  for (size_t k = 0; k < u_.size(); ++k)
    for (size_t i = 0; i < u_[k].size(); ++i) flight[k][i] += dt * v_[k][i];
  // (K + c M) u_{n+1} = rhs with the contact conditions on u_{n+1}:
  //   Newmark:    rhs = f + c M (u_n + dt v_n) + M a_n,
  //   stabilized: rhs = f_{n+1} + f_n - K u_n + c M w, w the projected flight.
  const bool stabilized = spec_.scheme == TimeScheme::ContactStabilizedNewmark;
  DynamicStep s;
  const Subdomains w = stabilized ? projectedPredictor(flight, s.solve) : flight;
  if (stabilized && !s.solve.verdict.converged) {  // no step from a predictor that missed its check
    recordState(s);
    return s;
  }
  const Subdomains Mw = massTimes(w);
  const Subdomains Ku = stabilized ? stiffnessTimes(u_) : Subdomains();
  Subdomains rhs = next_f;
  for (size_t k = 0; k < rhs.size(); ++k)
    for (size_t i = 0; i < rhs[k].size(); ++i)
      rhs[k][i] += c * Mw[k][i] + (stabilized ? load_[k][i] - Ku[k][i] : Ma_[k][i]);
  const FetiSolveResult projection = s.solve;
  s.solve = solveStep(*problem_, *steps_, rhs, "the contact solve");
  if (stabilized) addCost(projection, s.solve);
  const Subdomains next = subdomains(*s.solve.primal);
  // The trapezoidal rule's velocity, from the displacements: v_{n+1} =
  // v_n + 2 (u_{n+1} - w) / dt (w = u_n + dt v_n without projection); and
  // M a_{n+1} = c M (u_{n+1} - u_n - dt v_n) - M a_n.
  const Subdomains Mnext = stabilized ? Subdomains() : massTimes(next);
  double work = 0;  // (f_n + f_{n+1})' (u_{n+1} - u_n) / 2
  for (size_t k = 0; k < next.size(); ++k)
    for (size_t i = 0; i < next[k].size(); ++i) {
      work += (load_[k][i] + next_f[k][i]) / 2 * (next[k][i] - u_[k][i]);
      v_[k][i] += 2 * (next[k][i] - w[k][i]) / dt;
      if (!stabilized) Ma_[k][i] = c * (Mnext[k][i] - Mw[k][i]) - Ma_[k][i];
    }
  u_ = next;
  load_ = next_f;
  time_ += dt;
  // The step's forces as means over it; friction dissipates the mean
  // friction force against the slip of the step.
  auto& contact = s.solve.contact;
  meanForces(contact, stabilized);
  double force = 0, dissipated = 0;
  for (size_t k = 0; k < contact.nodes.size(); ++k) {
    force += contact.normalForce[k];
    dissipated += contact.frictionDissipation(k);
  }
  const auto& comm = *problem_->comm();
  externalWork_ += sumOverRanks(work, comm);
  frictionDissipation_ += sumOverRanks(dissipated, comm);
  s.contactForce = sumOverRanks(force, comm);
  recordState(s);
  return s;
}

void ImplicitDynamics::addCost(const FetiSolveResult& projection, FetiSolveResult& step) {
  step.n_A += projection.n_A;
  step.solveSeconds += projection.solveSeconds;
  step.F_applications += projection.F_applications;
  step.F_seconds += projection.F_seconds;
}

void ImplicitDynamics::recordState(DynamicStep& s) const {
  s.time = time_;
  s.kineticEnergy = kineticEnergy();
  s.strainEnergy = strainEnergy();
  s.externalWork = externalWork_;
  s.frictionDissipation = frictionDissipation_;
}

void ImplicitDynamics::meanForces(ContactNodeResults& contact, bool stabilized) {
  auto& normal = contact.normalForce;
  auto& tangential = contact.tangentialForce;
  if (lastNormal_.size() != normal.size()) lastNormal_.assign(normal.size(), 0.0);
  if (lastTangential_.size() != tangential.size()) lastTangential_.assign(tangential.size(), 0.0);
  const std::vector<double> atEnd = normal, tangentialAtEnd = tangential;
  for (size_t k = 0; k < normal.size(); ++k) normal[k] = (stabilized ? 0.0 : lastNormal_[k]) / 2 + normal[k] / 2;
  for (size_t k = 0; k < tangential.size(); ++k)
    tangential[k] = (stabilized ? 0.0 : lastTangential_[k]) / 2 + tangential[k] / 2;
  lastNormal_ = atEnd;
  lastTangential_ = tangentialAtEnd;
}

double ImplicitDynamics::kineticEnergy() const {
  const Subdomains Mv = massTimes(v_);
  double e = 0;
  for (size_t k = 0; k < v_.size(); ++k)
    for (size_t i = 0; i < v_[k].size(); ++i) e += 0.5 * v_[k][i] * Mv[k][i];
  return sumOverRanks(e, *problem_->comm());
}

double ImplicitDynamics::strainEnergy() const {
  const Subdomains Ku = stiffnessTimes(u_);
  double e = 0;
  for (size_t k = 0; k < u_.size(); ++k)
    for (size_t i = 0; i < u_[k].size(); ++i) e += 0.5 * u_[k][i] * Ku[k][i];
  return sumOverRanks(e, *problem_->comm());
}

}  // namespace Contact
}  // namespace Tribos
