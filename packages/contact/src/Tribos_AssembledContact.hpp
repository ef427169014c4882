// Tribos_AssembledContact.hpp: frictional contact for a Trilinos finite
// element application that assembles its stiffness the Tpetra way, one
// matrix over the ranks, in the shape of Belos' LinearProblem and
// SolverManager:
//
//   Tribos::Assembled::ContactProblem problem(K, ownedMap, coordinates);
//   problem.setLoad(f);                         // a Tpetra::Vector
//   problem.setDirichlet(fixedDofs);            // (global dof, value)
//   problem.addContactPair(pair);               // facets by global node ids
//   Tribos::Assembled::ContactSolver solver(rcpFromRef(problem), params);
//   solver.solve();                             // Converged or Unconverged
//   solver.getDisplacement();                   // a Tpetra::Vector on ownedMap
//
// What Tribos takes. The application's dofs are numbered 3 node + c (c = x,
// y, z), global ordinals of type Tribos::GO (long long). K is the stiffness
// as each rank's own elements sum it, before anything is summed over the
// ranks: a Tpetra::FECrsMatrix between beginAssembly() and endAssembly()
// (its row map then holds the rank's owned and shared dofs and its rows the
// sums of the rank's element matrices), or any Tpetra::RowMatrix with that
// overlapping row map and those rows (a CrsMatrix the application fills
// with its elements' matrices on its owned+shared map). That is exactly the
// Neumann matrix of the rank's elements, which is what FETI solves with: the
// elements a rank holds are its subdomain (each connected piece of them one
// subdomain), the nodes that several ranks hold are glued by Tribos. After
// endAssembly() the shared rows have been summed into their owners' rows
// and the rank's own part is lost; such a matrix is refused with that
// reason. ownedMap is the application's owned (one-to-one) dof map, the
// FECrsGraph's owned row map, on which the results come back.
// coordinates: a MultiVector of 3 columns on a map of node ids (owned or
// owned+shared nodes, as MueLu takes coordinates).
//
// What Tribos builds: the subdomains and their rigid-body modes, the rows
// of B (gluing of the copies of shared nodes, Dirichlet rows, contact rows
// from its own contact search and mortar integrals), the FETI operators and
// the contact solve. The application writes no row of B.
//
// Reuse: after a solve, setLoad and setDirichlet with new values (the same
// dofs) make the next solve a load step of a history (docs/load_history.md):
// nothing is factored again, the step starts from the previous solution,
// and friction acts on the slip since the previous step. setStiffness with
// a new K of the same pattern (a nonlinear material's next tangent) is a
// numeric refactorization of the subdomains; the history goes on.
#pragma once

#include <Teuchos_ParameterListAcceptorDefaultBase.hpp>
#include <Tpetra_RowMatrix_decl.hpp>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_ContactSolver.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_SolveResult.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Assembled {

using RowMatrix = Tpetra::RowMatrix<SC, LO, GO, Node>;

// Facets of a body's boundary by the application's global node ids,
// nodesPerFacet (3: triangles, 4: quadrilaterals) per facet, each
// counter-clockwise seen from outside the body (its normal points out).
// A rank gives the facets of its own elements (or any it holds all nodes
// of); a facet given by several ranks counts once.
struct Surface {
  std::vector<GO> nodes;
  int nodesPerFacet = 4;
  size_t numFacets() const { return nodesPerFacet > 0 ? nodes.size() / nodesPerFacet : 0; }
};

// A contact pair: the slave surface pressed against the master surface of
// another body, or, when master has no facets, against the rigid plane
// through planePoint with unit normal planeNormal (pointing out of the
// obstacle, towards the body). Its friction is the solver's
// "Friction"/"Pair <k>", k the number addContactPair returned.
struct ContactPair {
  std::string name;
  Surface slave, master;
  std::array<double, 3> planePoint{0, 0, 0};
  std::array<double, 3> planeNormal{0, 0, 1};
  Contact::ContactDiscretization discretization = Contact::ContactDiscretization::Mortar;
  bool glued = false;  // bonded: no relative motion at all
  // Slave nodes farther than this from the master surface get no
  // constraint (infinity: every slave node the master surface covers).
  double searchDistance = std::numeric_limits<double>::infinity();
};

