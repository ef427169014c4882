// A load history solved step by step (Contact::FetiLoadSteps) against its
// exact solution: the sliding block.
//
// A block [0,1]^3 (nu = 0, so compression does not spread it sideways) lies
// on a rigid plane with Coulomb friction F. Its top is held at
// u = (a(t), 0, -delta): pressed by p = E delta / H, then dragged forward past
// the stick limit and back. The x faces carry the tractions -+tau e_z of the
// uniform stress state (sigma_xz = tau, sigma_zz = -p), so the exact solution
// is uniform: the bottom at u_x = b, the shear stress tau = G (a - b) / H,
// and b follows the one-dimensional stick-slip rule with memory:
//   trial tau = G (a_k - b_{k-1}) / H;  |trial| <= F p: stick, b_k = b_{k-1};
//   else slip, b_k = a_k - sign(trial) F p H / G,  tau = sign(trial) F p.
// Trilinear hexahedra reproduce these linear fields exactly, so every node
// must match to the solver's tolerance: in stick steps the slip increment is
// zero, in slip steps |t_T| = F t_N against the motion, and after the
// reversal the block sticks for exactly the travel 2 F p H / G that the
// elastic shear stiffness gives.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <vector>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_FetiSolve.hpp"

namespace {

using namespace Tribos;

constexpr double kE = 1000.0, kH = 1.0, kDelta = 0.01, kF = 0.3;
constexpr double kG = kE / 2.0;               // nu = 0
constexpr double kP = kE * kDelta / kH;       // contact pressure
constexpr double kTauMax = kF * kP;           // stick limit of the shear stress

struct Exact {
  double a, b, tau;
  bool slip;
};

// The history of the bottom displacement b for the top displacements a.
std::vector<Exact> exactHistory(const std::vector<double>& a) {
  std::vector<Exact> out;
  double b = 0;
  for (double ak : a) {
    const double trial = kG * (ak - b) / kH;
    Exact e{ak, b, trial, false};
    if (std::abs(trial) > kTauMax) {
      e.slip = true;
      e.tau = std::copysign(kTauMax, trial);
      e.b = b = ak - e.tau * kH / kG;
    }
    out.push_back(e);
  }
  return out;
}

Mesh::Discretization block(const Comm& comm) {
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Hex8;
  spec.cells = {3, 2, 2};
  Mesh::DecompositionSpec dec;
  dec.grid = {3, 1, 1};
  return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
}

Fem::LoadCase loadsAt(const Exact& e) {
  Fem::LoadCase l;
  Fem::DirichletCondition top;
  top.face = "zmax";
  top.value = {e.a, 0.0, -kDelta};
  l.dirichlet = {top};
  l.tractions = {{"xmin", {0, 0, -e.tau}}, {"xmax", {0, 0, e.tau}}};
  return l;
}

Teuchos::ParameterList tight() {
  Teuchos::ParameterList p;
  p.set("Outer Algorithm", "Algorithm2");
  p.sublist("Algorithm 2").set("Relative Tolerance", 1e-11);
  p.sublist("Algorithm 2").set("Slip Bound Tolerance", 1e-10);
  return p;
}

Contact::FrictionSpec coulomb() {
  Contact::FrictionSpec f;
  f.law = FrictionLaw::Coulomb;
  f.coefficient = kF;
  return f;
}

RCP<Feti::FetiProblem> problemAt(const Mesh::Discretization& disc, const Exact& first, const RCP<const Comm>& comm) {
  Contact::ContactSpec contact;
  contact.enabled = true;
  return rcp(new Feti::FetiProblem(disc, Fem::Material{kE, 0.0}, loadsAt(first),
                                   Contact::faceContactConstraints(disc, contact, comm), Teuchos::ParameterList(), comm));
}

// The largest deviation, over this rank's nodes, of u from the uniform
// field of e (relative to delta), and of the contact forces from p and tau
// times the nodal area (relative to F p times the area).
struct Deviation {
  double displacement = 0, normalForce = 0, tangentialForce = 0, slip = 0;
  int stickNodes = 0, slipNodes = 0;
};

Deviation deviation(const Feti::FetiProblem& problem, const Contact::FetiSolveResult& r, const Exact& e) {
  const auto& disc = problem.discretization();
  Deviation d;
  for (int node : r.u.layout().nodes()) {
    const auto& x = disc.part.coords.at(disc.partNode(node));
    const double z = x[2] / kH;
    const double expected[3] = {e.b + (e.a - e.b) * z, 0.0, -kDelta * z};
    for (int c = 0; c < 3; ++c)
      d.displacement = std::max(d.displacement, std::abs(r.u.at(node)[c] - expected[c]) / kDelta);
  }
  const auto& cn = r.contact;
  for (size_t k = 0; k < cn.nodes.size(); ++k) {
    const double area = cn.constraint[k].area;
    d.normalForce = std::max(d.normalForce, std::abs(cn.normalForce[k] - kP * area) / (kP * area));
    // The friction force on the body opposes the shear the top imposes.
    d.tangentialForce = std::max(d.tangentialForce, std::abs(cn.tangentialForce[3 * k] + e.tau * area) / (kTauMax * area));
    d.tangentialForce = std::max({d.tangentialForce, std::abs(cn.tangentialForce[3 * k + 1]) / (kTauMax * area),
                                  std::abs(cn.tangentialForce[3 * k + 2]) / (kTauMax * area)});
    // The slip written is the total relative tangential displacement: b.
    d.slip = std::max(d.slip, std::abs(cn.slip[3 * k] - e.b) / kDelta);
    d.stickNodes += cn.status[k] == 1;
    d.slipNodes += cn.status[k] == 2;
  }
  return d;
}

TEUCHOS_UNIT_TEST(LoadSteps, SlidingBlockFollowsTheStickSlipHistory) {
  const auto comm = Tpetra::getDefaultComm();
  const auto disc = block(*comm);
  // Dragged forward past the limit, then back past the limit the other way.
  const auto history = exactHistory({0.0, 0.004, 0.009, 0.012, 0.008, 0.004, 0.001, -0.004});
  auto problem = problemAt(disc, history.front(), comm);
  Contact::FetiLoadSteps steps(problem, {coulomb()}, tight());
  for (size_t k = 0; k < history.size(); ++k) {
    const Exact& e = history[k];
    const auto r = steps.solve(loadsAt(e));
    const Deviation d = deviation(*problem, r, e);
    int stick = 0, slip = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, d.stickNodes, Teuchos::outArg(stick));
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, d.slipNodes, Teuchos::outArg(slip));
    double worst[4] = {d.displacement, d.normalForce, d.tangentialForce, d.slip}, all[4];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 4, worst, all);
    out << "step " << k + 1 << ": a = " << e.a << ", b = " << e.b << (e.slip ? " slip" : " stick")
        << "; deviations u " << all[0] << ", t_N " << all[1] << ", t_T " << all[2] << ", slip " << all[3]
        << "; stick/slip nodes " << stick << "/" << slip << "; KKT " << r.kkt.worst() << ", n_A " << r.n_A << "\n";
    TEST_ASSERT(r.verdict.converged);
    TEST_COMPARE(all[0], <, 1e-7);
    TEST_COMPARE(all[1], <, 1e-6);
    TEST_COMPARE(all[2], <, 1e-6);
    TEST_COMPARE(all[3], <, 1e-7);
    // Every contact node in the state of the exact solution (a stick step
    // whose shear is below the limit; every slip step at it).
    TEST_EQUALITY(slip, e.slip ? static_cast<int>(r.counts.nodes) : 0);
    TEST_EQUALITY(stick, e.slip ? 0 : static_cast<int>(r.counts.nodes));
  }
}

