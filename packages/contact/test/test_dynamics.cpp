// Implicit dynamics with contact (Tribos_ImplicitDynamics.hpp,
// docs/dynamics.md) on Signorini's bar: an elastic bar (nu = 0) along z,
// its lower face on the rigid plane z = 0 at t = 0, moving down at v0, free
// of any Dirichlet condition (the mass alone holds it in each step). A
// compression wave runs up at c = sqrt(E / rho) and back: the contact lasts
// 2 L / c, its force is rho c v0 A throughout, and the bar leaves with its
// initial kinetic energy. Both schemes on 1 and 2 ranks (2 subdomains
// along the bar); the default's errors fall as the step and the cells
// shrink.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
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

// What the run measured, relative to the exact values.
struct Impact {
  double duration = 0, meanForce = 0, energyAfter = 0;  // relative errors
  double deepest = 0;                                   // the largest penetration / (v0 2L/c)
  int steps = 0;
};

// The bar's impact with dt = courant h / c, up to 1.5 contact times.
Impact impact(const Bar& bar, Contact::TimeScheme scheme, double courant, const RCP<const Comm>& comm) {
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Hex8;
  spec.x = spec.y = {0, bar.side};
  spec.z = {0, bar.L};
  spec.cells = {1, 1, bar.cells};
  Mesh::DecompositionSpec dec;
  dec.grid = {1, 1, 2};
  const Mesh::Discretization disc(Mesh::generateBox(spec), spec, dec, comm->getSize(), comm->getRank());
  Contact::ContactSpec plane;
  plane.enabled = true;
  const auto contact = Contact::faceContactConstraints(disc, plane, comm);
  Contact::DynamicsSpec dyn;
  dyn.timeStep = courant * (bar.L / bar.cells) / bar.waveSpeed();
  dyn.scheme = scheme;
  dyn.initialVelocity = {0, 0, -bar.v0};
  Teuchos::ParameterList solver;
  solver.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-10);
  Contact::ImplicitDynamics run(disc, Fem::Material{bar.E, 0.0}, bar.rho, Fem::LoadCase{}, contact,
                                {Contact::FrictionSpec{FrictionLaw::Frictionless, 0.0, 0.0}}, dyn,
                                Teuchos::ParameterList(), solver, comm);
  Impact m;
  double first = -1, last = -1, impulse = 0, deepest = 0;
  const double floor = 1e-6 * bar.force();
  while (run.time() < 1.5 * bar.contactTime()) {
    const auto s = run.step();
    ++m.steps;
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
  TEST_COMPARE(std::abs(m.duration), <=, 0.05);
  TEST_COMPARE(std::abs(m.meanForce), <=, 0.05);
  TEST_COMPARE(m.deepest, <=, 1e-8);
}

}  // namespace
