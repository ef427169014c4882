// Export of a FETI contact problem as an FCLIB global problem, read back and
// solved through the FCLIB path (W = H'M^-1 H): the brick of the contact
// tests (Tet4 6x2x2 on (0,3)x(0,1)x(0,1), 3 subdomains, clamped xmin,
// contact on zmin, Coulomb F = 0.3). Checks the sign conventions: the
// exported FETI solution satisfies M v = H r + f and Coulomb's law in the
// FCLIB form (small err), and the FCLIB solve gives the FETI displacement.
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

#include "Tribos_FCLIB_Export.hpp"
#include "Tribos_FCLIB_Solve.hpp"
#include "Tribos_FetiContact.hpp"
#include "Tribos_FetiDual.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;

namespace {

double relDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]) * (a[i] - b[i]), n += b[i] * b[i];
  return std::sqrt(d / std::max(n, 1e-300));
}

// The brick solved by FETI (Algorithm 2), exported and read back on rank 0;
// done once for all cases, the file removed once read.
struct Exported {
  bool converged = false;
  std::string reason;
  std::vector<double> uFeti;
  FCLIB::GlobalProblem p;
  std::optional<FCLIB::Solution> stored;
};

const Exported& exported() {
  static const Exported e = [] {
    Exported e;
    auto comm = Tpetra::getDefaultComm();
    Mesh::BoxSpec spec;
    spec.type = Mesh::CellType::Tet4;
    spec.x = {0, 3};
    spec.cells = {6, 2, 2};
    Mesh::DecompositionSpec dec;
    dec.grid = {3, 1, 1};
    const Mesh::Mesh whole = Mesh::generateBox(spec);
    Mesh::Discretization disc(whole, spec, dec, comm->getSize(), comm->getRank());
    Fem::LoadCase loads;
    Fem::DirichletCondition clamp;
    clamp.face = "xmin";
    loads.dirichlet = {clamp};
    loads.tractions = {{"zmax", {0, 0, -4e7}}, {"xmax", {-2e7, 0, 0}}};
    const Fem::Material steel{21.2e10, 0.277};
    const double F = 0.3;

    Contact::ContactSpec contact;
    contact.enabled = true;
    auto problem = rcp(new Feti::FetiProblem(disc, steel, loads, Contact::faceContactConstraints(disc, contact, comm),
                                             Teuchos::ParameterList(), comm));
    auto dual = rcp(new Feti::FetiDual(problem));
    Contact::FrictionSpec fs;
    fs.law = FrictionLaw::Coulomb;
    fs.coefficient = F;
    Contact::FetiContactProblem cp(dual, fs);
    Teuchos::ParameterList tight;
    tight.sublist("Algorithm 2").set("Relative Tolerance", 1e-10);
    tight.sublist("Algorithm 2").set("Slip Bound Tolerance", 1e-10);
    const auto sol = cp.solve("Algorithm2", tight);
    e.converged = sol.status.converged;
    e.reason = sol.status.reason;
    e.uFeti = problem->nodalDisplacement(*sol.u).gathered();

    const std::string path = fclib_test::scratchPath("export", "brick.hdf5");
    FCLIB::Info info{"Tribos brick", "Tet4 6x2x2, 3 subdomains, clamped xmin, contact zmin, Coulomb F = 0.3",
                     "exported from a FETI solution"};
    FCLIB::exportFeti(path, *problem, whole, steel, loads, fs.law, F, *sol.u, *sol.lambda, info);
    if (comm->getRank() == 0) {
      e.p = FCLIB::readGlobal(path);
      e.stored = FCLIB::readSolution(path);
      std::remove(path.c_str());
    }
    return e;
  }();
  return e;
}

// Solves the exported problem through the FCLIB path and compares with FETI.
void solveExported(const std::string& alg, Teuchos::FancyOStream& out, bool& success) {
  const Exported& e = exported();
  if (Tpetra::getDefaultComm()->getRank() != 0) return;
  TEST_ASSERT(e.stored.has_value());
  if (!e.stored) return;
  const auto& p = e.p;
  const auto& stored = e.stored;
  auto self = Teuchos::rcp(new Teuchos::SerialComm<int>());
  FCLIB::SolveOptions opt;
  opt.algorithm = alg;
  const auto rep = FCLIB::solve(p, opt, self);
  const double dv = relDiff(rep.v, e.uFeti), dr = relDiff(rep.r, stored->r);
  std::printf("%-15s converged %d (result check %d: %s), n_A %lld, err/max %.2e, kkt %.1e %.1e %.1e, "
              "|v - u_FETI|/|u_FETI| = %.2e, |r - r_FETI|/|r_FETI| = %.2e\n",
              alg.c_str(), rep.status.converged, rep.converged, rep.stopReason.c_str(), rep.n_A,
              rep.err.relativeToMax, rep.kktNormal, rep.kktComplementarity, rep.kktFriction, dv, dr);
  // phi mixes forces (r ~ 1e6 N) and displacements (u ~ 1e-5 m), so err/||q|| is
  // dominated by the force scale; the max-normalized measure is the meaningful one here.
  TEST_COMPARE(rep.err.relativeToMax, <=, 1e-8);  // err/max
  TEST_ASSERT(rep.converged);  // result check
  TEST_COMPARE(dv, <=, 1e-6);  // FCLIB v vs FETI u
  TEST_COMPARE(dr, <=, 1e-5);  // FCLIB r vs FETI multipliers
}

}  // namespace

// The FETI solution, and the stored one in FCLIB form: equilibrium and
// Coulomb's law.
TEUCHOS_UNIT_TEST(Export, StoredFetiSolution) {
  const Exported& e = exported();
  out << "FETI Algorithm 2: " << e.reason << "\n";
  TEST_ASSERT(e.converged);
  if (Tpetra::getDefaultComm()->getRank() != 0) return;
  const auto& p = e.p;
  const auto& stored = e.stored;
  TEST_ASSERT(stored.has_value());  // the exported file has a solution
  if (!stored) return;
  TEST_EQUALITY(p.numberOfContacts(), 18);  // the 21 zmin nodes less the 3 clamped
  std::vector<double> Mv, Hr;
  p.M.multiply(stored->v, Mv);
  p.H.multiply(stored->r, Hr);
  double res = 0, nf = 0;
  for (size_t i = 0; i < Mv.size(); ++i) res += std::pow(Mv[i] - Hr[i] - p.f[i], 2), nf += p.f[i] * p.f[i];
  const double equilibrium = std::sqrt(res / nf);
  FCLIB::MassSolver M(p.M, "KLU2");
  const auto errFeti = FCLIB::naturalMapError(p, stored->r, M.function());
  std::printf("stored FETI solution: ||Mv - Hr - f||/||f|| = %.2e, err = %.2e, err/max = %.2e\n", equilibrium,
              errFeti.relativeToQ, errFeti.relativeToMax);
  TEST_COMPARE(equilibrium, <, 1e-8);  // M v = H r + f
  TEST_COMPARE(errFeti.relativeToMax, <, 1e-6);  // Coulomb's law
  double maxRN = 0;
  for (int k = 0; k < p.numberOfContacts(); ++k) maxRN = std::max(maxRN, stored->r[3 * k]);
  TEST_COMPARE(maxRN, >, 0);  // some contact is in compression
}

TEUCHOS_UNIT_TEST(Export, SolveAlgorithm2) { solveExported("Algorithm2", out, success); }
TEUCHOS_UNIT_TEST(Export, SolveMSAAlgorithm1) { solveExported("MSA+Algorithm1", out, success); }
