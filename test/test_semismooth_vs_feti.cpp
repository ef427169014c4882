// Cross-check of two independent Tresca solvers on the semismooth* prism:
// the semismooth* Newton method (primal, reduced to the contact boundary,
// one process) and FETI with Algorithm 1 (dual, subdomains over the ranks).
// Contact displacements and contact forces must agree to 1e-6 relative.
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <iostream>
#include <map>

#include "Tribos_FetiContact.hpp"
#include "Tribos_FrictionSolver.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

using namespace Tribos;

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  // The prism of input/prism_tresca.xml at level L = 3.
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Hex8;
  spec.x = {0, 2};
  spec.cells = Mesh::prismLevelCells(3);
  const Fem::Material steel{2.1e11, 0.3};
  Fem::LoadCase loads;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  loads.dirichlet = {clamp};
  loads.tractions = {{"zmax", {0, 0, -1e8}}, {"xmax", {-1e8, 0, 1e8}}};
  const double slipTraction = 5e7;

  // Semismooth* on every rank (serial method, small problem).
  auto ssParams = *Semismooth::SemismoothStarNewton::getValidParameters();
  ssParams.set("Tolerance", 1e-12);
  const auto mesh = Mesh::generateBox(spec);
  const auto ss = Semismooth::solveFromMesh(mesh, steel, loads, "zmin", 0.0, slipTraction, ssParams, nullptr);

  // FETI + Algorithm 1.
  Mesh::DecompositionSpec dec;
  dec.grid = {2, 2, 1};
  Mesh::Discretization disc(Mesh::generateBox(spec), spec, dec, comm->getSize(), comm->getRank());
  Contact::ContactSpec contact;
  contact.enabled = true;
  auto problem = rcp(new Feti::FetiProblem(disc, steel, loads, Contact::faceContactConstraints(disc, contact, comm),
                                           Teuchos::ParameterList(), comm));
  auto dual = rcp(new Feti::FetiDual(problem));
  Contact::FrictionSpec fs;
  fs.law = FrictionLaw::Tresca;
  fs.slipBoundTraction = slipTraction;
  Contact::FetiContactProblem cp(dual, fs);
  Teuchos::ParameterList p;
  p.sublist("Algorithm 1").sublist("SMALBE").set("Relative Tolerance", 1e-10);
  const auto sol = cp.solve("Tresca", p);
  const auto& st = sol.status;
  const auto& lambda = sol.lambda;
  const auto& u = sol.u;
  const auto uNodes = problem->nodalDisplacement(*u);
  Contact::ContactCounts counts;
  auto r = Contact::contactResults(*problem, uNodes, *lambda, st.slipBound, {fs});
  Contact::resultKKT(*problem, uNodes, r, {fs}, counts);

  // Compare node by node on the contact nodes of this rank; sums over ranks.
  std::map<int, int> ssIndex;
  for (size_t i = 0; i < ss.contactNodes.size(); ++i) ssIndex[ss.contactNodes[i]] = static_cast<int>(i);
  double du = 0, nu = 0, dF = 0, nF = 0;
  int missing = 0;
  for (size_t k = 0; k < r.nodes.size(); ++k) {
    const int node = r.nodes[k];
    auto it = ssIndex.find(node);
    if (it == ssIndex.end()) {
      ++missing;
      continue;
    }
    const int i = it->second;
    for (int c = 0; c < 3; ++c) {
      const double a = uNodes.at(node)[c], b = ss.u[3 * node + c];
      du += (a - b) * (a - b);
      nu += b * b;
      // Tangential force on the body: FETI -(l1 t1 + l2 t2); semismooth* -lambdaT.
      const double fa = r.tangentialForce[3 * k + c], fb = -ss.lambdaT[i][c];
      dF += (fa - fb) * (fa - fb);
      nF += fb * fb;
    }
    dF += (r.normalForce[k] - ss.lambdaN[i]) * (r.normalForce[k] - ss.lambdaN[i]);
    nF += ss.lambdaN[i] * ss.lambdaN[i];
  }
  double local[5] = {du, nu, dF, nF, static_cast<double>(missing)}, global[5];
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 5, local, global);
  const double relU = std::sqrt(global[0] / global[1]), relF = std::sqrt(global[2] / global[3]);
  int fail = 0;
  if (root) {
    std::cout << "semismooth*: " << ss.iterations << " Newton iterations; FETI Algorithm 1: " << st.outer_iterations
              << " SMALBE iterations, n_A " << st.n_A << "\ncontact nodes " << counts.nodes << " (semismooth* "
              << ss.numContactNodes << "), active " << counts.active << ", stick " << counts.stick << ", slip "
              << counts.slip << "\n|u_FETI - u_ss| / |u_ss| on contact nodes = " << relU
              << ", |forces_FETI - forces_ss| / |forces_ss| = " << relF << std::endl;
    if (!ss.converged || !st.converged) std::cerr << "FAILED: a solver did not converge\n", ++fail;
    if (global[4] > 0 || counts.nodes != ss.numContactNodes) std::cerr << "FAILED: contact node sets differ\n", ++fail;
    if (!(relU < 1e-6)) std::cerr << "FAILED: contact displacements differ by " << relU << "\n", ++fail;
    if (!(relF < 1e-6)) std::cerr << "FAILED: contact forces differ by " << relF << "\n", ++fail;
    if (!(counts.stick > 0 && counts.slip > 0 && counts.active < counts.nodes))
      std::cerr << "FAILED: the prism should have stick, slip and no-contact nodes\n", ++fail;
  }
  Teuchos::broadcast(*comm, 0, &fail);
  return fail ? 1 : 0;
}
