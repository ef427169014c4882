// Tribos_ContactReduction.hpp: reduction of a linear elastic body in contact
// with rigid planes to its contact boundary (Section 3 of the semismooth*
// paper). Contact dofs are rotated to a per-node frame (tau1, tau2, nu); all
// other free dofs (r) are eliminated:
//     S = K_cc - K_cr K_rr^-1 K_rc,   l = f_c - K_cr K_rr^-1 f_r.
// S is never formed (except on request for small meshes): it is applied with
// one sparse Cholesky factorization of K_rr. The same fixed sparsity pattern
// serves the Newton matrices, so the symbolic analysis is done once.
#pragma once

#include "Tribos_ArrayScan.hpp"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Tribos_LocalCsr.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Semismooth {

// Why a body that Dirichlet conditions do not hold is refused here.
inline const char* const kSemicoerciveAdvice =
    "the semismooth* method needs every rigid motion held by Dirichlet conditions (the contact alone does not "
    "hold the body); use Solver/Type = FETI";

// One contact node i: non-penetration u_i . normal <= d, Tresca slip bound g.
struct ContactNode {
  int node = -1;
  std::array<double, 3> normal{0, 0, -1};  // outward unit normal of the body
  double g = 0.0;                          // slip bound (a force: traction bound x nodal area); 0: frictionless
  double d = 0.0;                          // gap
};

// The discrete problem: K (3 dof per node, dof = 3 node + c, both triangles,
// sorted columns, unconstrained), f, prescribed dofs, contact nodes. A
// contact node may carry prescribed dofs only in tangent directions (e.g. a
// symmetry plane through the contact face): such a direction is a Dirichlet
// dof of the node's frame and has no friction; the node keeps its contact
// and its friction in the remaining tangential direction.
struct ContactProblem {
  LocalCsr K;
  std::vector<double> f;
  std::map<long long, double> dirichlet;  // dof -> prescribed value
  std::vector<ContactNode> contact;
  // Node coordinates: the check that the Dirichlet conditions hold every
  // rigid motion (K restricted to the other dofs is then positive definite),
  // and the rigid-body modes that the "CG+MueLu" Newton solver gives MueLu as
  // near null space.
  std::vector<std::array<double, 3>> coords;
  // Ranks over which the "CG+MueLu" Newton solver distributes its CG solves
  // (optional; every rank of it must solve the same problem). Null: one
  // process.
  RCP<const Comm> comm;
  int numNodes() const { return K.rows / 3; }
};

// How the prescribed global components of a contact node (fixed[c]: u_c is
// prescribed) meet its normal n:
//   None        no prescribed component;
//   Tangential  every prescribed axis e_c is tangent (n_c = 0): the node keeps
//               its contact, the prescribed directions lose their friction;
//   Normal      n lies in the span of the prescribed axes, so u.n is
//               prescribed: the node is a Dirichlet node, not a contact node;
//   Oblique     anything else (a prescribed axis that is neither normal nor
//               tangent): the contact frame cannot represent it.
enum class PrescribedDirections { None, Tangential, Normal, Oblique };
PrescribedDirections classifyPrescribed(const std::array<double, 3>& normal, const std::array<bool, 3>& fixed);

// Sparse symmetric positive definite solver on one fixed pattern: factor()
// may be called repeatedly with new values (analysis once for CHOLMOD).
class PatternSolver {
 public:
  virtual ~PatternSolver() = default;
  virtual void factor(const std::vector<double>& values) = 0;
  virtual void solve(const double* b, double* x, int nrhs = 1) const = 0;
};
// A LocalSolver of feti (createLocalSolver(name)) that refactors: "CHOLMOD"
// keeps the symbolic analysis; the other backends factor from scratch.
std::unique_ptr<PatternSolver> createPatternSolver(const std::string& name, const LocalCsr& pattern);

// The problem in contact frames on the unprescribed ("free") dofs: K and f
// rotated node by node (x_i = R_i' u_i at contact nodes, identity
// elsewhere, so 3x3 node blocks stay blocks), prescribed values moved to the
// right-hand side, and the numberings between dofs, free dofs and the
// reduced vector x = (x_1, ..., x_m), x_i = (tau1, tau2, nu). Dofs are
// numbered 3 node + k as the global ones; at a contact node k is the frame
// direction. A tangential direction fixed by a Dirichlet condition is a
// prescribed dof of the frame (its frame vector is the fixed axis): it keeps
// its place 3i+k in x with the prescribed value, but it is not a free dof
// (freeOfReduced = -1), so S, l and the Newton systems never see it. No
// solves. Refuses (Tribos::Error) a Dirichlet problem that leaves a rigid
// motion free (K_rr would be singular) and contact nodes whose prescribed
// components are not tangent directions.
struct RotatedSystem {
  explicit RotatedSystem(const ContactProblem& problem);