// The stiffness as element matrices, for an application that hands its
// elements rather than an overlap matrix: element e has nodesPerElement
// global node ids (nodes[e m .. e m + m - 1]) and a symmetric matrix of
// (3m)^2 values, row-major, its dof 3a + c the component c of its a-th node.
// Each rank gives its own elements. Tribos splits a rank's elements into
// subdomains of about (subdomainSize + 1)^3 nodes (METIS on the elements
// sharing faces, each connected part of the rank's elements apart; 0: Auto,
// 4, the size the driver's Auto takes), as many smaller subdomains make the
// contact solve faster than one per rank. Tet4 (4) and Hex8 (8) elements are
// split; other element types give one subdomain per connected part.
struct ElementMatrices {
  int nodesPerElement = 8;
  std::vector<GO> nodes;
  std::vector<double> values;
  int subdomainSize = 0;
  size_t numElements() const { return nodesPerElement > 0 ? nodes.size() / nodesPerElement : 0; }
};

// The problem, as the application holds it (Belos::LinearProblem's role).
// Every set* and add* is local to the rank; the solver reads them all,
// collectively, at its next solve().
class ContactProblem {
 public:
  ContactProblem(const RCP<const RowMatrix>& K, const RCP<const Map>& ownedMap,
                 const RCP<const MultiVector>& coordinates);
  // The same with the rank's element matrices instead of K (their nodes are
  // the rank's rows: the load on K's row map means on theirs).
  ContactProblem(ElementMatrices elements, const RCP<const Map>& ownedMap,
                 const RCP<const MultiVector>& coordinates);
  // A new stiffness (a nonlinear material's next tangent, say): of the same
  // pattern, a numeric refactorization at the next solve; otherwise the
  // subdomains are built again.
  void setStiffness(const RCP<const RowMatrix>& K);
  void setElementMatrices(ElementMatrices elements);
  // The load: a Vector on ownedMap (assembled nodal forces) or on K's row
  // map (the rank's own elements' contributions, summed over the ranks by
  // Tribos). Null: zero.
  void setLoad(const RCP<const Vector>& f);
  // The Dirichlet conditions: (global dof 3 node + c, value). Any rank may
  // give any dof of its K's rows; a dof given twice must have one value.
  // Replaces the previous list. A symmetry plane is u_c = 0 on its nodes
  // (contact nodes on it keep their contact along the other directions).
  void setDirichlet(std::vector<std::pair<GO, double>> dofValues);
  // Returns the pair's number k (0, 1, ... in the order of the calls, the
  // same on every rank): its friction is "Friction"/"Pair <k>". Every rank
  // adds the same pairs (names, planes, discretizations) in the same order,
  // each with its own facets.
  int addContactPair(ContactPair pair);

  const RCP<const RowMatrix>& stiffness() const { return K_; }  // null when given as elements
  const RCP<const ElementMatrices>& elements() const { return elements_; }
  const RCP<const Map>& ownedMap() const { return ownedMap_; }
  const RCP<const MultiVector>& coordinates() const { return coordinates_; }
  const RCP<const Vector>& load() const { return f_; }
  const std::vector<std::pair<GO, double>>& dirichlet() const { return dirichlet_; }
  const std::vector<ContactPair>& contactPairs() const { return pairs_; }
  // Counters of the changes, for the solver to know what to redo.
  int stiffnessVersion() const { return stiffnessVersion_; }
  int loadVersion() const { return loadVersion_; }
  int pairsVersion() const { return static_cast<int>(pairs_.size()); }

 private:
  RCP<const RowMatrix> K_;
  RCP<const ElementMatrices> elements_;
  RCP<const Map> ownedMap_;
  RCP<const MultiVector> coordinates_;
  RCP<const Vector> f_;
  std::vector<std::pair<GO, double>> dirichlet_;
  std::vector<ContactPair> pairs_;
  int stiffnessVersion_ = 0, loadVersion_ = 0;
};

// The columns of ContactSolver::getContactState(), per node of the owned
// node map: the contact traction (force per area of the node's share of the
// slave surface: the multiplier of dual mortar), its tangential part in
// global coordinates, the slip (the relative tangential displacement since
// the unloaded state) and the slip of the step (since the previous solve of
// the history), the normal gap and the status (-1: not a slave node, 0:
// open, 1: stick, 2: slip). Forces act on the slave node; the same
// quantities as the driver writes (Tribos_SolveResult.hpp).
enum ContactColumn {
  NormalTraction = 0,
  TangentialTractionX = 1, TangentialTractionY = 2, TangentialTractionZ = 3,
  SlipX = 4, SlipY = 5, SlipZ = 6,
  SlipIncrementX = 7, SlipIncrementY = 8, SlipIncrementZ = 9,
  Gap = 10,
  Status = 11,
  NumContactColumns = 12
};

