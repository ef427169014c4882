// kkt.cpp: the computed solution of the prism (L = 4; and L = 3 with a gap
// of 2.5e-4, a tenth of max |u|, and per-node step sizes) satisfies the Tresca
// KKT conditions node by node, checked from the full displacement u and the
// contact forces alone, with K and f of the unreduced problem and frames of
// its own (n from the problem, u_t = u - (u.n) n):
//   (K u - f)_j + (B' lambda)_j = 0 at every unprescribed dof j,
//   B' lambda at contact node i = lambdaN_i n_i + lambdaT_i,
//   u_n <= d,  lambdaN >= 0,  lambdaN (u_n - d) = 0,  ||lambdaT|| <= g,
//   ||lambdaT|| < g => u_t = 0,  u_t != 0 => lambdaT = g u_t / ||u_t||.
// Tolerances: equilibrium 1e-6 ||f|| (the stopping rule is 1e-8 ||l|| on the
// reduced residual); the pointwise conditions 1e-9 relative to the node's
// scale (they hold by construction of the approximation step up to rounding).
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>

#include "PrismProblem.hpp"

namespace {

using namespace Tribos;

void checkKKT(const Semismooth::MeshContactProblem& pr, const Teuchos::ParameterList& params, bool allZones,
              Teuchos::FancyOStream& out, bool& success) {
  const Semismooth::ContactProblem p =
      Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace, pr.gap, pr.slipBoundTraction);
  Semismooth::SemismoothStarNewton solver(p, params);
  const Semismooth::SemismoothResult r = solver.solve(&out);
  TEST_ASSERT(r.converged);
  const int n = p.K.rows, m = static_cast<int>(p.contact.size());
  TEST_EQUALITY(static_cast<int>(r.u.size()), n);

  // Equilibrium at the unprescribed dofs.
  std::vector<double> res(n);
  p.K.multiply(r.u.data(), res.data());
  for (int j = 0; j < n; ++j) res[j] -= p.f[j];
  double umax = 0;
  for (double v : r.u) umax = std::max(umax, std::abs(v));
  for (int i = 0; i < m; ++i) {
    const auto& nn = p.contact[i].normal;
    const double len = std::sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    for (int c = 0; c < 3; ++c) res[3 * p.contact[i].node + c] += r.lambdaN[i] * nn[c] / len + r.lambdaT[i][c];
  }
  double rn = 0, fn = 0;
  for (int j = 0; j < n; ++j) {
    fn += p.f[j] * p.f[j];
    if (!p.dirichlet.count(j)) rn += res[j] * res[j];
  }
  out << "equilibrium residual " << std::sqrt(rn / fn) << " ||f||\n";
  TEST_COMPARE(std::sqrt(rn), <=, 1e-6 * std::sqrt(fn));
  // Prescribed dofs keep their values.
  for (const auto& [dof, value] : p.dirichlet) TEST_EQUALITY(r.u[dof], value);

  int stick = 0, slip = 0, contact = 0;
  for (int i = 0; i < m; ++i) {
    const auto& node = p.contact[i];
    double nv[3], un = 0;
    const double len = std::sqrt(node.normal[0] * node.normal[0] + node.normal[1] * node.normal[1] +
                                 node.normal[2] * node.normal[2]);
    for (int c = 0; c < 3; ++c) nv[c] = node.normal[c] / len;
    for (int c = 0; c < 3; ++c) un += r.u[3 * node.node + c] * nv[c];
    double ut[3], lt[3], utn = 0, ltn = 0, ltDotN = 0;
    for (int c = 0; c < 3; ++c) {
      ut[c] = r.u[3 * node.node + c] - un * nv[c];
      lt[c] = r.lambdaT[i][c];
      utn += ut[c] * ut[c];
      ltn += lt[c] * lt[c];
      ltDotN += lt[c] * nv[c];
    }
    utn = std::sqrt(utn);
    ltn = std::sqrt(ltn);
    const double uTol = 1e-9 * umax, gTol = 1e-9 * std::max(node.g, 1.0);
    const double lnScale = std::max(std::abs(r.lambdaN[i]), node.g) + 1.0;
    out << "node " << node.node << "\n";
    TEST_COMPARE(std::abs(ltDotN), <=, gTol);                // no normal part in the tangential force
    TEST_COMPARE(un, <=, node.d + uTol);                     // no penetration
    TEST_COMPARE(r.lambdaN[i], >=, -1e-9 * lnScale);         // lambda_n >= 0
    TEST_COMPARE(std::abs(r.lambdaN[i] * (un - node.d)), <=, 1e-9 * lnScale * umax);  // complementarity
    TEST_COMPARE(ltn, <=, node.g + gTol);                    // ||lambda_t|| <= g
    if (r.lambdaN[i] > 0) ++contact;
    if (utn <= uTol) {
      ++stick;
    } else {
      ++slip;
      double err = 0;
      for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(lt[c] - node.g * ut[c] / utn));
      TEST_COMPARE(err, <=, 1e-8 * node.g);  // slipping: lambda_t = g u_t/||u_t||
    }
    if (ltn < node.g * (1 - 1e-8)) TEST_COMPARE(utn, <=, uTol);  // no slip below the bound
  }
  out << "max |u| " << umax << ", gap " << p.contact[0].d << "; contact " << contact << ", no contact " << m - contact << ", stick " << stick << ", slip " << slip
            << "\n";
  if (allZones) {
    // The benchmark shows contact, no contact, stick and slip.
    TEST_COMPARE(contact, >, 0);
    TEST_COMPARE(contact, <, m);
    TEST_COMPARE(stick, >, 0);
    TEST_COMPARE(slip, >, 0);
  } else {
    TEST_COMPARE(contact, >, 0);
  }
  // The solver's counts are the ones found here.
  TEST_EQUALITY(contact, r.numContact.back());
  TEST_EQUALITY(stick, r.numStick.back());
  TEST_EQUALITY(slip, r.numSlip.back());
}

}  // namespace

// The benchmark as given.
TEUCHOS_UNIT_TEST(KKT, PrismLevel4) {
  Semismooth::MeshContactProblem pr = sstest::prism(4);
  checkKKT(pr, pr.solverParams, true, out, success);
}

// A positive gap (a tenth of the largest contact displacement scale) and
// per-node step sizes.
TEUCHOS_UNIT_TEST(KKT, PrismLevel3GapNodalSteps) {
  Semismooth::MeshContactProblem pg = sstest::prism(3);
  pg.gap = 2.5e-4;
  Teuchos::ParameterList nodal = pg.solverParams;
  nodal.set("Step Scaling", "Nodal");
  checkKKT(pg, nodal, false, out, success);
}
