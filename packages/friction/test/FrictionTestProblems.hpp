// FrictionTestProblems.hpp: small dual contact problems (1-3 contacts) whose
// solution the tests know without the library: either manufactured (choose
// the solution and the state of every contact, then the right-hand side that
// makes it a KKT point; A is SPD, so a Tresca KKT point is the minimizer) or
// enumerated (one tangential direction per contact, every stick/slip and
// contact/separation state solved as a linear system, the consistent one
// kept). The dense side is plain std::vector; buildDual spreads a problem
// over the ranks as a Friction::ContactDual on Tpetra objects.
#pragma once

#include <Teuchos_FancyOStream.hpp>

#include <string>
#include <vector>

#include "Tribos_ContactDual.hpp"

namespace frictest {

using Tribos::RCP;
using Vec = std::vector<double>;

struct Dense {
  int n = 0;
  Vec a;
  explicit Dense(int size = 0) : n(size), a(size * size, 0.0) {}
  double& operator()(int i, int j) { return a[i * n + j]; }
  double operator()(int i, int j) const { return a[i * n + j]; }
};

Vec multiply(const Dense& A, const Vec& x);
double norm(const Vec& x);
double maxAbsDiff(const Vec& a, const Vec& b);
// Gaussian elimination with partial pivoting; false when A is singular.
bool solveDense(Dense A, Vec b, Vec& x);

// Disk: both tangential directions free (a circle of radius g per contact).
// Interval: the second direction fixed, as a Dirichlet condition does it.
enum class Tangent { Disk, Interval };
enum class Law { Tresca, Coulomb };

struct Problem {
  int contacts = 0;
  Tangent tangent = Tangent::Disk;
  Law law = Law::Tresca;
  Dense A;
  Vec b;
  Vec lower, offset;   // l_k and the normal-force offset, per contact
  Vec slipBound;       // Tresca g_k
  Vec friction;        // Coulomb F_k
  std::vector<Vec> G;  // rows of the equality constraint G x = 0 (may be empty)

  int dofsPerContact() const { return tangent == Tangent::Disk ? 3 : 2; }
  int size() const { return contacts * dofsPerContact(); }
  int normal(int k) const { return dofsPerContact() * k; }
  int tangential(int k, int j) const { return dofsPerContact() * k + 1 + j; }
  int tangentialDims() const { return dofsPerContact() - 1; }
};

// SPD matrix with ||A|| <= 1 (the scaling the algorithms' defaults assume);
// coupling in [0, 1] sets the off-diagonal weight.
Dense spdMatrix(int n, unsigned seed, double coupling);
// A with the normal-tangential blocks removed (still SPD).
Dense withoutNormalTangentialCoupling(const Problem& p, Dense A);

// The state of one contact in the manufactured solution.
struct ContactState {
  bool touching;    // x_N > l (positive contact force) or x_N = l (separated)
  bool slipping;    // ||x_T|| = g, or ||x_T|| = g / 2 (stick)
  double angle;     // direction of x_T (Interval: sign of cos)
};

struct Manufactured {
  Problem problem;
  Vec x;   // the solution
  Vec mu;  // the multiplier of G x = 0
};

struct ManufacturedOptions {
  Tangent tangent = Tangent::Disk;
  Law law = Law::Tresca;
  int equalityRows = 0;
  double coupling = 0.5;
  bool decoupled = false;
  double lower = 0.0;      // l_k of every contact
  double offset = 0.0;     // normal-force offset of every contact (Coulomb)
  double friction = 0.3;   // Coulomb F_k
  unsigned seed = 1;
};

Manufactured manufacture(const std::vector<ContactState>& states, const ManufacturedOptions& opt);

// Slip bound of the problem at x: g (Tresca) or F max(x_N + offset, 0).
Vec slipBoundAt(const Problem& p, const Vec& x);
// ||x - P_Omega(x - (A x - b + G'mu))|| / ||b||, Omega with slip bound g: zero
// exactly at a KKT point of the Tresca problem with that bound.
double naturalResidual(const Problem& p, const Vec& x, const Vec& mu, const Vec& g);
// max_k of the violation of x_N >= l, ||x_T|| <= g and G x = 0.
double feasibilityViolation(const Problem& p, const Vec& x, const Vec& g);

// Every solution of the Interval problem (no G) over the 6^contacts states,
// duplicates removed: a well-posed problem has exactly one.
std::vector<Vec> enumerateSolutions(const Problem& p);

// The problem on the ranks of comm: contacts split into contiguous blocks,
// the 2 or 3 unknowns of a contact on one rank.
struct DistributedDual {
  Tribos::Friction::ContactDual dual;
  RCP<const Tribos::Map> map;
  int firstContact = 0;  // global index of this rank's first contact
};
DistributedDual buildDual(const Problem& p, const RCP<const Tribos::Comm>& comm);
RCP<Tribos::Vector> toVector(const RCP<const Tribos::Map>& map, const Vec& x);
Vec gather(const Tribos::Vector& x);
// Per-contact local values (e.g. FrictionStatus::slipBound) on every rank.
Vec gatherContacts(const Vec& local, const DistributedDual& d, int contacts);

// Quiet, tight parameters for the friction solvers.
Teuchos::ParameterList solverParameters(double tolerance);

}  // namespace frictest
