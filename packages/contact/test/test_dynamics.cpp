// Implicit dynamics with contact (Tribos_ImplicitDynamics.hpp,
// docs/dynamics.md) on Signorini's bar: an elastic bar (nu = 0) along z,
// its lower face on the rigid plane z = 0 at t = 0, moving down at v0, free
// of any Dirichlet condition (the mass alone holds it in each step). A
// compression wave runs up at c = sqrt(E / rho) and back: the contact lasts
// 2 L / c, its force is rho c v0 A throughout, and the bar leaves with its
// initial kinetic energy. Both schemes on 1 and 2 ranks (2 subdomains
// along the bar); the default's errors fall as the step and the cells
// shrink. And a block sliding to a stop under Coulomb friction.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_ImplicitDynamics.hpp"

namespace {

using namespace Tribos;

struct Bar {
  double L = 1, side = 0.1, E = 2.1e11, rho = 7850, v0 = 1;
  int cells = 20;
  double waveSpeed() const { return std::sqrt(E / rho); }
  double contactTime() const { return 2 * L / waveSpeed(); }
  double force() const { return rho * waveSpeed() * v0 * side * side; }
  double energy() const { return 0.5 * rho * L * side * side * v0 * v0; }
};

// A box [0, a] x [0, b] x [0, c] of Hex8 cells, split into a grid of
// subdomains, its face z = 0 on the rigid plane z = 0.
struct OnThePlane {
  Mesh::BoxSpec spec;
  Mesh::Discretization disc;
  std::vector<Feti::ContactConstraint> contact;
  OnThePlane(const std::array<double, 3>& size, const std::array<int, 3>& cells, const std::array<int, 3>& grid,
             const RCP<const Comm>& comm)
      : spec(box(size, cells)), disc(Mesh::generateBox(spec), spec, decomposition(grid), comm->getSize(),
                                     comm->getRank()) {
    Contact::ContactSpec plane;
    plane.enabled = true;
    contact = Contact::faceContactConstraints(disc, plane, comm);
  }
  static Mesh::BoxSpec box(const std::array<double, 3>& size, const std::array<int, 3>& cells) {
    Mesh::BoxSpec s;
    s.type = Mesh::CellType::Hex8;
    s.x = {0, size[0]};
    s.y = {0, size[1]};
    s.z = {0, size[2]};
    s.cells = cells;
    return s;
  }
  static Mesh::DecompositionSpec decomposition(const std::array<int, 3>& grid) {
    Mesh::DecompositionSpec d;
    d.grid = grid;
    return d;
  }
};

// What the run measured, relative to the exact values.
struct Impact {
  double duration = 0, meanForce = 0, energyAfter = 0;  // relative errors
  double deepest = 0;                                   // the largest penetration / (v0 2L/c)
  int steps = 0, unconverged = 0;
};

// The bar's impact with dt = courant h / c, up to 1.5 contact times.
Impact impact(const Bar& bar, Contact::TimeScheme scheme, double courant, const RCP<const Comm>& comm) {
  const OnThePlane box({bar.side, bar.side, bar.L}, {1, 1, bar.cells}, {1, 1, 2}, comm);
  Contact::DynamicsSpec dyn;
  dyn.timeStep = courant * (bar.L / bar.cells) / bar.waveSpeed();
  dyn.scheme = scheme;
  dyn.initialVelocity = {0, 0, -bar.v0};
  Teuchos::ParameterList solver;
  solver.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-10);
  Contact::ImplicitDynamics run(box.disc, Fem::Material{bar.E, 0.0}, bar.rho, Fem::LoadCase{}, box.contact,
                                {Contact::FrictionSpec{FrictionLaw::Frictionless, 0.0, 0.0}}, dyn,
                                Teuchos::ParameterList(), solver, comm);
  Impact m;
  double first = -1, last = -1, impulse = 0, deepest = 0;
  const double floor = 1e-6 * bar.force();
  while (run.time() < 1.5 * bar.contactTime()) {
    const auto s = run.step();
    ++m.steps;
    if (!s.solve.verdict.converged) ++m.unconverged;
    if (s.contactForce > floor) {
      if (first < 0) first = s.time - dyn.timeStep;
      last = s.time;
    }
    impulse += s.contactForce * dyn.timeStep;
    for (double g : s.solve.contact.gap) deepest = std::max(deepest, -g);
  }
  double deepestAll = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, deepest, Teuchos::outArg(deepestAll));
  const double duration = last - first;
  m.duration = duration / bar.contactTime() - 1;
  m.meanForce = impulse / duration / bar.force() - 1;
  m.energyAfter = (run.kineticEnergy() + run.strainEnergy()) / bar.energy() - 1;
  m.deepest = deepestAll / (bar.v0 * bar.contactTime());
  return m;
}

