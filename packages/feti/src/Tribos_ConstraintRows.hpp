// Tribos_ConstraintRows.hpp: the rows of FETI's constraint matrix
//   B = [B_E; B_N; B_T],  B_E u = c_E (gluing, Dirichlet),  B_N u <= c_N (contact),
// B_T the tangential rows of the contact nodes (friction).
// A row is described by the copies of the node it touches and belongs to
// the rank of its first copy's subdomain; meshConstraintRows() derives this
// rank's rows from a decomposed mesh, assembleConstraints() makes this
// rank's part of B and c from a list that holds at least them (a mesh's or
// an application's), numbering the rows rank after rank from the counts.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "Tribos_ContactConstraint.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

// The copy of a node in one subdomain that a row touches: the row's entry
// at dof c of that copy (local dof 3 localNode + c) is weight * dir[c].
struct RowCopy {
  int subdomain = -1;
  int localNode = -1;
  double weight = 1.0;
};

// One row of B.
// Kinds: equality rows (Gluing, Dirichlet: B_E u = c), the contact row of a
// node (Normal: u.dir <= c, c the gap) and its tangential rows (Tangent1,
// Tangent2: friction directions, c = 0).
struct DualRow {
  // Bonded: an equality row of a glued contact pair (its node's constraint
  // frame: n, t1, t2), whose multiplier is a force between two bodies.
  enum Kind { Gluing, Dirichlet, Normal, Tangent1, Tangent2, Bonded } kind;
  int node = -1;            // global node number (the mesh node)
  std::vector<RowCopy> copies;  // ascending subdomains
  std::array<double, 3> dir{0, 0, 0};  // direction on the 3 dofs (unit vector for gluing and Dirichlet)
  double c = 0.0;           // right-hand side
  int owner = 0;            // rank: the owner of the first copy's subdomain (FetiProblem sets it)
};

// The contact structure of this rank's dual dofs (local indices): per
// local contact node its rows and its constraint (frame, gap, master nodes,
// pair, area; Tribos_ContactConstraint.hpp).
struct LocalContact {
  std::vector<LO> normalRows;       // lambda_I rows, one per local contact node
  std::vector<LO> tangentRows;      // 2 per contact node: t1, t2 (-1: direction fixed by a Dirichlet condition)
  std::vector<int> nodes;           // mesh node of each local contact node
  std::vector<double> nodalArea;    // contact-face area attached to the node
  std::vector<ContactConstraint> constraint;  // of each local contact node
  // Glued pairs: per local bonded node its constraint and its rows along
  // n, t1, t2 (-1: a direction Dirichlet conditions fix at all its nodes).
  std::vector<ContactConstraint> bondedConstraint;
  std::vector<LO> bondedRows;  // 3 per bonded node
};

// This rank's part of the constraints: B (rows of this rank, columns the
// primal dofs), c, which rows are equalities, and the contact structure.
struct DualConstraints {
  RCP<const Map> dualMap;
  RCP<CrsMatrix> B;
  RCP<Vector> c;
  std::vector<char> isEquality;
  LocalContact contact;
};

// The gluing and Dirichlet rows of one node (global number `node`) from its
// copies (ascending subdomains), as meshConstraintRows makes them: each row
// goes to emit (the caller keeps the rows of its own rank).
void nodeRows(int node, const std::vector<Mesh::NodeCopy>& copies, const std::map<long long, double>& dirichlet,
              const std::string& gluing, bool eliminateDirichlet, const std::function<void(const DualRow&)>& emit);
// The rows of one contact constraint, appended to rows, as meshConstraintRows
// makes them: on the first copies (firstCopy(node)) of its slave and master
// nodes, leaving out the directions Dirichlet conditions fix. x: the slave
// node's position (for messages). Throws Tribos::Error naming the node for
// Dirichlet values that push it through its partner or fix an oblique mix
// of its directions.
void contactRows(const ContactConstraint& constraint, const std::function<Mesh::NodeCopy(int)>& firstCopy,
                 const std::map<long long, double>& dirichlet, const std::array<double, 3>& x, bool eliminateDirichlet,
                 std::vector<DualRow>& rows);
// This rank's rows of a decomposed mesh (those whose first copy is on one
// of its subdomains; in the order of the node numbers): gluing of the subdomain copies of every node
// ("Orthonormal", "Non-redundant" or "Full"), the Dirichlet conditions
// (none when eliminateDirichlet: FETI-1 eliminates them in the subdomains)
// and the contact constraints (Contact::contactConstraints()): per slave node a
// normal row and the tangential rows, on the slave node's first copy and
// the first copies of its master nodes (weights -N_i), leaving out the
// directions that Dirichlet conditions fix at the slave node and at every
// master node; a glued constraint gives three equality rows instead. With
// eliminateDirichlet a copy whose node has the row's direction fixed gets
// weight 0 and its prescribed part moves to c (B acts on free dofs only).
// dirichlet: by mesh node numbers, at the part's nodes and the partners;
// partners: contactPartners().
std::vector<DualRow> meshConstraintRows(const Mesh::Discretization& disc, const std::map<long long, double>& dirichlet,
                                        const std::vector<ContactConstraint>& contact, const std::string& gluing,
                                        bool eliminateDirichlet, const std::map<int, Mesh::NodeCopy>& partners = {});

// The master nodes of this rank's contact nodes that its part does not
// hold: their first copies (the rows of B name them), and their Dirichlet
// conditions, added to `dirichlet` (a row is left out where they fix its
// direction). Asked of the nodes' owners. Collective.
std::map<int, Mesh::NodeCopy> contactPartners(const Mesh::Discretization& disc,
                                              const std::vector<ContactConstraint>& contact,
                                              std::map<long long, double>& dirichlet, const Comm& comm);

// Sets every row's owner (owner[s]: the rank of subdomain s) and orders the
// rows per rank: equality rows, normal rows, tangential rows (so that every
// friction disk lives on one rank).
void distributeRows(std::vector<DualRow>& rows, const std::vector<int>& owner);

// This rank's part of B and c; primalOffsets[s]: the first global primal dof
// of subdomain s. contact: the constraints of (at least) the nodes of this
// rank's Normal and Bonded rows. Rows ordered by distributeRows(); rows of
// other ranks in the list are passed over. Collective over the primal
// map's communicator.
DualConstraints assembleConstraints(const std::vector<DualRow>& rows, const RCP<const Map>& primalMap,
                                    const std::vector<GO>& primalOffsets,
                                    const std::vector<ContactConstraint>& contact);

}  // namespace Feti
}  // namespace Tribos
