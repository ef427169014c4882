// Tribos_SemismoothStarNewton.hpp: the semismooth* Newton method of Gfrerer
// and Outrata for contact with Tresca friction, on the contact boundary:
//     0 in S x - l + d psi(x),
//     psi(x) = sum_i g_i ||x_tau,i|| + indicator(x_nu,i <= d_i).
// Each iteration: an approximation step (a proximal step, node by node in
// closed form) gives (x^, y^) with y^ in d psi(x^); a Newton step linearizes
// the graph of d psi at (x^, y^) and solves a sparse SPD system in the full
// primal space. Serial: the whole problem lives on one process.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <array>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "Tribos_ContactReduction.hpp"
#include "Tribos_FullSpaceNewton.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_Registry.hpp"
#include "Tribos_ResultKKT.hpp"

namespace Tribos {
namespace Semismooth {

// The rule chosen per node at the last approximation point. Without
// friction (g_i = 0) a node slides; a node whose tangential directions are
// both fixed by Dirichlet conditions sticks.
enum class NodeState { NoContactStick, NoContactSlip, ContactStick, ContactSlip };

struct SemismoothResult {
  bool converged = false;
  int iterations = 0;                 // Newton steps
  std::vector<double> residuals;      // ||S x^ - l + y^|| / ||l|| after each approximation step
  std::vector<int> numContact, numStick, numSlip;  // per approximation step
  int numNodes = 0, numContactNodes = 0;
  std::vector<int> contactNodes;      // mesh node of contact node i
  // Reduced solution x^ and multiplier y^ (3 per contact node: tau1, tau2,
  // nu); a tangential direction fixed by a Dirichlet condition holds its
  // prescribed value in x and 0 in y.
  std::vector<double> x, y;
  std::vector<double> u;              // full displacement, 3 per mesh node, global coordinates
  // Multipliers of K u - f + B' lambda = 0: lambdaN_i = y_nu >= 0 and the
  // tangential part in global coordinates; the plane's force on the body is
  // -(lambdaN_i n_i + lambdaT_i). lambdaT has no component along a direction
  // that a Dirichlet condition fixes (the reaction there is not friction).
  std::vector<double> lambdaN;
  std::vector<std::array<double, 3>> lambdaT;
  std::vector<NodeState> state;
  // Per contact node: the unit outward normal n_i of its frame, the slip
  // bound g_i (0: frictionless) and the gap d_i.
  std::vector<std::array<double, 3>> normal;
  std::vector<double> slipBound, gap;
  // The assembled K u and f (3 per mesh node, global coordinates, Dirichlet
  // dofs included) and the Dirichlet map (dof -> value): what
  // Contact::resultKKT needs besides the contact forces. Filled by
  // solveFromMesh(), or by addAssembledVectors() after
  // SemismoothStarNewton::solve().
  std::vector<double> Ku, f;
  std::map<long long, double> dirichlet;
  double assemblySeconds = 0, reductionSeconds = 0, solverSeconds = 0;
  double newtonFactorSeconds = 0;     // part of solverSeconds
  // "Reduced CG": total CG steps (= K_rr solves); "CG+MueLu": total CG steps
  // of the Newton steps and the confirmations of the residual (not the
  // initial solve, part of reductionSeconds).
  int cgIterations = 0;
  // "CG+MueLu": all MueLu setups (the first ones are part of reductionSeconds,
  // the re-setups per Newton step part of solverSeconds).
  double preconditionerSeconds = 0;
};

// How a Newton step is solved: in the reduced space of the contact dofs
// (S applied by K_rr solves) or in the full primal space, by a
// factorization or by conjugate gradients. The registry's names are the
// values of "Newton Solver"; those that accept "Dense Schur" can work with
// a dense S (then the Newton systems are solved densely).
struct NewtonSolverKind {
  enum Space { Reduced, FullSpace } space;
  enum Step { Factorization, ConjugateGradients } step;
};
using NewtonSolverRegistry = Registry<NewtonSolverKind>;
const NewtonSolverRegistry& newtonSolvers();

// "Newton Solver" = "Auto" (the default) takes a factorization while it is
// cheap and conjugate gradients beyond: "Sparse Direct" up to
// kAutoSparseDirectMaxDofs primal dofs, when "Dense Schur" asks for S, or
// without node coordinates (MueLu's aggregates need them); "CG+MueLu"
// otherwise. Measured on the prism of input/prism_tresca.xml, one process:
// level 3 (1911 dofs) 0.17 s against 0.46 s, level 4 (4131) 0.49-0.63 s
// against 0.42-0.46 s, level 6 (28611) 14.9 s against 5.0 s (docs/semismooth.md).
constexpr const char* kAutoNewtonSolver = "Auto";
constexpr long long kAutoSparseDirectMaxDofs = 3000;
// The registered name "Newton Solver" of params (validated) stands for on a
// problem of that many primal dofs, with or without node coordinates.
std::string chosenNewtonSolver(const Teuchos::ParameterList& params, long long primalDofs, bool haveCoordinates);

class SemismoothStarNewton {
 public:
  // Reduces the problem (factors K_rr; forms S densely if "Dense Schur"), or
  // with "Newton Solver" = "CG+MueLu" sets up the full-space iterative solver
  // (no factorization).
  SemismoothStarNewton(const ContactProblem& problem, const Teuchos::ParameterList& params);
  ~SemismoothStarNewton();

