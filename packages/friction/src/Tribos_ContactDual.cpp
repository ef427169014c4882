#include "Tribos_ContactDual.hpp"

#include "Tribos_QP_Utils.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Friction {

void ContactDual::check() const {
  TRIBOS_REQUIRE(!A.is_null() && !b.is_null(), "ContactDual: Hessian A and vector b are required");
  const size_t nc = normalRows.size();
  TRIBOS_REQUIRE(tangentRows.size() == 2 * nc, "ContactDual: " << tangentRows.size() << " tangential rows for " << nc
                                                                << " contacts (need 2 per contact)");
  TRIBOS_REQUIRE(normalLower.size() == nc && normalOffset.size() == nc,
                 "ContactDual: normalLower/normalOffset need one entry per contact");
  TRIBOS_REQUIRE(slipBound.empty() || slipBound.size() == nc, "ContactDual: slipBound needs one entry per contact");
  TRIBOS_REQUIRE(frictionCoefficient.empty() || frictionCoefficient.size() == nc,
                 "ContactDual: frictionCoefficient needs one entry per contact");
  const LO n = static_cast<LO>(map()->getNodeNumElements());
  for (LO i : normalRows) TRIBOS_REQUIRE(i >= 0 && i < n, "ContactDual: normal row " << i << " out of range");
  for (LO i : tangentRows) TRIBOS_REQUIRE(i >= -1 && i < n, "ContactDual: tangential row " << i << " out of range");
  TRIBOS_REQUIRE(tangentCenter.empty() || tangentCenter.size() == 2 * nc,
                 "ContactDual: tangentCenter needs two entries per contact");
  for (SC c : tangentCenter) TRIBOS_REQUIRE(std::isfinite(c), "ContactDual: tangentCenter " << c << " is not finite");
}

QP::ConstraintSet ContactDual::constraintSet(const std::vector<SC>& g) const {
  QP::ConstraintSet Omega(map());
  std::vector<SC> r;  // radii of the circles, in the order they are set
  for (int k = 0; k < numLocalContacts(); ++k) {
    Omega.setLower(normalRows[k], normalLower[k]);
    const SC gk = g.empty() ? 0.0 : std::max(g[k], 0.0);
    const LO t1 = tangentRows[2 * k], t2 = tangentRows[2 * k + 1];
    const SC c1 = tangentCenter.empty() ? 0.0 : tangentCenter[2 * k];
    const SC c2 = tangentCenter.empty() ? 0.0 : tangentCenter[2 * k + 1];
    if (t1 >= 0 && t2 >= 0) {
      Omega.setCircle(t1, t2, static_cast<int>(r.size()), c1, c2);
      r.push_back(gk);
    } else if (t1 >= 0) {  // the disk of one remaining direction: an interval
      Omega.setBox(t1, c1 - gk, c1 + gk);
    } else if (t2 >= 0) {
      Omega.setBox(t2, c2 - gk, c2 + gk);
    }
  }
  Omega.setRadii(r);
  return Omega;
}

SC ContactDual::hessianNorm(int powerSteps, long& n_A) const {
  if (normAEstimate > 0 && normAOf.get() == A.get()) return normAEstimate;
  return QP::estimateNorm(*A, powerSteps, n_A);
}

std::vector<SC> ContactDual::normalForce(const Vector& x) const {
  auto xv = x.getData();
  std::vector<SC> lambdaN(numLocalContacts());
  for (int k = 0; k < numLocalContacts(); ++k) lambdaN[k] = xv[normalRows[k]] + normalOffset[k];
  return lambdaN;
}

bool ContactDual::coulombOnSomeRank() const {
  int local = frictionCoefficient.empty() ? 0 : 1, any = 0;
  Teuchos::reduceAll(*map()->getComm(), Teuchos::REDUCE_MAX, local, Teuchos::outArg(any));
  return any != 0;
}

std::vector<SC> ContactDual::coulombSlipBound(const Vector& x) const {
  TRIBOS_REQUIRE(frictionCoefficient.size() == normalRows.size(), "Coulomb friction needs a friction coefficient per contact");
  auto lambdaN = normalForce(x);
  for (int k = 0; k < numLocalContacts(); ++k) lambdaN[k] = frictionCoefficient[k] * std::max(lambdaN[k], 0.0);
  return lambdaN;
}

std::vector<char> ContactDual::tangentBlockMask() const {
  std::vector<char> mask(map()->getNodeNumElements(), 0);
  for (LO i : tangentRows)
    if (i >= 0) mask[i] = 1;
  return mask;
}

std::vector<char> ContactDual::normalBlockMask() const {
  auto mask = tangentBlockMask();
  for (auto& m : mask) m = !m;
  return mask;
}

SC globalNorm(const std::vector<SC>& a, const Comm& comm) {
  SC local = 0, global = 0;
  for (SC v : a) local += v * v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return std::sqrt(global);
}

SC globalDistance(const std::vector<SC>& a, const std::vector<SC>& b, const Comm& comm) {
  SC local = 0, global = 0;
  for (size_t k = 0; k < a.size(); ++k) local += (a[k] - b[k]) * (a[k] - b[k]);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return std::sqrt(global);
}

}  // namespace Friction
}  // namespace Tribos
