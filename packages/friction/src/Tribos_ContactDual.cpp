#include "Tribos_ContactDual.hpp"

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
  for (LO i : tangentRows) TRIBOS_REQUIRE(i >= 0 && i < n, "ContactDual: tangential row " << i << " out of range");
}

QP::ConstraintSet ContactDual::constraintSet(const std::vector<SC>& g) const {
  QP::ConstraintSet Omega(map());
  for (int k = 0; k < numLocalContacts(); ++k) {
    Omega.setLower(normalRows[k], normalLower[k]);
    Omega.setCircle(tangentRows[2 * k], tangentRows[2 * k + 1], k);
  }
  std::vector<SC> r(g.size());
  for (size_t k = 0; k < g.size(); ++k) r[k] = std::max(g[k], 0.0);
  Omega.setRadii(r);
  return Omega;
}

std::vector<SC> ContactDual::normalForce(const Vector& x) const {
  auto xv = x.getData();
  std::vector<SC> lambdaN(numLocalContacts());
  for (int k = 0; k < numLocalContacts(); ++k) lambdaN[k] = xv[normalRows[k]] + normalOffset[k];
  return lambdaN;
}

std::vector<SC> ContactDual::coulombSlipBound(const Vector& x) const {
  TRIBOS_REQUIRE(frictionCoefficient.size() == normalRows.size(), "Coulomb friction needs a friction coefficient per contact");
  auto lambdaN = normalForce(x);
  for (int k = 0; k < numLocalContacts(); ++k) lambdaN[k] = frictionCoefficient[k] * std::max(lambdaN[k], 0.0);
  return lambdaN;
}

std::vector<char> ContactDual::tangentBlockMask() const {
  std::vector<char> mask(map()->getNodeNumElements(), 0);
  for (LO i : tangentRows) mask[i] = 1;
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