void report(Teuchos::FancyOStream& out, const char* what, const Impact& m) {
  out << what << ": " << m.steps << " steps, duration " << m.duration << ", mean force " << m.meanForce
      << ", energy after " << m.energyAfter << ", deepest penetration " << m.deepest << "\n";
}

// The default scheme: within the targets on 80 cells at dt = h / c (the
// duration 5 %, the mean force 5 %, the energy after separation 2 %, no
// penetration), every error falling as h and dt halve together.
TEUCHOS_UNIT_TEST(SignoriniBar, ContactStabilizedNewmark) {
  const auto comm = Tpetra::getDefaultComm();
  std::vector<Impact> runs;
  for (int cells : {20, 40, 80}) {
    Bar bar;
    bar.cells = cells;
    runs.push_back(impact(bar, Contact::TimeScheme::ContactStabilizedNewmark, 1.0, comm));
    report(out, ("stabilized, " + std::to_string(cells) + " cells").c_str(), runs.back());
    TEST_EQUALITY(runs.back().unconverged, 0);
    TEST_COMPARE(runs.back().deepest, <=, 1e-8);
  }
  const Impact& f = runs.back();
  TEST_COMPARE(std::abs(f.duration), <=, 0.05);
  TEST_COMPARE(std::abs(f.meanForce), <=, 0.05);
  TEST_COMPARE(std::abs(f.energyAfter), <=, 0.02);
  for (size_t k = 1; k < runs.size(); ++k) {
    TEST_COMPARE(std::abs(runs[k].duration), <, std::abs(runs[k - 1].duration));
    TEST_COMPARE(std::abs(runs[k].meanForce), <, std::abs(runs[k - 1].meanForce));
    TEST_COMPARE(std::abs(runs[k].energyAfter), <, std::abs(runs[k - 1].energyAfter));
  }
}

// The trapezoidal rule with the contact conditions on u_{n+1}: the contact's
// duration and mean force come out right, but the contact nodes chatter and
// the bar leaves with several times its energy (printed; docs/dynamics.md).
TEUCHOS_UNIT_TEST(SignoriniBar, Newmark) {
  const auto comm = Tpetra::getDefaultComm();
  Bar bar;
  bar.cells = 40;
  const auto m = impact(bar, Contact::TimeScheme::Newmark, 1.0, comm);
  report(out, "Newmark, 40 cells", m);
  TEST_EQUALITY(m.unconverged, 0);
  TEST_COMPARE(std::abs(m.duration), <=, 0.05);
  TEST_COMPARE(std::abs(m.meanForce), <=, 0.05);
  TEST_COMPARE(m.deepest, <=, 1e-8);
}

