// Tribos_FetiProblem.hpp: Total FETI discretization of an elastic body split
// into subdomains, optionally in contact with a rigid plane.
//
//   min 1/2 u'Ku - u'f   s.t.  B_E u = c_E (gluing + Dirichlet),  N u <= d,
//   (+ Tresca/Coulomb friction on the tangential rows T1, T2)
//
// Every subdomain is floating (Dirichlet conditions are rows of B), so the
// kernel R of K is known from coordinates. The dual problem is
//   F = B K+ B',  h = B K+ f - c,  G = R'B',  e = R'f.
// Primal dofs: subdomain after subdomain, each rank owning a contiguous block.
// Dual dofs: per rank, equality rows first, then normal contact rows, then the
// tangential pairs (t1, t2) of the same contact nodes, so every friction disk
// lives on one rank.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

// Contact of one face with a rigid plane: u . n <= gap at every node of the
// face (n the outward normal of the face), two tangents per node.
struct ContactSpec {
  bool enabled = false;
  std::string face = "zmin";
  double gap = 0.0;
};

// One row of B, described on every rank (cheap) so numbering is global.
struct DualRow {
  enum Kind { Gluing, Dirichlet, Normal, Tangent1, Tangent2 } kind;
  int node = -1;            // mesh node
  // Copies of the node the row touches: (subdomain, weight); the row's entry
  // at dof c of that copy is weight * dir[c]. Ascending subdomains.
  std::vector<std::pair<int, double>> copies;
  std::array<double, 3> dir{0, 0, 0};  // direction on the 3 dofs (unit vector for gluing and Dirichlet)
  double c = 0.0;           // right-hand side
  int owner = 0;            // rank
};

// The contact structure of this rank's dual dofs (local indices).
struct LocalContact {
  std::vector<LO> normalRows;       // lambda_I rows, one per local contact node
  std::vector<LO> tangentRows;      // 2 per contact node: t1, t2 (-1: direction fixed by a Dirichlet condition)
  std::vector<int> nodes;           // mesh node of each local contact node
  std::vector<double> nodalArea;    // contact-face area attached to the node
  std::array<double, 3> normal{0, 0, 0}, t1{0, 0, 0}, t2{0, 0, 0};
  double gap = 0.0;                 // u . normal <= gap
};

class FetiProblem {
 public:
  // Parameters: "Formulation" (TFETI | FETI-1), "Local Solver" (CHOLMOD | KLU2 | Tacho),
  // "Gluing" (Orthonormal | Non-redundant | Full), "Dual Operator" (Auto | Explicit | Implicit).
  FetiProblem(const Mesh::Discretization& disc, const Fem::Material& mat, const Fem::LoadCase& loads,
              const ContactSpec& contact, const Teuchos::ParameterList& params, const RCP<const Comm>& comm);
  static RCP<const Teuchos::ParameterList> getValidParameters();

  const RCP<const Comm>& comm() const { return comm_; }
  RCP<const Map> primalMap() const { return primalMap_; }
  RCP<const Map> dualMap() const { return dualMap_; }
  RCP<const CrsMatrix> B() const { return B_; }
  const Vector& f() const { return *f_; }
  const Vector& c() const { return *c_; }
  const LocalContact& contact() const { return contact_; }
  // Local dual rows that are equality rows (gluing, Dirichlet).
  const std::vector<char>& isEqualityRow() const { return isEquality_; }
  int numSubdomains() const { return disc_.numSubdomains(); }
  int numLocalSubdomains() const { return static_cast<int>(systems_.size()); }
  const Fem::SubdomainSystem& subdomain(int k) const { return systems_[k]; }
  // Offset of subdomain s in the primal numbering (replicated, size S+1).
  const std::vector<GO>& primalOffsets() const { return primalOffsets_; }
  const Mesh::Discretization& discretization() const { return disc_; }

