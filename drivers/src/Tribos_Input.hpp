// Tribos_Input.hpp: the XML parameter file of a Tribos run. Sublists "Mesh",
// "Material", "Boundary Conditions", "Load Steps", "Load Curves", "Contact",
// "Solver", "Output"; every entry
// is validated against validParameters() before any work, so a misspelled key
// or an unknown choice stops the run with a message naming it.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <array>
#include <string>
#include <vector>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_FetiContact.hpp"
#include "Tribos_ImplicitDynamics.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_LoadCurve.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_MeshFile.hpp"
#include "Tribos_Monolithic.hpp"
#include "Tribos_SemismoothSolve.hpp"
#include "Tribos_SemismoothStarNewton.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// The size of a mesh that is not the box of the parameters (Mesh/File): the
// counts of the mesh read.
struct MeshSize {
  double nodes = 0, cells = 0;
  int bodies = 1;
  int nodesPerCell = 8;  // 4, 8, 10 or 20; the mean, rounded up, of a mesh of several cell types
};

namespace Input {

// The complete tree of valid parameters with defaults and documentation.
// Sublists of "Boundary Conditions/Dirichlet", ".../Traction" and "Load
// Curves" may have any name; each is checked against the item lists returned
// here.
RCP<const Teuchos::ParameterList> validParameters();
const Teuchos::ParameterList& dirichletItem();
const Teuchos::ParameterList& tractionItem();
// The items of "Load Curves": Times and Values, both required.
const Teuchos::ParameterList& curveItem();
// The items of "Contact/Pairs" (friction defaults taken from the Contact
// list given) and of "Bodies" (material defaults from the Material given).
Teuchos::ParameterList pairItem(const Teuchos::ParameterList& contact);
Teuchos::ParameterList bodyItem(const Teuchos::ParameterList& material);

// Reads the file, applies "Sublist/Key=value" overrides typed as in the valid
// list, validates and fills defaults. Throws Tribos::Error naming the file,
// the parameter and the valid choices.
RCP<Teuchos::ParameterList> read(const std::string& file, const std::vector<std::string>& overrides);

// Validates an in-memory list in place (as read() does after parsing).
void validate(Teuchos::ParameterList& params, const std::string& source);

// Overrides one entry: path "Sublist/.../Key", value as text.
void applyOverride(Teuchos::ParameterList& params, const std::string& assignment);

// How a validated run is solved; the one place that reads Solver/Type,
// Contact/Enabled and Solver/Outer Algorithm together.
enum class Method { Monolithic, FetiLinear, FetiContact, Semismooth, FetiDynamics };
Method method(const Teuchos::ParameterList& params);

// Whether the run steps in time (Dynamics/Enabled, docs/dynamics.md).
bool dynamics(const Teuchos::ParameterList& params);
// Whether FETI solves the run's contact: Method::FetiContact, or a Dynamics
// run with Contact/Enabled (its contact search, constraints and checks).
bool fetiContact(const Teuchos::ParameterList& params);
// Dynamics' step, scheme and Initial Conditions/Velocity; with the mesh,
// the velocity of each of its bodies too.
Contact::DynamicsSpec dynamicsSpec(const Teuchos::ParameterList& params);
Contact::DynamicsSpec dynamicsSpec(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);
// The initial velocity of every body of the mesh: Bodies/NAME/Initial
// Velocity where given, Initial Conditions/Velocity elsewhere.
std::vector<std::array<double, 3>> initialVelocities(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);
// A Dynamics run whose bodies share nodes (bonded) with different initial
// velocities is refused, naming both bodies, their parameters and a node.
// On the whole mesh, before any work.
void checkBondedVelocities(const Mesh::Mesh& mesh, const Teuchos::ParameterList& params);
// Output/Step Stride: a run of several steps writes every k-th step's data
// file and the last; at most kMaxStepStride (the rows of the steps between
// two written ones wait in memory, 1-2 kB each).
constexpr int kMaxStepStride = 10000;
int stepStride(const Teuchos::ParameterList& params);
// Material/Density of every body of the mesh (Bodies' own where named).
Fem::BodyDensities densities(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);

// Builders from a validated list.
Mesh::BoxSpec boxSpec(const Teuchos::ParameterList& params);
// Mesh/File: the Gmsh file of the body ("" for the box). read() makes a
// relative path absolute (relative to the input file's directory).
std::string meshFile(const Teuchos::ParameterList& params);
// How Mesh/File is read: Run Geo Script, Geo Time Limit, and the run's
// memory limit (bytes, 0 for none).
Mesh::MeshFileOptions meshFileOptions(const Teuchos::ParameterList& params, double memoryLimit);
// The mesh of the run: the box of boxSpec(), or the bodies read from
// meshFile() (Mesh::readMeshFile with meshFileOptions(params, memoryLimit);
// its warnings are added to `warnings`, printed on std::cerr when null). The
// driver reads on rank 0 only.
Mesh::Mesh mesh(const Teuchos::ParameterList& params, std::vector<std::string>* warnings = nullptr,
                double memoryLimit = 0);
// Every face the conditions and the contact name exists in `mesh`; throws
// naming the parameter, the file and the names the mesh has.
void checkMeshFaces(const Mesh::Mesh& mesh, const Teuchos::ParameterList& params);
// The problem's scales within [kMinScale, kMaxScale] (checked before any
// work, on the mesh the run has): the stiffness E L of every material (L the
// mesh's extent), the resultant of the loads (|t| L^2, |b| L^3), the
// displacement they cause (load / (E L)), the prescribed displacements, gaps
// and plane points. The solver forms products of these (K u, the work u'f,
// F = B K+ B', squared norms); within this window every such product is
// representable in double precision with room to spare, and physical
// problems in any consistent units lie far inside it. Throws naming the
// parameter, its value and the scale it gives.
constexpr double kMinScale = 1e-100, kMaxScale = 1e100;
void checkScales(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);
// Mesh/Subdomain Size: "Grid" (or 0: Subdomain Grid, or Subdomains for
// METIS, as given), a positive H (subdomains of about H cells per edge: a
// grid of boxes of the box mesh, or METIS parts of about (H+1)^3 nodes), or
// "Auto" (H by automaticSubdomainSize). Throws naming the parameter.
struct SubdomainSizing {
  enum Kind { Grid, Fixed, Auto } kind = Grid;
  int H = 0;  // Fixed only
};
SubdomainSizing subdomainSizing(const Teuchos::ParameterList& params);
// The measured rule (docs/scaling.md, Tet4 bricks on 2 ranks): H = 4 is the
// fastest while it gives at most kAutoSubdomains subdomains (measured up to
// 10 125 of them), H = 6 beyond, where the coarse problem (6 rows per
// subdomain, replicated on every rank) is expected to outgrow what the
// smaller dense blocks save; then H is lowered until there are at least
// numRanks subdomains. subdomainsOfSize(H): the count size H gives.
constexpr double kAutoSubdomains = 12000;
template <class Count>
int automaticSubdomainSize(const Count& subdomainsOfSize, int numRanks) {
  int H = subdomainsOfSize(4) <= kAutoSubdomains ? 4 : 6;
  while (H > 1 && subdomainsOfSize(H) < numRanks) --H;
  return H;
}
// The METIS parts of a mesh file (docs/scaling.md, "The parts of a mesh
// file"): measured on nine geometries of 2300 to 37 000 nodes on 2 ranks
// (lap joints, Hertz, Cattaneo-Mindlin, two blocks; histories and single
// steps), parts larger than the box's are faster while a rank holds few
// nodes, where the iterations cost more than the setup: H = 6 (within 1.31x
// of the best of 4, 5, 6, 8 on every one; 8 left some bodies one part and
// cost up to 2x) up to kAutoLargePartsNodes nodes per rank (the largest
// measured: 18 700), the box's rule beyond, where the setup of the dense
// blocks dominates as on the brick. Then H is lowered until every rank
// has a part.
constexpr double kAutoLargePartsNodes = 25000;
template <class Count>
int automaticMeshFileSubdomainSize(double nodes, const Count& subdomainsOfSize, int numRanks) {
  if (nodes / numRanks > kAutoLargePartsNodes) return automaticSubdomainSize(subdomainsOfSize, numRanks);
  int H = 6;
  while (H > 1 && subdomainsOfSize(H) < numRanks) --H;
  return H;
}
// The decomposition of the run on numRanks ranks. A mesh file sized by
// Subdomain Size needs the mesh's counts (*meshSize): without them its
// METIS subdomain count is left 0 (not known before the file is read); with
// them, at least one subdomain per rank and per body, at most one per cell.
Mesh::DecompositionSpec decompositionSpec(const Teuchos::ParameterList& params, int numRanks,
                                          const MeshSize* meshSize = nullptr);
// The grid of boxes along x, y, z whose boxes have about H cells per edge:
// along each axis the divisor of the cell count nearest (in ratio) to cells / H.
std::array<int, 3> subdomainGridOfSize(const std::array<int, 3>& cells, int H);
Fem::Material material(const Teuchos::ParameterList& params);
// The material of every body of the mesh: Bodies/NAME/Material, or Material
// for the bodies not named.
Fem::BodyMaterials materials(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);
// The contact pairs of the run: Contact/Pairs, or the rigid plane beyond
// Contact/Face (planeBeyondFace) when there are none; empty without contact.
std::vector<Contact::ContactPair> contactPairs(const Teuchos::ParameterList& params, const Mesh::Mesh& mesh);
// The friction of each pair of contactPairs() (glued pairs: frictionless).
Contact::PairFriction pairFriction(const Teuchos::ParameterList& params);
// Every load at its full Value (the static problem: the run without Load
// Steps and Curves); the base of loadHistory().
Fem::LoadCase loadCase(const Teuchos::ParameterList& params);

// The load history (docs/load_history.md). Load Steps/Times: the times at
// which the run solves, {1} without Load Steps.
std::vector<double> loadStepTimes(const Teuchos::ParameterList& params);
// Load Curves/NAME as a curve whose messages name its path; "" the ramp
// min(t, 1) of a load without a Curve.
Fem::LoadCurve loadCurve(const Teuchos::ParameterList& params, const std::string& name);
// loadCase() with the curve of each load (validate() checked that every
// curve named exists and covers every step time).
Fem::LoadHistory loadHistory(const Teuchos::ParameterList& params);
// The loads at time t: each Value times its curve at t (min(t, 1) without
// one); equals loadCase() at t = 1 for an input without Curves.
Fem::LoadCase loadCaseAt(const Teuchos::ParameterList& params, double t);

// The rigid-plane contact of the semismooth* method: Contact/Face, Gap and
// the slip bound per unit area (Slip Bound Traction; 0 when frictionless).
using PlaneContact = Semismooth::PlaneContact;
PlaneContact planeContact(const Teuchos::ParameterList& params);
// The whole semismooth* problem of a validated list, on the mesh of
// mesh(params): what the prism benchmark and tests solve.
Semismooth::MeshContactProblem semismoothProblem(const Teuchos::ParameterList& params);

}  // namespace Input
}  // namespace Tribos