// A block sliding on the plane (docs/dynamics.md): a soft cube of 0.1 m
// (E = 10 MPa, rho = 1000, so that dt = 6.8 h / c: a steel cube at this dt,
// 340 h / c, stalls in stick, docs/dynamics.md) resting on z = 0 under
// gravity g, moving along x at v0, Coulomb friction F, the default scheme.
// It decelerates at F g and stops after v0^2 / (2 F g) at t = v0 / (F g),
// having dissipated its kinetic energy in friction. 100 steps to the stop;
// the distance its nodes slid on the mean, the stop (to the step), the
// energy lost and the energy friction dissipated (summed from the contact
// forces and slips of the steps), within 2 %; the energies balance.
TEUCHOS_UNIT_TEST(SlidingBlock, StopsAfterItsDistance) {
  const auto comm = Tpetra::getDefaultComm();
  const double side = 0.1, E = 1e7, rho = 1000, g = 9.81, v0 = 1, F = 0.3;
  const double distance = v0 * v0 / (2 * F * g), stopTime = v0 / (F * g);
  const OnThePlane box({side, side, side}, {2, 2, 2}, {2, 1, 1}, comm);
  Fem::LoadCase loads;
  loads.volumeForce = {0, 0, -rho * g};
  Contact::DynamicsSpec dyn;
  dyn.timeStep = stopTime / 100;
  dyn.initialVelocity = {v0, 0, 0};
  Teuchos::ParameterList solver;
  solver.sublist("Algorithm 2").set("Relative Tolerance", 1e-9);
  Contact::ImplicitDynamics run(box.disc, Fem::Material{E, 0.3}, rho, loads, box.contact,
                                {Contact::FrictionSpec{FrictionLaw::Coulomb, F, 0.0}}, dyn, Teuchos::ParameterList(),
                                solver, comm);
  const double initial = run.kineticEnergy();
  // The block has stopped when its mean velocity along x is below 1e-3 v0.
  auto meanVelocityX = [&] {
    const auto v = run.velocity().gathered();
    double sum = 0;
    for (size_t n = 0; n < v.size() / 3; ++n) sum += v[3 * n];
    return sum / (v.size() / 3);
  };
  double stopped = -1;
  Contact::DynamicStep last;
  while (run.time() < 1.2 * stopTime) {
    last = run.step();
    TEST_ASSERT(last.solve.verdict.converged);
    if (stopped < 0 && meanVelocityX() < 1e-3 * v0) stopped = run.time();
  }
  // The energies balance: what friction dissipated is the kinetic energy the
  // block had, less what is left (its bouncing), plus the work of gravity
  // as it settles.
  const double balance =
      (last.kineticEnergy + last.strainEnergy + last.frictionDissipation - last.externalWork) / initial - 1;
  out << "dissipated by friction - initial energy " << last.frictionDissipation / initial - 1 << "; work of gravity "
      << last.externalWork / initial << ", balance " << balance << "\n";
  TEST_COMPARE(std::abs(last.frictionDissipation / initial - 1), <=, 0.02);
  TEST_COMPARE(std::abs(balance), <=, 0.02);
  const auto u = run.displacement().gathered();
  double slid = 0;
  for (size_t n = 0; n < u.size() / 3; ++n) slid += u[3 * n] / (u.size() / 3);
  const double lost = (initial - run.kineticEnergy()) / initial;
  out << "slid " << slid << " m against " << distance << " (" << slid / distance - 1 << "), stopped at " << stopped
      << " s against " << stopTime << " (" << stopped / stopTime - 1 << "), energy lost - initial " << lost - 1 << "\n";
  TEST_COMPARE(std::abs(slid / distance - 1), <=, 0.02);
  TEST_COMPARE(std::abs(stopped / stopTime - 1), <=, 0.02);
  TEST_COMPARE(std::abs(lost - 1), <=, 0.02);
}

// A run continued from a state (ImplicitDynamics::resumeFrom, what a
// restart of the driver does): the sliding block of above, 2 subdomains,
// Coulomb friction and gravity, 40 steps through; and 20 steps, then a new
// object resumed from the nodal displacement and velocity, the time and the
// running sums of the first, 20 steps more. The two ends agree to the
// solves' tolerance (1e-11; checked 1e-8, measured 3e-10 in the velocity):
// the resumed steps start from zero multipliers and from subdomain copies
// made equal. Newmark refuses to resume.
TEUCHOS_UNIT_TEST(Resume, FromAStateIsTheUninterruptedRun) {
  const auto comm = Tpetra::getDefaultComm();
  const double side = 0.1, E = 1e7, rho = 1000, g = 9.81, v0 = 1, F = 0.3;
  const OnThePlane box({side, side, side}, {2, 2, 2}, {2, 1, 1}, comm);
  Fem::LoadCase loads;
  loads.volumeForce = {0, 0, -rho * g};
  Contact::DynamicsSpec dyn;
  dyn.timeStep = v0 / (F * g) / 100;
  dyn.initialVelocity = {v0, 0, 0};
  Teuchos::ParameterList solver;
  solver.sublist("Algorithm 2").set("Relative Tolerance", 1e-11);
  solver.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-11);
  auto make = [&](Contact::TimeScheme scheme) {
    dyn.scheme = scheme;
    return std::make_unique<Contact::ImplicitDynamics>(box.disc, Fem::Material{E, 0.3}, rho, loads, box.contact,
                                                       Contact::PairFriction{{FrictionLaw::Coulomb, F, 0.0}}, dyn,
                                                       Teuchos::ParameterList(), solver, comm);
  };
  auto through = make(Contact::TimeScheme::ContactStabilizedNewmark);
  auto first = make(Contact::TimeScheme::ContactStabilizedNewmark);
  Contact::DynamicStep end, half, resumedEnd;
  for (int n = 0; n < 40; ++n) end = through->step();
  for (int n = 0; n < 20; ++n) half = first->step();
  const Contact::DynamicState state{half.time, first->displacement(), first->velocity(), half.externalWork,
                                    half.frictionDissipation};
  auto resumed = make(Contact::TimeScheme::ContactStabilizedNewmark);
  resumed->resumeFrom(state, loads);
  for (int n = 0; n < 20; ++n) resumedEnd = resumed->step();
  TEST_ASSERT(end.solve.verdict.converged && resumedEnd.solve.verdict.converged);
  auto relative = [](const std::vector<double>& a, const std::vector<double>& b) {
    double diff = 0, scale = 0;
    for (size_t i = 0; i < a.size(); ++i) diff = std::max(diff, std::abs(a[i] - b[i])), scale = std::max(scale, std::abs(b[i]));
    return diff / scale;
  };
  const double du = relative(resumed->displacement().gathered(), through->displacement().gathered());
  const double dv = relative(resumed->velocity().gathered(), through->velocity().gathered());
  const double dw = std::abs(resumedEnd.frictionDissipation - end.frictionDissipation) / end.frictionDissipation;
  const double dk = std::abs(resumedEnd.kineticEnergy - end.kineticEnergy) / through->kineticEnergy();
  out << "resumed after 20 of 40 steps: displacement " << du << ", velocity " << dv << ", dissipation " << dw
      << ", kinetic energy " << dk << " from the run through\n";
  TEST_COMPARE(std::max({du, dv, dw, dk}), <=, 1e-8);
  TEST_FLOATING_EQUALITY(resumedEnd.time, end.time, 1e-12);
  auto newmark = make(Contact::TimeScheme::Newmark);
  TEST_THROW(newmark->resumeFrom(state, loads), Error);
}

