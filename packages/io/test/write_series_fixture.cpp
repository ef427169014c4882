// A load history written as a run in load steps writes it (IO::StepSeries),
// with values the caller chooses, for the test of scripts/plot_history.py
// (check_plot_history.py), so that the script is tested on the files the
// library writes.
//
// usage: write_series_fixture DIR STEP [STEP ...]
//   STEP = time,delta,force,stick,slip (numbers)
// The unit box (4 x 2 x 2 cells) moves as a whole by u = (delta, 0, delta/4)
// at a step. Two contact pairs: "top" (the nodes at z = 1, normal +z) and
// "side" (the nodes at x = 1 below it, normal +x). The summary's step lists
// the tangential force (force, 0, 0) for "top" and (0, 0, force/2) for
// "side", and the contact counts stick and slip of nodes = every contact node.
// Result Base Name "cycle" in DIR.
#include <Teuchos_GlobalMPISession.hpp>
#include <Tpetra_Core.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>

#include "IoTestSupport.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_StepSeries.hpp"

using namespace Tribos;

namespace {

struct Step {
  double time, delta, force;
  long long stick, slip;
};

Step parseStep(const std::string& text) {
  Step s{};
  char comma[4];
  std::istringstream in(text);
  if (!(in >> s.time >> comma[0] >> s.delta >> comma[1] >> s.force >> comma[2] >> s.stick >> comma[3] >> s.slip) ||
      comma[0] != ',' || comma[1] != ',' || comma[2] != ',' || comma[3] != ',')
    throw std::runtime_error("a STEP is time,delta,force,stick,slip, not " + text);
  return s;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The summary of steps 1..k, with the keys a run gives each step.
std::string summaryJson(const std::vector<Step>& steps, size_t k, long long nodes) {
  std::ostringstream j;
  j << "{\n  \"problem\": \"fixture\",\n  \"steps\": [";
  for (size_t i = 0; i < k; ++i) {
    const Step& s = steps[i];
    j << (i ? ", " : "") << "{\"time\": " << number(s.time) << ", \"iterations\": " << i + 3 << ", \"n_A\": " << 10 * (i + 1)
      << ", \"kkt\": {\"stationarity\": 1e-9}, \"contact\": {\"nodes\": " << nodes
      << ", \"active\": " << s.stick + s.slip << ", \"stick\": " << s.stick << ", \"slip\": " << s.slip
      << "}, \"pairs\": [{\"name\": \"top\", \"normal_force\": -1, \"tangential_force\": [" << number(s.force)
      << ", 0, 0]}, {\"name\": \"side\", \"normal_force\": -2, \"tangential_force\": [0, 0, " << number(s.force / 2)
      << "]}], \"converged\": true}";
  }
  j << "]\n}\n";
  return j.str();
}

// Step s of the box: displacement and the contact point set of this rank's nodes.
IO::StepResult stepResult(const Mesh::Discretization& disc, const Step& s) {
  IO::StepResult r;
  IO::PointSet contact{"contact", {}, {}};
  IO::Field normalForce{"normal_force", 1, {}}, tangentialForce{"tangential_force", 3, {}}, slip{"slip", 3, {}},
      status{"status", 1, {}}, normal{"normal", 3, {}}, pair{"pair", 1, {}}, node{"node", 1, {}};
  const std::array<double, 3> u = {s.delta, 0.0, s.delta / 4};
  for (int n : disc.ownedNodes()) {
    r.uOwned.insert(r.uOwned.end(), u.begin(), u.end());
    const auto& x = disc.part.coords[n];
    const bool top = x[2] == 1.0, side = !top && x[0] == 1.0;
    if (!top && !side) continue;
    contact.coords.push_back(x);
    normalForce.values.push_back(top ? -1 : -2);
    const std::array<double, 3> t = top ? std::array<double, 3>{s.force, 0, 0} : std::array<double, 3>{0, 0, s.force / 2};
    tangentialForce.values.insert(tangentialForce.values.end(), t.begin(), t.end());
    slip.values.insert(slip.values.end(), {0.0, 0.0, 0.0});
    status.values.push_back(s.slip > 0 ? 2 : 1);
    normal.values.insert(normal.values.end(), {top ? 0.0 : 1.0, 0.0, top ? 1.0 : 0.0});
    pair.values.push_back(top ? 0 : 1);
    node.values.push_back(disc.nodeIndex()[n]);
  }
  contact.fields = {normalForce, tangentialForce, slip, status, normal, pair, node};
  r.pointSets = {contact};
  r.attributes.text = {{"problem", "fixture"}};
  return r;
}

}  // namespace

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  Tpetra::ScopeGuard tpetra(&argc, &argv);
  const auto comm = Tpetra::getDefaultComm();
  try {
    if (argc < 3) throw std::runtime_error("usage: write_series_fixture DIR STEP [STEP ...]");
    std::vector<Step> steps;
    for (int i = 2; i < argc; ++i) steps.push_back(parseStep(argv[i]));
    const Mesh::Discretization disc = Test::boxDiscretization(4, 2, 2, *comm);
    const IO::StepResult probe = stepResult(disc, steps[0]);
    const long long nodes = static_cast<long long>(
        sumOver(static_cast<double>(probe.pointSets[0].coords.size()), *comm));
    IO::OutputDirectory dir(argv[1], comm);
    IO::StepSeries series(dir, "cycle", static_cast<int>(steps.size()), comm);
    for (size_t k = 0; k < steps.size(); ++k)
      series.writeStep(static_cast<int>(k) + 1, steps[k].time, disc, stepResult(disc, steps[k]),
                       {{"cycle.parameters.xml", "<ParameterList name=\"fixture\"/>\n"},
                        {"cycle.history.csv", "step\n"},
                        {"cycle.json", summaryJson(steps, k + 1, nodes)}});
  } catch (const std::exception& e) {
    if (comm->getRank() == 0) std::cerr << "write_series_fixture: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