  // "Tolerance", "Maximum Iterations", "Dense Schur", "Local Solver",
  // "Step Scaling", "Step Size Factor", "Newton Solver", "CG Tolerance",
  // "CG Maximum Iterations", "MueLu Smoother", "MueLu Reuse",
  // "Equilibrium Tolerance", "Forcing Term Maximum".
  static RCP<const Teuchos::ParameterList> getValidParameters();
  // Validates params and the compatibility of its choices (before any work;
  // the constructor calls it too). Messages name the parameters of this list.
  static void checkParameters(const Teuchos::ParameterList& params);

  // Runs the iteration from x = 0; log (optional) gets one line per iteration.
  SemismoothResult solve(std::ostream* log = nullptr);

  // Not available with "CG+MueLu" (nothing is reduced).
  const ContactReduction& reduction() const;
  // The problem in contact frames (frames, prescribed tangential directions).
  const RotatedSystem& system() const { return fullSpace_ ? fullSpace_->system() : reduction_->system(); }

 private:
  struct Approximation {
    std::vector<double> x, y;
    std::vector<NodeState> state;
    int contact = 0, stick = 0, slip = 0;
  };
  // Sxl = S x - l.
  Approximation approximationStep(const std::vector<double>& x, const std::vector<double>& Sxl) const;
  // The Newton linearization at ap: free components and sliding curvatures.
  void linearization(const Approximation& ap, std::vector<char>& freeComp, std::vector<std::array<double, 4>>& G) const;
  void solveReduced(SemismoothResult& res, Approximation& ap, std::ostream* log);
  void solveFullSpace(SemismoothResult& res, Approximation& ap, std::ostream* log);
  // ||(x - x^)/a|| for the step sizes a of the approximation step.
  double naturalResidual(const std::vector<double>& x, const Approximation& ap) const;
  void record(SemismoothResult& res, const Approximation& ap, double rel, int k, std::ostream* log) const;
  void applyS(const std::vector<double>& x, std::vector<double>& Sx) const;
  void reducedCG(const std::vector<char>& freeComp, const std::vector<std::array<double, 4>>& G,
                 const std::vector<double>& rhs, std::vector<double>& dx, std::vector<double>& Sdx);
  void newtonStep(const Approximation& ap, const std::vector<double>& residual, std::vector<double>& dx,
                  std::vector<double>& Sdx);