// A load on a curve in time: the bar floating free (no contact, no
// Dirichlet condition) pushed along z by a traction on its top face that
// grows linearly from 0 at t = 0, p(t) = p0 t / T. The trapezoidal rule
// integrates a load linear in time exactly into the momentum: the bar's
// mean velocity (mass-weighted; Hex8: half a node's share at the ends) is
// p0 A t^2 / (2 T m) at every step, to the solver's accuracy; the work of
// the load equals the kinetic and strain energy (no contact, no friction).
TEUCHOS_UNIT_TEST(FreeBar, LoadOnACurveGivesItsMomentum) {
  const auto comm = Tpetra::getDefaultComm();
  const Bar bar;
  const OnThePlane box({bar.side, bar.side, bar.L}, {1, 1, bar.cells}, {1, 1, 2}, comm);
  const double T = bar.contactTime(), p0 = 1e6, m = bar.rho * bar.L * bar.side * bar.side;
  auto loadsAt = [&](double t) {
    Fem::LoadCase loads;
    loads.tractions.push_back({"zmax", {0, 0, p0 * t / T}});
    return loads;
  };
  Contact::DynamicsSpec dyn;
  dyn.timeStep = T / 40;
  Contact::ImplicitDynamics run(box.disc, Fem::Material{bar.E, 0.0}, bar.rho, loadsAt(0.0), {},
                                {Contact::FrictionSpec{}}, dyn, Teuchos::ParameterList(), Teuchos::ParameterList(),
                                comm);
  const auto mesh = Mesh::generateBox(box.spec);  // the nodes' places, in gathered()'s numbering
  double worst = 0, balance = 0;
  for (int n = 1; n <= 40; ++n) {
    const double t = n * dyn.timeStep;
    const auto s = run.step(loadsAt(t));
    TEST_ASSERT(s.solve.verdict.converged);
    const auto v = run.velocity().gathered();
    double momentum = 0;
    for (int node = 0; node < mesh.numNodes(); ++node) {
      const double z = mesh.coords[node][2];
      const double share = (z == 0 || z == bar.L) ? 0.5 : 1.0;
      momentum += share * v[3 * node + 2];
    }
    const double mean = momentum / (bar.cells * 4.0);  // 4 nodes per layer, bar.cells layers of mass
    const double exact = p0 * bar.side * bar.side * t * t / (2 * T * m);
    worst = std::max(worst, std::abs(mean - exact) / exact);
    balance = (s.kineticEnergy + s.strainEnergy) / s.externalWork - 1;
  }
  out << "momentum against p0 A t^2 / (2 T m): worst " << worst << "; energies / work - 1 at the end " << balance
      << "\n";
  TEST_COMPARE(worst, <=, 1e-6);
  TEST_COMPARE(std::abs(balance), <=, 1e-6);
}

}  // namespace
