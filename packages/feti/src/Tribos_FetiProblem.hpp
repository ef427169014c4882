// Tribos_FetiProblem.hpp: Total FETI discretization of elastic bodies split
// into subdomains, optionally in contact with each other and with rigid
// planes (node-to-segment rows, one constraint per slave node:
// Tribos_ContactConstraint.hpp) or glued to each other.
//
//   min 1/2 u'Ku - u'f   s.t.  B_E u = c_E (gluing + Dirichlet + glued pairs),  N u <= d,
//   (+ Tresca/Coulomb friction on the tangential rows T1, T2)
//
// Every subdomain is floating (Dirichlet conditions are rows of B), so the
// kernel R of K is known from coordinates. The dual problem is
//   F = B K+ B',  h = B K+ f - c,  G = R'B',  e = R'f.
// The class composes three parts: the constraint rows (B, c, contact
// structure; Tribos_ConstraintRows.hpp), the subdomain pseudo-inverse K+
// (Tribos_SubdomainPseudoInverse.hpp) and the Dirichlet preconditioner
// (Tribos_DirichletPreconditioner.hpp), over this rank's subdomain systems.
// Primal dofs: subdomain after subdomain, each rank owning a contiguous block.
// Dual dofs: per rank, equality rows first, then normal contact rows, then the
// tangential pairs (t1, t2) of the same contact nodes, so every friction disk
// lives on one rank.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_DirichletPreconditioner.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_SubdomainPseudoInverse.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mass.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

// What an application that assembles its own subdomains gives FetiProblem
// besides them (see the second constructor): the rows of B and what the
// result check needs to know of them.
struct FetiConstraints {
  // The rows of B (gluing, Dirichlet, contact normal and tangential rows):
  // on every rank either all of them (the same list) or only its own, those
  // whose first copy lies on one of its subdomains (no rank then holds the
  // whole list). FetiProblem sets the owners and keeps its own rows.
  std::vector<DualRow> rows;
  // Global dof (3 node + c) -> prescribed value: the Dirichlet conditions
  // that rows of kind Dirichlet impose (the result check reads them here).
  std::map<long long, double> dirichlet;
  // The constraint of every node that has a Normal or Bonded row among the
  // rows given on this rank (more are ignored; Tribos_ContactConstraint.hpp): its frame (the normal row's and
  // the tangential rows' directions), gap (the normal row's c), master
  // nodes (global numbers; the rows' further copies) and contact area (a
  // Tresca slip bound traction times it is the node's slip bound). The
  // result check reads the relative displacement and the forces from it.
  std::vector<ContactConstraint> contact;
  // Shorthand when `contact` is empty: every Normal row presses its node on
  // one rigid plane with the body's outward normal contactNormal and the
  // gap contactGap (u . n <= gap), tangents Feti::tangents(n), and the
  // contact area of each node (absent: 1).
  std::array<double, 3> contactNormal{0, 0, 0};
  double contactGap = 0.0;
  std::map<int, double> contactArea;
};

// A mass term in every subdomain's matrix: stiffnessCoefficient K +
// massCoefficient M, M the consistent mass of the densities. With a positive
// mass coefficient every subdomain is positive definite (floating = false,
// no kernel, no coarse space): an implicit time step's K + M / (beta dt^2),
// or M alone (stiffnessCoefficient 0) for a projection in the mass norm
// (docs/dynamics.md).
struct MassTerm {
  Fem::BodyDensities density;
  double massCoefficient = 0, stiffnessCoefficient = 1;
};

class FetiProblem {
 public:
  // Parameters: "Formulation" (TFETI | FETI-1), "Local Solver" (CHOLMOD | KLU2 | Tacho),
  // "Gluing" (Orthonormal | Non-redundant | Full), "Dual Operator" (Auto | Explicit | Implicit).
  // A decomposed mesh: assembles the subdomains of this rank (each body with
  // its material) and derives this rank's rows of B (meshConstraintRows)
  // with the contact constraints `contact` (none: no contact), as the
  // contact search finds them (Contact::contactConstraints on the whole
  // mesh, Contact::faceContactConstraints on the ranks' parts). A rank may
  // be given every constraint or only those of the slave nodes it owns
  // (scatterContactConstraints); it keeps the latter. With a mass term, the
  // subdomains' matrices are massTerm's (TFETI only). Collective.
  FetiProblem(const Mesh::Discretization& disc, const Fem::BodyMaterials& mat, const Fem::LoadCase& loads,
              const std::vector<ContactConstraint>& contact, const Teuchos::ParameterList& params,
              const RCP<const Comm>& comm, const MassTerm* massTerm = nullptr);
  // Subdomains an application assembled: this rank's subdomains (ids
  // ascending, each rank a contiguous range, rank 0 first; K, f, the global
  // node numbers, the coordinates, and R, or empty R to have the rigid-body
  // modes built from the coordinates) and the rows of B. Checks sizes,
  // ranges and that R spans the kernel of K; throws Tribos::Error naming
  // the subdomain or row. Collective.
  FetiProblem(std::vector<Fem::SubdomainSystem> localSubdomains, FetiConstraints constraints,
              const Teuchos::ParameterList& params, const RCP<const Comm>& comm);
  static RCP<const Teuchos::ParameterList> getValidParameters();