  Teuchos::ParameterList params_;
  NewtonSolverKind newtonSolver_{NewtonSolverKind::Reduced, NewtonSolverKind::Factorization};
  std::unique_ptr<ContactReduction> reduction_;  // all solvers but "CG+MueLu"
  std::unique_ptr<FullSpaceNewton> fullSpace_;   // "CG+MueLu"
  std::vector<ContactNode> contact_;
  std::vector<double> a_;       // per contact node
  std::vector<double> denseS_;  // only with "Dense Schur"
  double denseSeconds_ = 0;
  std::vector<double> diagKcc_;  // Jacobi preconditioner of "Reduced CG"
  int cgIterations_ = 0;     // forming denseS_ (part of the reduction)
  int numNodes_ = 0;
};

// Fills result.Ku = K u, result.f and result.dirichlet from the problem
// that was solved.
void addAssembledVectors(const ContactProblem& problem, SemismoothResult& result);

// The contact forces of the result for Contact::resultKKT and the output, one
// per contact node: normalForce = lambdaN_i >= 0, tangentialForce = -lambdaT_i
// (the friction force of the plane on the body, global coordinates),
// slipBound = g_i.
std::vector<Contact::ContactNodeForce> contactForces(const SemismoothResult& result);
// The slip of each contact node on its (fixed) plane: the tangential
// displacement u_i - (u_i.n_i) n_i, global coordinates.
std::vector<std::array<double, 3>> contactSlip(const SemismoothResult& result);
// Status of each contact node as written to the result file: 0 no contact,
// 1 stick, 2 slip (frictionless contact nodes slip).
std::vector<int> contactStatus(const SemismoothResult& result);

// A body on a rigid plane, as solveFromMesh() takes it: the mesh, material
// and loads, the contact face with its gap and the Tresca slip bound per
// unit area (0: frictionless), and the list "SemismoothStarNewton".
struct MeshContactProblem {
  Mesh::Mesh mesh;
  Fem::Material material;
  Fem::LoadCase loads;
  std::string contactFace = "zmin";
  double gap = 0.0, slipBoundTraction = 0.0;
  Teuchos::ParameterList solverParams;
};

// Assembles K and f of the whole mesh, takes the contact face on a rigid
// plane at distance gap (outward area-weighted facet normals), nodal slip
// bounds g_i = slipBoundTraction x nodal area (0: frictionless), and solves.
// Nodes of the face whose normal displacement is prescribed are Dirichlet
// nodes, not contact nodes; a node with only tangential components
// prescribed (a symmetry plane) stays a contact node. Timings of all three
// phases, K u, f and the Dirichlet map are in the result. Throws
// Tribos::Error when the Dirichlet conditions leave a rigid motion free (the
// message names the motions) or a prescribed component of a contact node is
// oblique to its normal.
// comm (optional): the ranks over which "CG+MueLu" distributes its solves;
// every rank of comm must call with the same arguments. The other Newton
// solvers are serial and ignore it.
SemismoothResult solveFromMesh(const Mesh::Mesh& mesh, const Fem::Material& material, const Fem::LoadCase& loads,
                               const std::string& contactFace, double gap, double slipBoundTraction,
                               const Teuchos::ParameterList& params, std::ostream* log,
                               const RCP<const Comm>& comm = Teuchos::null);

// The contact nodes of a face against the rigid plane at distance gap: the
// face's nodes whose normal displacement is free, with their outward
// area-weighted normals and slip bounds (traction x nodal area). Refuses
// Dirichlet conditions at a node that are oblique to its frame or that
// prescribe a penetration, or a slip against friction (Fem::requireNoPrescribedPenetration,
// requireNoPrescribedSlip).
std::vector<ContactNode> contactFaceNodes(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                                          const std::string& contactFace, double gap, double slipBoundTraction);

// The contact problem solveFromMesh() solves (for tests and other drivers).
// With a communicator its ranks share the element matrices out and every
// rank gets the whole problem (collective).
ContactProblem buildContactProblem(const Mesh::Mesh& mesh, const Fem::Material& material, const Fem::LoadCase& loads,
                                   const std::string& contactFace, double gap, double slipBoundTraction,
                                   const Comm* comm = nullptr);

}  // namespace Semismooth
}  // namespace Tribos
