// factory.cpp: solvers by name, parameter validation (a misspelled key or a
// bad value throws naming it), parameters reaching the solver (iteration
// limit, setTolerance), and verbosity-gated output on a given stream.
#include <Teuchos_ParameterList.hpp>

#include "QPTestUtils.hpp"
#include "Tribos_QP_Factory.hpp"
#include "Tribos_QP.hpp"

using namespace qptest;
using namespace Tribos::QP;

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  Checker check(*comm);
  try {
    QPSolverFactory factory;
    const auto names = factory.supportedSolverNames();
    check(names.size() == 3, "three solver names");
    for (const auto& name : names) {
      auto s = factory.create(name, Teuchos::null);
      check(!s.is_null(), "create " + name);
      check(s->getValidParameters()->isParameter("Relative Tolerance"), name + ": has Relative Tolerance");
    }
    std::string msg;
    check(throwsWith([&] { factory.create("CG", Teuchos::null); }, "MPRGP, MPGP, SMALBE", &msg),
          "unknown name lists the valid names: " + msg);

    auto misspelled = Teuchos::rcp(new Teuchos::ParameterList);
    misspelled->set("Relative Tolerence", 1e-6);
    check(throwsWith([&] { factory.create("MPRGP", misspelled); }, "Relative Tolerence", &msg), "misspelled key named");
    auto badVerbosity = Teuchos::rcp(new Teuchos::ParameterList);
    badVerbosity->set("Verbosity", std::string("Loud"));
    check(throwsWith([&] { factory.create("MPGP", badVerbosity); }, "Loud", &msg), "bad Verbosity value named");
    auto badAlpha = Teuchos::rcp(new Teuchos::ParameterList);
    badAlpha->set("Alpha Bar", 3.0);
    check(throwsWith([&] { factory.create("MPGP", badAlpha); }, "Alpha Bar", &msg), "Alpha Bar > 2 rejected");
    auto badInner = Teuchos::rcp(new Teuchos::ParameterList);
    badInner->sublist("Inner Solver").set("Type", std::string("CG"));
    check(throwsWith([&] { factory.create("SMALBE", badInner); }, "CG", &msg), "bad inner Type named");
    auto badInnerKey = Teuchos::rcp(new Teuchos::ParameterList);
    badInnerKey->sublist("Inner Solver").set("Gama", 1.0);
    check(throwsWith([&] { factory.create("SMALBE", badInnerKey); }, "Gama", &msg), "misspelled inner key named");
    auto defaults = Teuchos::rcp(new Teuchos::ParameterList);
    factory.create("SMALBE", defaults);
    check(defaults->get<double>("eta") == 0.1 && defaults->get<double>("beta") == 2.0 &&
              defaults->sublist("Inner Solver").get<std::string>("Type") == "MPGP",
          "SMALBE defaults filled in");

    // a small problem with lower bounds
    const int n = 20;
    auto map = pairMap(n, comm);
    Dense Ad = randomSPD(n, 5);
    auto A = toCrs(map, Ad);
    auto b = toVector(map, randomVec(n, 6, -1, 1));
    SetSpec spec{std::string(n, 'L'), Vec(n, 0.0), Vec(n, inf), {}};
    ConstraintSet Omega = makeSet(map, spec);
    const double normB = b->norm2();

    auto limited = Teuchos::rcp(new Teuchos::ParameterList);
    limited->set("Maximum Iterations", 2);
    Vector x(map);
    QPStatus st = factory.create("MPRGP", limited)->solve(*A, *b, Omega, x);
    check(!st.converged && st.iterations == 2, "Maximum Iterations reaches the solver");

    auto tight = Teuchos::rcp(new Teuchos::ParameterList);
    tight->set("Relative Tolerance", 1e-12);
    auto solver = factory.create("MPRGP", tight);
    x.putScalar(0.0);
    QPStatus stTight = solver->solve(*A, *b, Omega, x);
    check(stTight.converged && stTight.norm_gP <= 1e-12 * normB, "rtol 1e-12 reached");
    solver->setTolerance(1e-2 * normB);
    x.putScalar(0.0);
    QPStatus stLoose = solver->solve(*A, *b, Omega, x);
    check(stLoose.converged && stLoose.norm_gP <= 1e-2 * normB && stLoose.iterations < stTight.iterations,
          "setTolerance overrides: " + std::to_string(stLoose.iterations) + " < " + std::to_string(stTight.iterations));

    // output: nothing at "None", a summary at "Low", iterations at "Medium"
    for (std::string level : {"None", "Low", "Medium"}) {
      std::ostringstream os;
      auto out = Teuchos::getFancyOStream(Teuchos::rcpFromRef(os));
      auto pl = Teuchos::rcp(new Teuchos::ParameterList);
      pl->set("Verbosity", level);
      auto s = factory.create("MPGP", pl);
      s->setOutputStream(out);
      x.putScalar(0.0);
      s->solve(*A, *b, Omega, x);
      const std::string text = os.str();
      if (level == "None") check(text.empty(), "Verbosity None prints nothing");
      if (level == "Low") check(text.find("MPGP: converged") != std::string::npos && text.find(" it ") == std::string::npos,
                                "Verbosity Low prints the summary only: " + text);
      if (level == "Medium") check(text.find(" it ") != std::string::npos, "Verbosity Medium prints iterations");
    }
  } catch (const std::exception& e) {
    check(false, std::string("unexpected exception: ") + e.what());
  }
  return check.finish(*comm);
}