  const RCP<const Comm>& comm() const { return comm_; }
  RCP<const Map> primalMap() const { return primalMap_; }
  RCP<const Map> dualMap() const { return constraints_.dualMap; }
  RCP<const CrsMatrix> B() const { return constraints_.B; }
  const Vector& f() const { return *f_; }
  const Vector& c() const { return *constraints_.c; }
  const LocalContact& contact() const { return constraints_.contact; }
  // The contact constraints of this rank's contact nodes (those with a
  // Normal or Bonded row here; gatherContactConstraints() for all).
  const std::vector<ContactConstraint>& contactConstraints() const { return contactConstraints_; }
  // Whether the problem is a contact problem (the mesh's contact is enabled,
  // or an application gave Normal rows), on every rank.
  bool hasContact() const { return hasContact_; }
  // Local dual rows that are equality rows (gluing, Dirichlet).
  const std::vector<char>& isEqualityRow() const { return constraints_.isEquality; }
  int numSubdomains() const { return static_cast<int>(primalOffsets_.size()) - 1; }
  // 1 + the largest global node number of any subdomain.
  int numNodes() const { return numNodes_; }
  int numLocalSubdomains() const { return static_cast<int>(systems_.size()); }
  const Fem::SubdomainSystem& subdomain(int k) const { return systems_[k]; }
  // Offset of subdomain s in the primal numbering (replicated, size S+1).
  const std::vector<GO>& primalOffsets() const { return primalOffsets_; }
  // The decomposed mesh of the first constructor (throws for the second).
  const Mesh::Discretization& discretization() const;
  bool hasDiscretization() const { return disc_ != nullptr; }

  // z = K+ p on this rank's subdomains (generalized inverse by fixing nodes).
  void applyKplus(const Vector& p, Vector& z) const { Kplus_->apply(p, z); }
  // z = K+ p as F = B K+ B' needs it: p = B'x lives on the dofs B touches and
  // only those entries of z are computed (the others are left as they are).
  // With an explicit dual operator it uses the dense blocks (K+)_bb.
  void applyDualKplus(const Vector& p, Vector& z) const { Kplus_->applyOnBoundary(p, z); }
  // z = K p (block diagonal).
  void applyK(const Vector& p, Vector& z) const;
  // z = K_bb p on the dofs B touches, per subdomain (zero elsewhere): all of
  // K that B K B' reads, for the lumped preconditioner. On a subdomain with
  // few dofs on its interface and contact surface K_bb is a small part of K.
  // The blocks are extracted on first use.
  void applyKBoundary(const Vector& p, Vector& z) const;
  // Whether the equality rows (gluing, Dirichlet) are orthonormal (Gluing =
  // Orthonormal): then BB' is the identity on them.
  bool orthonormalEqualityRows() const { return orthonormalEquality_; }
  // An estimate of the diagonal of F = B K+ B' on this rank's dual rows,
  // sum_j B_ij^2 / K_jj: exact for a diagonal K, and within the spread of
  // K's rows otherwise, which is what a scaling of the dual by it needs
  // (Friction::DiagonalScalingTransform). Formed once (setStiffness forms
  // it again): every load step's dual is scaled alike. Collective.
  std::vector<double> dualDiagonalEstimate() const;
  // "Conjugate Projector": whether a dual of positive definite subdomains
  // takes their rigid motions out by ConjugateProjector.
  bool conjugateProjectorWanted() const { return conjugateProjector_; }
  // "Dual Scaling": whether a contact dual without a coarse space is scaled
  // by dualDiagonalEstimate().
  bool dualScalingWanted() const { return dualScaling_; }
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
  // The nodes this rank holds results at: those of its subdomains and the
  // partners of its contact nodes; each owned by the lowest rank holding it.
  const RCP<const Fem::NodalLayout>& nodalLayout() const { return nodalLayout_; }
  // The nodal displacement on nodalLayout(): the mean of the subdomain
  // copies of each node (they agree to the gluing tolerance). Collective.
  Fem::NodalVector nodalDisplacement(const Vector& u) const;
  // K u of the assembled body for a nodal displacement on nodalLayout(),
  // from the subdomain matrices. Collective.
  Fem::NodalVector assembledProduct(const Fem::NodalVector& u) const;
  // The assembled load f on nodalLayout(). Collective.
  Fem::NodalVector assembledLoad() const;
  // Global dof (3 node + c) -> prescribed value of the Dirichlet conditions
  // at the nodes of nodalLayout().
  const std::map<long long, double>& dirichlet() const { return dirichlet_; }

