// choices.cpp: every documented value of every string choice of the input
// runs end to end. The choices are read from the validators of the valid
// parameters (Input::validParameters() and the item lists of conditions
// and contact pairs), so a value added to a choice is run here without a
// word of this file changing:
//
//   choices --source DIR --work DIR
//
// Each value is set by --set on tiny problems where its parameter is read
// (the prefix rules below name them, the nearest first) and the driver is
// called as a function on every rank (driver_call.hpp). A value passes when
// one of its problems converges (exit 0); the problems before it may refuse
// the value (exit 1) with a message that names the parameter (a value that
// does not apply to a problem, e.g. Algorithm1 for Coulomb friction).
// Any other exit (2: not converged, 3: a value accepted and then refused by
// a list built from the input) fails the value, and so does a value that no
// problem runs. One line per value; the exit code is 1 when any failed.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_Core.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "Tribos_Input.hpp"
#include "Tribos_ProcessStartup.hpp"
#include "driver_call.hpp"

namespace fs = std::filesystem;

namespace {

using Teuchos::ParameterList;

constexpr int kTimeoutSeconds = 120;

// A tiny problem: an input of the repository and what makes it tiny or
// picks what it solves.
struct Problem {
  std::string name, input;
  std::vector<std::string> sets;
};

const std::vector<Problem>& problems() {
  static const std::vector<Problem> all = {
      // (Subdomains: METIS's count, the Subdomain Grid's three boxes)
      {"linear", "input/brick_linear.xml", {"Mesh/Level=1", "Mesh/Subdomains=3", "Solver/Type=Auto"}},
      {"linear FETI", "input/brick_linear.xml", {"Mesh/Level=1", "Mesh/Subdomains=3", "Solver/Type=FETI"}},
      {"Coulomb", "input/brick_coulomb_F03.xml", {"Mesh/Level=2"}},
      {"Coulomb MSA", "input/brick_coulomb_F03.xml", {"Mesh/Level=2", "Solver/Outer Algorithm=MSA+Algorithm1"}},
      {"Coulomb Algorithm2", "input/brick_coulomb_F03.xml", {"Mesh/Level=2", "Solver/Outer Algorithm=Algorithm2"}},
      {"Coulomb Semismooth Newton", "input/brick_coulomb_F03.xml",
       {"Mesh/Level=2", "Solver/Outer Algorithm=Semismooth Newton"}},
      {"Tresca", "input/brick_coulomb_F03.xml",
       {"Mesh/Level=2", "Contact/Friction Law=Tresca", "Contact/Friction Coefficient=0.3",
        "Contact/Slip Bound Traction=1e7"}},
      {"semismooth*", "input/prism_tresca.xml", {"Mesh/Level=1"}},
      // (held in x as well, so that a frictionless or glued interface leaves
      // no body free)
      {"pairs", "input/two_blocks_coulomb.xml",
       {"Boundary Conditions/Dirichlet/symmetry x/Face=symmetry_x",
        "Boundary Conditions/Dirichlet/symmetry x/Components=x"}},
      // (pressed only: Tresca pairs solve it in a few hundred iterations)
      {"pairs Tresca", "test/data/two_blocks_pressure.xml",
       {"Contact/Friction Law=Tresca", "Contact/Slip Bound Traction=1e5"}},
  };
  return all;
}

const Problem& problem(const std::string& name) {
  for (const auto& p : problems())
    if (p.name == name) return p;
  throw std::runtime_error("no problem " + name);
}

// Where a parameter is read: the problems to try for a path, by its longest
// listed prefix.
std::vector<std::string> problemsFor(const std::string& path) {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> rules = {
      {"Solver/SemismoothStarNewton/", {"semismooth*"}},
      {"Solver/Monolithic/", {"linear"}},
      {"Solver/FETI/", {"linear FETI", "Coulomb"}},
      {"Solver/Algorithm 1/", {"Tresca"}},
      {"Solver/MSA/", {"Coulomb MSA"}},
      {"Solver/Algorithm 2/", {"Coulomb Algorithm2"}},
      {"Solver/Semismooth Newton/", {"Coulomb Semismooth Newton"}},
      {"Contact/Pairs/", {"pairs", "pairs Tresca"}},
      {"Contact/", {"Coulomb", "Tresca", "semismooth*"}},
      {"Solver/", {"Coulomb", "Tresca", "semismooth*", "linear"}},
      {"", {"linear", "linear FETI", "Coulomb"}},
  };
  const std::pair<std::string, std::vector<std::string>>* best = nullptr;
  for (const auto& rule : rules)
    if (path.rfind(rule.first, 0) == 0 && (!best || rule.first.size() > best->first.size())) best = &rule;
  return best->second;
}

// A string parameter whose validator lists its values.
struct Choice {
  std::string path;
  std::vector<std::string> values;
};

void collect(const ParameterList& valid, const std::string& path, std::vector<Choice>& out) {
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const std::string full = path.empty() ? name : path + "/" + name;
    if (valid.isSublist(name)) {
      collect(valid.sublist(name), full, out);
      continue;
    }
    const auto validator = valid.getEntry(name).validator();
    if (validator.is_null() || !valid.isType<std::string>(name)) continue;
    const auto values = validator->validStringValues();
    if (!values.is_null()) out.push_back({full, {values->begin(), values->end()}});
  }
}