  int numNodes = 0, m = 0;
  std::vector<ContactNode> contact;
  std::vector<std::array<double, 9>> frame;  // row-major R_i: R[a][k] = component a of frame vector k
  std::vector<int> freeOfDof;      // dof -> free index or -1 (prescribed)
  std::vector<int> dofOfFree;      // free index -> dof
  std::vector<int> reducedOfFree;  // free index -> index in x (3i+k) or -1 (an r dof)
  std::vector<int> freeOfReduced;  // 3i+k -> free index, -1 for a prescribed tangential direction
  std::vector<char> prescribed;    // 3i+k: a tangential direction fixed by a Dirichlet condition
  std::vector<double> xPrescribed; // 3i+k: its prescribed value (0 for the others)
  LocalCsr Kfree;                  // rotated K on the free dofs, natural order
  std::vector<double> fFree;       // rotated f minus the prescribed-value lifting
  std::vector<double> uPrescribed; // dof vector with the prescribed values (in the frame at contact nodes)
  // Positions in Kfree of the tau block of node i (-1 when a tangential
  // direction is prescribed: the sliding curvature needs both directions).
  std::vector<std::array<int, 4>> tangentialEntries;

  // Largest diagonal entry of K_cc per contact node; K_cc >= S, so 1/this
  // bounds 1/diag(S) from below.
  std::vector<double> nodalMaxDiagonalKcc() const;
  // diag(K_cc), 3 per contact node.
  std::vector<double> diagonalKcc() const;
  // Global displacement (3 per node, global coordinates) from values on the
  // free dofs in the rotated frame.
  std::vector<double> globalDisplacement(const std::vector<double>& vFree) const;
};

class ContactReduction {
 public:
  // Rotates K (RotatedSystem), factors K_rr.
  ContactReduction(const ContactProblem& problem, const std::string& localSolver);
  ~ContactReduction();

  int numContactNodes() const { return sys_.m; }
  int numReduced() const { return 3 * sys_.m; }
  const std::vector<double>& l() const { return l_; }
  const ContactNode& contactNode(int i) const { return sys_.contact[i]; }
  const RotatedSystem& system() const { return sys_; }

  // Sx = S x (one K_rr solve). S acts on the free components: prescribed
  // directions of x are ignored (their values are in l) and zero in Sx.
  void applyS(const std::vector<double>& x, std::vector<double>& Sx) const;
  // S as a dense column-major (3m)^2 array (3m solves): small meshes only.
  std::vector<double> denseS() const;
  // Largest diagonal entry of K_cc per contact node; K_cc >= S, so 1/this
  // bounds 1/diag(S) from below.
  std::vector<double> nodalMaxDiagonalKcc() const { return sys_.nodalMaxDiagonalKcc(); }
  // diag(K_cc), 3 per contact node.
  std::vector<double> diagonalKcc() const { return sys_.diagonalKcc(); }

  // Newton step in the full primal space. freeComp[3i+k]: component k of node
  // i is free (else dx = 0; always so at prescribed directions); G[i]: 2x2
  // row-major curvature added on the tangential pair of node i when both are
  // free. Solves (S_FF + G_FF) dx_F = rhs_F and returns
  // dx and S dx (the latter from one product, no extra solve).
  void newtonSolve(const std::vector<char>& freeComp, const std::vector<std::array<double, 4>>& G,
                   const std::vector<double>& rhs, std::vector<double>& dx, std::vector<double>& Sdx);

  // Full displacement (3 per node, global coordinates) for contact values x:
  // u_r = K_rr^-1 (f_r - K_rc x).
  std::vector<double> displacement(const std::vector<double>& x) const;

  double reductionSeconds() const { return reductionSeconds_; }
  double newtonFactorSeconds() const { return newtonFactorSeconds_; }

 private:
  void krrSolve(const std::vector<double>& rhsFree, std::vector<double>& zFree) const;
  // y = Kfree v restricted to c, v given on the free dofs.
  void multiplyFree(const std::vector<double>& v, std::vector<double>& y) const;

  RotatedSystem sys_;
  std::vector<double> l_, zf_;     // zf = K_rr^-1 f_r (padded with zeros on c)
  std::unique_ptr<PatternSolver> Krr_, newton_;
  std::string solverName_;
  double reductionSeconds_ = 0, newtonFactorSeconds_ = 0;
};

}  // namespace Semismooth
}  // namespace Tribos