// What a solve reports besides the fields (the same on every rank).
struct SolveSummary {
  bool converged = false;       // the solver's test and the result check (docs/embedding.md)
  std::string reason;           // why not, or how it stopped
  int step = 0;                 // solves since the unloaded state (1: a static solve)
  std::string outerAlgorithm;   // empty without contact
  int iterations = 0;           // outer (or projected CG) iterations
  long long n_A = 0;            // applications of the dual operator
  int rounds = 1;               // solves until the result met its check
  Contact::ResultKKT kkt;       // residuals of the result returned, node by node
  double limit = 0;             // what the residuals are held to
  Contact::ContactCounts counts;
  int subdomains = 0;           // FETI subdomains (connected pieces of the ranks' elements)
  long long primalDofs = 0, dualDofs = 0;
  bool rebuilt = false;         // this solve built the subdomains and factored them
  bool refactored = false;      // a new K of the same pattern: numeric refactorization only
  double setupSeconds = 0, solveSeconds = 0;
};

class AssembledFeti;  // the FETI problem built from a ContactProblem

// The solver (Belos::SolverManager's role), a Teuchos::ParameterListAcceptor:
// the list is Contact::ContactSolver's ("FETI", "Outer Algorithm",
// "Friction" with "Pair <k>" sublists, ...), validated when set.
class ContactSolver : public Teuchos::ParameterListAcceptorDefaultBase {
 public:
  ContactSolver();
  ContactSolver(const RCP<ContactProblem>& problem, const RCP<Teuchos::ParameterList>& params);
  ~ContactSolver() override;

  // Validates and fills in the defaults; throws Tribos::Error naming the
  // entry, or an outer algorithm that does not solve the law of the
  // problem's pairs (also refused by setProblem). A new list starts the
  // history again at the next solve.
  void setParameterList(const RCP<Teuchos::ParameterList>& params) override;
  RCP<const Teuchos::ParameterList> getValidParameters() const override;
  void setProblem(const RCP<ContactProblem>& problem);
  const RCP<ContactProblem>& getProblem() const { return problem_; }
  void setOutputStream(const RCP<Teuchos::FancyOStream>& out) { out_ = out; }

  // Solves at the problem's current load and Dirichlet values: the first
  // solve from rest, each later one a step of the history (see above).
  // Collective. Throws CollectiveError on every rank for a problem Tribos
  // refuses (naming the object and what is wrong).
  Contact::SolveStatus solve();
  // The next solve starts from the unloaded state again (no friction
  // history); the factors stay.
  void resetHistory();

  // On the problem's ownedMap: the displacement, and the reaction at the
  // Dirichlet dofs, K u - f - (contact forces) (the force the supports
  // exert on the body, Contact::supportReactions; zero elsewhere).
  RCP<const Vector> getDisplacement() const;
  RCP<const Vector> getReaction() const;
  // On getNodeMap(), the columns of ContactColumn.
  RCP<const MultiVector> getContactState() const;
  // The owned node map (node ids: ownedMap's dof ids / 3).
  RCP<const Map> getNodeMap() const;
  const SolveSummary& getSummary() const;

 private:
  // The friction of each of the problem's pairs from "Friction".
  Contact::PairFriction pairFriction() const;
  // Refuses, when both are set, an outer algorithm that does not solve the
  // law of the problem's pairs (Tresca and Coulomb pairs together too).
  void refuseWhatTheSolveWould() const;

  RCP<ContactProblem> problem_;
  RCP<Teuchos::FancyOStream> out_;
  Contact::ContactSolver parameters_;  // validation and the friction of the pairs
  std::unique_ptr<AssembledFeti> feti_;
  std::unique_ptr<Contact::FetiLoadSteps> steps_;  // the history since the unloaded state
  int stiffnessVersion_ = -1, loadVersion_ = -1, pairsVersion_ = -1;
  bool startAgain_ = true;
  int stepsBefore_ = 0;        // steps of the history solved before steps_ began
  Fem::NodalVector previous_;  // the last step's displacement (Tribos' node numbers)
  bool solved_ = false;
  SolveSummary summary_;
  RCP<Vector> u_, reaction_;
  RCP<MultiVector> contact_;
};

}  // namespace Assembled
}  // namespace Tribos