// One step is the static solve: the same problem, the same answer.
TEUCHOS_UNIT_TEST(LoadSteps, OneStepIsTheStaticSolve) {
  const auto comm = Tpetra::getDefaultComm();
  const auto disc = block(*comm);
  const Exact e{0.009, 0.0, 0.0, false};  // loaded once: past the limit
  auto problem = problemAt(disc, e, comm);
  const auto reference = Contact::solveFeti(problem, coulomb(), tight());
  Contact::FetiLoadSteps steps(problemAt(disc, e, comm), {coulomb()}, tight());
  const auto r = steps.solve(loadsAt(e));
  const auto a = reference.u.gathered(), b = r.u.gathered();
  double diff = 0, scale = 0;
  for (size_t i = 0; i < a.size(); ++i) diff = std::max(diff, std::abs(a[i] - b[i])), scale = std::max(scale, std::abs(a[i]));
  out << "|u_step - u_static| / |u| = " << diff / scale << "\n";
  TEST_COMPARE(diff / scale, <, 1e-12);
  TEST_EQUALITY(r.counts.slip, reference.counts.slip);
}

// Loaded and unloaded below the stick limit, the block returns exactly to
// its unloaded state; past the limit, it keeps exactly the predicted slip.
TEUCHOS_UNIT_TEST(LoadSteps, UnloadingReturnsOrKeepsThePredictedSlip) {
  const auto comm = Tpetra::getDefaultComm();
  const auto disc = block(*comm);
  for (double peak : {0.004, 0.010}) {
    const auto history = exactHistory({0.0, peak, 0.0});
    Contact::FetiLoadSteps steps(problemAt(disc, history.front(), comm), {coulomb()}, tight());
    Contact::FetiSolveResult last;
    for (const auto& e : history) last = steps.solve(loadsAt(e));
    // Unloaded: the top back at a = 0 with the bottom where it was left.
    double residual = 0;
    for (size_t k = 0; k < last.contact.nodes.size(); ++k)
      residual = std::max(residual, std::abs(last.contact.slip[3 * k] - history.back().b));
    double all = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, residual, Teuchos::outArg(all));
    out << "peak " << peak << ": residual slip " << history.back().b << " predicted, deviation " << all << "\n";
    TEST_COMPARE(all / kDelta, <, 1e-7);
    TEST_ASSERT((peak > kTauMax * kH / kG) == (history.back().b != 0.0));
  }
}

}  // namespace