  // A load history (docs/load_history.md) changes the right-hand sides only;
  // K, its factors, B and the coarse space stay.
  // The loads of a decomposed mesh (first constructor, TFETI) at another
  // time: the same Dirichlet dofs with other values, other tractions and
  // volume force. Re-assembles f, the Dirichlet rows' c and dirichlet().
  // Throws Error for a problem without a mesh or in FETI-1 (whose
  // subdomains eliminated the Dirichlet values). Collective.
  void setLoads(const Fem::LoadCase& loads);
  // Any problem (TFETI) at other loads: subdomainLoads[k] the load f of
  // local subdomain k (3 per local node), dirichletValues the prescribed
  // value of every Dirichlet dof the problem's rows fix (global dof
  // 3 node + c; at least those of this rank's rows and nodes). K, its
  // factors and B stay. Throws Error for a missing value or a wrong size.
  void setRightHandSides(const std::vector<std::vector<double>>& subdomainLoads,
                         const std::map<long long, double>& dirichletValues);
  // New values of the subdomains' K on the same patterns (K[k]: local
  // subdomain k), a nonlinear material's next tangent say: a numeric
  // refactorization of K+ (ordering and symbolic analysis kept). B, R and
  // the coarse space stay. Throws Error for another pattern.
  void setStiffness(const std::vector<LocalCsr>& K);
  // c on the tangential contact rows: (B u)_T of a previous primal
  // displacement u, so that friction acts on the slip since u (B_T u = c_T
  // is stick); a zero u restores the static problem.
  void setTangentialOffset(const Vector& previousPrimal);

  double factorTime() const { return Kplus_->factorSeconds(); }
  double factorMemoryMb() const { return Kplus_->memoryMb(); }
  double denseBlockMemoryMb() const { return Kplus_->denseBlockMemoryMb(); }
  const std::string& localSolverName() const { return localSolverName_; }
  // "Coarse Problem": how CoarseSpace factors GG' (Auto, Replicated, Split).
  const std::string& coarseProblem() const { return coarseProblem_; }
  // True when some local subdomain applies F from its dense block (K+)_bb.
  bool explicitDualOperator() const { return Kplus_->hasDenseBlocks(); }
  // True when some of this rank's dense blocks are stored in single
  // precision (Dense Block Precision = Single): applyDualKplus then applies
  // a rounded K+, applyKplus still the exact one.
  bool singlePrecisionBlocks() const { return Kplus_->hasSingleBlocks(); }
  // F = B K+ B' as a dense n x n column-major matrix on every rank (n dual
  // rows), summed from the dense blocks (K+)_bb: far cheaper than n
  // applications of F. False (D empty) when some subdomain has no dense
  // block. Collective.
  bool formDenseF(std::vector<double>& D) const;
  // "Auto" forms dense blocks only up to this many rows.
  static constexpr size_t kAutoExplicitRows = 4000;

 private:
  // What both constructors share once systems_ holds this rank's subdomains.
  void setup(FetiConstraints constraints, bool contact, const Teuchos::ParameterList& validated);
  // Per local subdomain, the dofs that some row of B touches (ascending).
  std::vector<std::vector<int>> boundaryDofs() const;
  RCP<const Fem::NodalLayout> makeNodalLayout() const;

  const Mesh::Discretization* disc_ = nullptr;
  bool feti1_ = false;
  // This rank's Dirichlet rows (first constructor): local dual row and the
  // global dof (3 node + c) whose value is its c.
  std::vector<std::pair<LO, long long>> dirichletRows_;
  int numNodes_ = 0;
  bool hasContact_ = false;
  bool conjugateProjector_ = true, dualScaling_ = true;
  mutable std::vector<double> dualDiagonal_;  // dualDiagonalEstimate(), once formed
  mutable bool dualDiagonalFormed_ = false;
  RCP<const Comm> comm_;
  std::string localSolverName_;
  std::string coarseProblem_ = "Auto";
  std::vector<Fem::SubdomainSystem> systems_;      // this rank's subdomains
  std::vector<GO> primalOffsets_;
  std::vector<int> kernelOffsets_;
  RCP<const Map> primalMap_;
  RCP<Vector> f_;
  std::map<long long, double> dirichlet_;
  DualConstraints constraints_;
  std::vector<ContactConstraint> contactConstraints_;
  RCP<const Fem::NodalLayout> nodalLayout_;
  std::vector<std::vector<int>> boundary_;         // boundaryDofs()
  std::unique_ptr<SubdomainPseudoInverse> Kplus_;
  // The Dirichlet preconditioner, factored on first use (only projected CG
  // with "Preconditioner" = Dirichlet needs it).
  mutable std::unique_ptr<DirichletPreconditioner> preconditioner_;
  mutable std::vector<LocalCsr> Kbb_;  // applyKBoundary's blocks, one per subdomain
  bool orthonormalEquality_ = false;
};

}  // namespace Feti
}  // namespace Tribos
