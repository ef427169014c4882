// test_input_load_history.cpp: the load history of an input (Load Steps,
// Load Curves, the loads' Curve) as Tribos::Input reads it:
//  - without Load Steps the run is one step at t = 1 whose loads are
//    loadCase()'s exactly;
//  - a file's history (test/data/load_history/brick_cycle.xml) gives at
//    every step each load times its own curve (values worked out by hand),
//    the ramp min(t, 1) for a load without one;
//  - the same history given by --set, and written back by toXml, reads
//    again as the same history;
//  - a list built in memory (bypassing the file reader) is refused for a
//    non-finite time or value, a curve that is not a sublist, and a Curve no
//    curve defines, naming the parameter and the curves there are.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "Tribos_Error.hpp"
#include "Tribos_Input.hpp"
#include "Tribos_InputXml.hpp"

using namespace Tribos;
using Teuchos::Array;
using Teuchos::ParameterList;

namespace {

std::string sourceFile(const std::string& relative) {
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  return std::string(dir ? dir : ".") + "/" + relative;
}

// The message of the Tribos::Error f throws, or "" when it throws none.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Array<double> doubles(const std::vector<double>& v) { return Array<double>(v); }

bool sameLoads(const Fem::LoadCase& a, const Fem::LoadCase& b) {
  bool same = a.dirichlet.size() == b.dirichlet.size() && a.tractions.size() == b.tractions.size() &&
              a.volumeForce == b.volumeForce;
  for (size_t i = 0; same && i < a.dirichlet.size(); ++i)
    same = a.dirichlet[i].face == b.dirichlet[i].face && a.dirichlet[i].fix == b.dirichlet[i].fix &&
           a.dirichlet[i].value == b.dirichlet[i].value;
  for (size_t i = 0; same && i < a.tractions.size(); ++i)
    same = a.tractions[i].face == b.tractions[i].face && a.tractions[i].traction == b.tractions[i].traction;
  return same;
}

// brick_cycle.xml's loads at time t, by hand: Dirichlet (clamped end 0,
// support z = -1e-4 * t / 2), tractions (top -4e7 min(t, 1) in z, end -2e7
// cycle(t) in x, cycle through (0, 0), (1, 1), (1.5, -1), (2, 0)), weight
// -7.8e4 throughout.
void expectCycle(const Fem::LoadCase& at, double t, double cycle, Teuchos::FancyOStream& out, bool& success) {
  TEST_EQUALITY(at.dirichlet.size(), 2u);
  TEST_EQUALITY(at.tractions.size(), 2u);
  TEST_ASSERT(at.dirichlet[0].value == (Fem::Point{0, 0, 0}));
  TEST_FLOATING_EQUALITY(at.dirichlet[1].value[2], -1e-4 * t / 2, 1e-15);
  TEST_EQUALITY(at.tractions[0].face, "zmax");
  TEST_EQUALITY(at.tractions[0].traction[2], -4e7 * std::min(t, 1.0));
  TEST_EQUALITY(at.tractions[1].face, "xmax");
  TEST_EQUALITY(at.tractions[1].traction[0], -2e7 * cycle);
  TEST_EQUALITY(at.volumeForce[2], -7.8e4);
}

void expectCycleHistory(const ParameterList& params, Teuchos::FancyOStream& out, bool& success) {
  const std::vector<double> times = Input::loadStepTimes(params);
  TEST_ASSERT(times == (std::vector<double>{0.25, 0.5, 0.75, 1.0, 1.5, 2.0}));
  const double cycle[] = {0.25, 0.5, 0.75, 1.0, -1.0, 0.0};
  for (size_t k = 0; k < times.size(); ++k) expectCycle(Input::loadCaseAt(params, times[k]), times[k], cycle[k], out, success);
  // Between two steps as well: the curves, not a table of the steps.
  expectCycle(Input::loadCaseAt(params, 1.25), 1.25, 0.0, out, success);
}

}  // namespace

