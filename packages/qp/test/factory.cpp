// factory.cpp: solvers by name, parameter validation (a misspelled key or a
// bad value throws naming it), parameters reaching the solver (iteration
// limit, setTolerance), and verbosity-gated output on a given stream.
#include <Teuchos_ParameterList.hpp>

#include "QPTestUtils.hpp"
#include "Tribos_QP_Factory.hpp"
#include "Tribos_QP.hpp"

using namespace qptest;
using namespace Tribos::QP;

namespace {

// A small problem with lower bounds.
struct Small {
  static constexpr int n = 20;
  RCP<const Map> map = pairMap(n, Tpetra::getDefaultComm());
  RCP<CrsMatrix> A = toCrs(map, randomSPD(n, 5));
  RCP<Vector> b = toVector(map, randomVec(n, 6, -1, 1));
  ConstraintSet Omega = makeSet(map, SetSpec{std::string(n, 'L'), Vec(n, 0.0), Vec(n, inf), {}});
  double normB = b->norm2();
};

}  // namespace

TEUCHOS_UNIT_TEST(Factory, SolverNames) {
  QPSolverFactory factory;
  const auto names = factory.supportedSolverNames();
  TEST_EQUALITY(names.size(), 3u);  // three solver names
  for (const auto& name : names) {
    out << name << "\n";
    auto s = factory.create(name, Teuchos::null);
    TEST_ASSERT(!s.is_null());  // create
    TEST_ASSERT(s->getValidParameters()->isParameter("Relative Tolerance"));  // has Relative Tolerance
  }
  std::string msg;
  TEST_ASSERT(throwsWith([&] { factory.create("CG", Teuchos::null); }, "MPRGP, MPGP, SMALBE", &msg));  // unknown name lists the valid names
}

// A misspelled key or a bad value throws naming it; defaults are filled in.
TEUCHOS_UNIT_TEST(Factory, ParameterValidation) {
  QPSolverFactory factory;
  std::string msg;
  auto misspelled = Teuchos::rcp(new Teuchos::ParameterList);
  misspelled->set("Relative Tolerence", 1e-6);
  TEST_ASSERT(throwsWith([&] { factory.create("MPRGP", misspelled); }, "Relative Tolerence", &msg));  // misspelled key named
  auto badVerbosity = Teuchos::rcp(new Teuchos::ParameterList);
  badVerbosity->set("Verbosity", std::string("Loud"));
  TEST_ASSERT(throwsWith([&] { factory.create("MPGP", badVerbosity); }, "Loud", &msg));  // bad Verbosity value named
  auto badAlpha = Teuchos::rcp(new Teuchos::ParameterList);
  badAlpha->set("Alpha Bar", 3.0);
  TEST_ASSERT(throwsWith([&] { factory.create("MPGP", badAlpha); }, "Alpha Bar", &msg));  // Alpha Bar > 2 rejected
  auto badInner = Teuchos::rcp(new Teuchos::ParameterList);
  badInner->sublist("Inner Solver").set("Type", std::string("CG"));
  TEST_ASSERT(throwsWith([&] { factory.create("SMALBE", badInner); }, "CG", &msg));  // bad inner Type named
  auto badInnerKey = Teuchos::rcp(new Teuchos::ParameterList);
  badInnerKey->sublist("Inner Solver").set("Gama", 1.0);
  TEST_ASSERT(throwsWith([&] { factory.create("SMALBE", badInnerKey); }, "Gama", &msg));  // misspelled inner key named
  auto defaults = Teuchos::rcp(new Teuchos::ParameterList);
  factory.create("SMALBE", defaults);
  TEST_ASSERT(defaults->get<double>("eta") == 0.1);
  TEST_ASSERT(defaults->get<double>("beta") == 2.0);
  TEST_ASSERT(defaults->sublist("Inner Solver").get<std::string>("Type") == "MPGP");  // SMALBE defaults filled in
}

TEUCHOS_UNIT_TEST(Factory, MaximumIterationsReachesSolver) {
  QPSolverFactory factory;
  Small p;
  auto limited = Teuchos::rcp(new Teuchos::ParameterList);
  limited->set("Maximum Iterations", 2);
  Vector x(p.map);
  QPStatus st = factory.create("MPRGP", limited)->solve(*p.A, *p.b, p.Omega, x);
  TEST_ASSERT(!st.converged);
  TEST_EQUALITY(st.iterations, 2);  // Maximum Iterations reaches the solver
}

TEUCHOS_UNIT_TEST(Factory, ToleranceAndSetTolerance) {
  QPSolverFactory factory;
  Small p;
  Vector x(p.map);
  auto tight = Teuchos::rcp(new Teuchos::ParameterList);
  tight->set("Relative Tolerance", 1e-12);
  auto solver = factory.create("MPRGP", tight);
  x.putScalar(0.0);
  QPStatus stTight = solver->solve(*p.A, *p.b, p.Omega, x);
  TEST_ASSERT(stTight.converged);
  TEST_COMPARE(stTight.norm_gP, <=, 1e-12 * p.normB);  // rtol 1e-12 reached
  solver->setTolerance(1e-2 * p.normB);
  x.putScalar(0.0);
  QPStatus stLoose = solver->solve(*p.A, *p.b, p.Omega, x);
  TEST_ASSERT(stLoose.converged);
  TEST_COMPARE(stLoose.norm_gP, <=, 1e-2 * p.normB);
  TEST_COMPARE(stLoose.iterations, <, stTight.iterations);  // setTolerance overrides
}

TEUCHOS_UNIT_TEST(Factory, Verbosity) {
  QPSolverFactory factory;
  Small p;
  Vector x(p.map);
  // output: nothing at "None", a summary at "Low", iterations at "Medium"
  for (std::string level : {"None", "Low", "Medium"}) {
    std::ostringstream os;
    auto stream = Teuchos::getFancyOStream(Teuchos::rcpFromRef(os));
    auto pl = Teuchos::rcp(new Teuchos::ParameterList);
    pl->set("Verbosity", level);
    auto s = factory.create("MPGP", pl);
    s->setOutputStream(stream);
    x.putScalar(0.0);
    s->solve(*p.A, *p.b, p.Omega, x);
    const std::string text = os.str();
    if (level == "None") TEST_ASSERT(text.empty());  // Verbosity None prints nothing
    if (level == "Low") {  // Verbosity Low prints the summary only
      TEST_INEQUALITY(text.find("MPGP: converged"), std::string::npos);
      TEST_EQUALITY(text.find(" it "), std::string::npos);
    }
    if (level == "Medium") TEST_INEQUALITY(text.find(" it "), std::string::npos);  // Verbosity Medium prints iterations
  }
}