// Every choice of the input: the valid list, and the items of the conditions
// and pairs under names the problems have.
std::vector<Choice> choices() {
  using namespace Tribos::Input;
  std::vector<Choice> out;
  collect(*validParameters(), "", out);
  collect(dirichletItem(), "Boundary Conditions/Dirichlet/clamped end", out);
  collect(tractionItem(), "Boundary Conditions/Traction/top", out);
  collect(curveItem(), "Load Curves/ramp", out);
  collect(pairItem(validParameters()->sublist("Contact")), "Contact/Pairs/interface", out);
  return out;
}

// Whether a refusal names the parameter: its path, or its key and the value.
bool namesParameter(const std::string& message, const std::string& path, const std::string& value) {
  const std::string key = path.substr(path.rfind('/') + 1);
  return message.find(path) != std::string::npos ||
         (message.find(key) != std::string::npos && message.find(value) != std::string::npos);
}

std::string lastLine(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  return t.substr(t.rfind('\n') == std::string::npos ? 0 : t.rfind('\n') + 1);
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  Tpetra::ScopeGuard guard(&argc, &argv);
  const auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank(), size = comm->getSize();
  std::string source, workRoot;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--source") source = argv[i + 1];
    else if (a == "--work") workRoot = argv[i + 1];
  }
  if (source.empty() || workRoot.empty()) {
    if (rank == 0) std::cerr << "usage: choices --source DIR --work DIR\n";
    return 1;
  }
  const std::string work = workRoot + "/choices_np" + std::to_string(size);
  if (rank == 0) fs::remove_all(work), fs::create_directories(work);
  comm->barrier();
  DriverCall::Capture capture;
  DriverCall::Watchdog watchdog(capture.realOut(), kTimeoutSeconds);
  const auto start = std::chrono::steady_clock::now();
  int values = 0, failed = 0, runs = 0;
  for (const Choice& choice : choices()) {
    for (const std::string& value : choice.values) {
      ++values;
      std::string verdict, tried;
      bool passed = false;
      for (const std::string& name : problemsFor(choice.path)) {
        const Problem& p = problem(name);
        std::vector<std::string> args = {source + "/" + p.input, "--quiet", "--output",
                                         work + "/run" + std::to_string(runs++)};
        for (const auto& s : p.sets) args.insert(args.end(), {"--set", s});
        args.insert(args.end(), {"--set", "Output/Write Results=false", "--set", choice.path + "=" + value});
        const auto o = DriverCall::call(args, work, choice.path + " = " + value + " on " + name, comm, capture, watchdog);
        int next = 0;  // rank 0's verdict on this problem: 1 try the next problem
        if (rank == 0) {
          const int code = o.codes[0];
          bool agree = true;
          for (int c : o.codes) agree = agree && c == code;
          const std::string message = lastLine(o.errs[0]);
          if (!agree) verdict = "the ranks exit with different codes on " + name;
          else if (code == 0) passed = true;
          else if (code != 1) verdict = "exit " + std::to_string(code) + " on " + name + ": " + message;
          else if (!namesParameter(message, choice.path, value))
            verdict = "exit 1 on " + name + " with a message that does not name the parameter: " + message;
          else next = 1, tried += "; refused on " + name + ": " + message;
        }
        Teuchos::broadcast(*comm, 0, Teuchos::outArg(next));
        if (!next) break;
      }
      if (rank != 0) continue;
      if (!passed && verdict.empty()) verdict = "no problem runs it" + tried;
      const std::string label = choice.path + " = " + value + " (np " + std::to_string(size) + ")";
      if (verdict.empty()) std::cout << "ok: " << label << tried << std::endl;
      else std::cout << "FAIL: " << label << ": " << verdict << std::endl, ++failed;
    }
  }
  if (rank == 0)
    std::cout << values - failed << " of " << values << " values of the input's choices run, in " << runs
              << " calls, " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s" << std::endl;
  Teuchos::broadcast(*comm, 0, Teuchos::outArg(failed));
  return failed == 0 ? 0 : 1;
}