TEUCHOS_UNIT_TEST(InputLoadHistory, WithoutLoadStepsOneStepAtOne) {
  const auto params = Input::read(sourceFile("input/brick_linear.xml"), {});
  TEST_ASSERT(Input::loadStepTimes(*params) == std::vector<double>{1.0});
  TEST_ASSERT(sameLoads(Input::loadCaseAt(*params, 1.0), Input::loadCase(*params)));
  const Fem::LoadHistory history = Input::loadHistory(*params);
  for (const auto& c : history.dirichletCurves) TEST_ASSERT(c.isRamp());
  for (const auto& c : history.tractionCurves) TEST_ASSERT(c.isRamp());
  TEST_ASSERT(history.volumeForceCurve.isRamp());
  // The same input in four ramped steps: a quarter of the loads at the first.
  const auto ramped = Input::read(sourceFile("input/brick_linear.xml"), {"Load Steps/Times={0.25, 0.5, 0.75, 1}"});
  TEST_EQUALITY(Input::loadStepTimes(*ramped).size(), 4u);
  TEST_EQUALITY(Input::loadCaseAt(*ramped, 0.25).tractions[0].traction[2], -1e7);
  TEST_ASSERT(sameLoads(Input::loadCaseAt(*ramped, 1.0), Input::loadCase(*params)));
}

TEUCHOS_UNIT_TEST(InputLoadHistory, EachLoadByItsOwnCurve) {
  expectCycleHistory(*Input::read(sourceFile("test/data/load_history/brick_cycle.xml"), {}), out, success);
}

TEUCHOS_UNIT_TEST(InputLoadHistory, SetAndWrittenBackAlike) {
  // brick_linear with brick_cycle's history given on the command line.
  const auto params = Input::read(
      sourceFile("input/brick_linear.xml"),
      {"Mesh/Level=2", "Boundary Conditions/Dirichlet/clamped end/Components=xy",
       "Boundary Conditions/Dirichlet/support/Value={0, 0, -1e-4}", "Boundary Conditions/Dirichlet/support/Curve=settle",
       "Boundary Conditions/Traction/end/Curve=cycle", "Boundary Conditions/Volume Force={0, 0, -7.8e4}",
       "Boundary Conditions/Volume Force Curve=weight", "Load Steps/Times={0.25,0.5,0.75,1,1.5,2}",
       "Load Curves/cycle/Times={0, 1, 1.5, 2}", "Load Curves/cycle/Values={0, 1, -1, 0}",
       "Load Curves/settle/Times={0, 2}", "Load Curves/settle/Values={0, 1}", "Load Curves/weight/Times={0, 2}",
       "Load Curves/weight/Values={1, 1}"});
  expectCycleHistory(*params, out, success);
  // Written as the run writes BASE.parameters.xml, and read again.
  const auto file = std::filesystem::temp_directory_path() / ("tribos_load_history_" + std::to_string(getpid()) + ".xml");
  std::ofstream(file) << Input::toXml(*params);
  const auto again = Input::read(file.string(), {});
  std::filesystem::remove(file);
  expectCycleHistory(*again, out, success);
  TEST_EQUALITY(again->sublist("Load Curves").numParams(), 3);
}

TEUCHOS_UNIT_TEST(InputLoadHistory, InMemoryListsRefused) {
  const auto base = Input::read(sourceFile("test/data/load_history/brick_cycle.xml"), {});
  auto refusal = [&](auto change) {
    ParameterList p(*base);
    change(p);
    return errorOf([&] { Input::validate(p, "list"); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  TEST_ASSERT(refusal([](ParameterList&) {}).empty());
  TEST_ASSERT(contains(refusal([&](ParameterList& p) {
                         p.sublist("Load Curves").sublist("cycle").set("Values", doubles({0, 1, nan, 0}));
                       }),
                       "parameter \"Load Curves/cycle/Values\" has a component that is not a finite number"));
  TEST_ASSERT(contains(refusal([&](ParameterList& p) { p.sublist("Load Steps").set("Times", doubles({0.5, inf})); }),
                       "parameter \"Load Steps/Times\" has a component that is not a finite number"));
  TEST_ASSERT(contains(refusal([](ParameterList& p) { p.sublist("Load Curves").set("flat", 1.0); }),
                       "parameter \"Load Curves/flat\" must be a sublist with keys: Times, Values"));
  TEST_ASSERT(contains(refusal([](ParameterList& p) {
                         p.sublist("Boundary Conditions").sublist("Traction").sublist("top").set("Curve", "ramp");
                       }),
                       "parameter \"Boundary Conditions/Traction/top/Curve\" = \"ramp\": Load Curves defines no curve "
                       "of that name; its curves are: cycle, settle, weight"));
  TEST_ASSERT(contains(refusal([](ParameterList& p) { p.sublist("Load Steps").set("Times", doubles({1, 2.5})); }),
                       "parameter \"Boundary Conditions/Dirichlet/support/Curve\" = \"settle\": \"Load Curves/settle\" "
                       "is defined on [0, 2] and does not cover the step time 2.5 of Load Steps/Times"));
}