  // z = K+ p on this rank's subdomains (generalized inverse by fixing nodes).
  void applyKplus(const Vector& p, Vector& z) const;
  // z = K+ p as F = B K+ B' needs it: p = B'x lives on the dofs B touches and
  // only those entries of z are computed (the others are left as they are).
  // With an explicit dual operator it uses the dense blocks (K+)_bb.
  void applyDualKplus(const Vector& p, Vector& z) const;
  // z = K p (block diagonal).
  void applyK(const Vector& p, Vector& z) const;
  // z = S p: per subdomain the Schur complement on the dofs B touches,
  // S = K_bb - K_bi K_ii^-1 K_ib (zero on interior dofs), for the Dirichlet
  // preconditioner. The interior blocks are factored on first use.
  void applySchur(const Vector& p, Vector& z) const;
  // Coarse numbering: subdomain s owns kernel columns [kernelOffsets()[s], kernelOffsets()[s+1])
  // (6 each in TFETI; fewer in FETI-1 for subdomains touching Dirichlet dofs).
  const std::vector<int>& kernelOffsets() const { return kernelOffsets_; }
  static int kernelDim(const Fem::SubdomainSystem& sys) {
    return sys.numDofs() > 0 ? static_cast<int>(sys.R.size() / sys.numDofs()) : 0;
  }
  // y = R' p (replicated coarse vector); z = R a (primal).
  void applyRt(const Vector& p, std::vector<double>& y) const;
  void applyR(const std::vector<double>& a, Vector& z) const;
  // Replicated global nodal displacement (3 numNodes): the mean of the
  // subdomain copies of each node (they agree to the gluing tolerance).
  std::vector<double> nodalDisplacement(const Vector& u) const;
  // K u of the assembled body for a nodal displacement (replicated, 3
  // numNodes), from the subdomain matrices. Collective.
  std::vector<double> assembledProduct(const std::vector<double>& uNodal) const;
  // The assembled load f (replicated, 3 numNodes). Collective.
  std::vector<double> assembledLoad() const;
  // Global dof (3 node + c) -> prescribed value of the Dirichlet conditions.
  const std::map<long long, double>& dirichlet() const { return dirichlet_; }

  double factorTime() const { return factorTime_; }
  double factorMemoryMb() const;
  const std::string& localSolverName() const { return localSolverName_; }
  // True when some local subdomain applies F from its dense block (K+)_bb.
  bool explicitDualOperator() const;
  // "Auto" forms dense blocks only up to this many rows.
  static constexpr size_t kAutoExplicitRows = 4000;

 private:
  std::vector<DualRow> buildRows(const Fem::LoadCase& loads, const ContactSpec& contact, const std::string& gluing);
  void buildB(const std::vector<DualRow>& rows);
  void buildContact(const std::vector<DualRow>& rows, const ContactSpec& contact);
  void factorSubdomains();
  // Per local subdomain, the dofs that some row of B touches (ascending).
  std::vector<std::vector<int>> boundaryDofs() const;
  void setupExplicitKplus(int k, const std::vector<int>& b);
  void applyKplus(size_t k, const double* p, double* z) const;  // one local subdomain

  const Mesh::Discretization& disc_;
  RCP<const Comm> comm_;
  std::string localSolverName_;
  std::vector<Fem::SubdomainSystem> systems_;      // this rank's subdomains
  std::vector<RCP<LocalSolver>> Kreg_;              // factorizations of K_s + rho sum e_i e_i'
  std::vector<GO> primalOffsets_;
  std::vector<int> kernelOffsets_;
  bool feti1_ = false;
  RCP<const Map> primalMap_, dualMap_;
  RCP<CrsMatrix> B_;
  RCP<Vector> f_, c_;
  std::vector<char> isEquality_;
  LocalContact contact_;
  std::map<long long, double> dirichlet_;
  double factorTime_ = 0;
  mutable std::vector<double> work_;
  // Subdomains with at most this many B dofs get a dense block (K+)_bb
  // (-1: none, Implicit); per local subdomain the B dofs b and the packed
  // lower triangle of (K+)_bb (empty: applied implicitly).
  long denseRowLimit_ = -1;
  std::vector<std::vector<int>> boundary_;
  std::vector<std::vector<double>> KplusBB_;
  mutable std::vector<double> workB_;
  // Dirichlet preconditioner data, per local subdomain: interior dofs and the
  // factorization of K_ii.
  void setupSchur() const;
  mutable std::vector<std::vector<int>> interior_;
  mutable std::vector<RCP<LocalSolver>> Kii_;
  mutable bool schurReady_ = false;
};

// The r rows of R (n x r, column-major; r = 6 in TFETI) chosen by greedy complete pivoting:
// R_I is then nonsingular and well conditioned, so adding rho to those
// diagonal entries of K makes it nonsingular and its inverse a generalized
// inverse of K (K K_reg^-1 K = K, see docs/feti.md).
std::vector<int> fixingDofs(const std::vector<double>& R, int n);

}  // namespace Feti
}  // namespace Tribos
