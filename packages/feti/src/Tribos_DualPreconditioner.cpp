#include "Tribos_DualPreconditioner.hpp"

#include <Tpetra_CrsMatrix.hpp>

#include <algorithm>
#include <functional>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

namespace {

// x = A^+ b for symmetric positive semidefinite A = BB' or B'B by conjugate
// gradients from x = 0: the minimum-norm solution of A x = b for b in range A.
// Both Gram matrices are block diagonal with one small block per mesh node,
// so they have few distinct eigenvalues and CG ends in a few dozen steps.
void gramSolve(const std::function<void(const Vector&, Vector&)>& A, const Vector& b, Vector& x) {
  const auto map = b.getMap();
  Vector r(map), p(map), q(map);
  x.putScalar(0.0);
  r.assign(b);
  p.assign(b);
  double rr = r.dot(r);
  const double stop = 1e-24 * rr;  // relative residual 1e-12
  for (int it = 0; it < 200 && rr > stop; ++it) {
    A(p, q);
    const double alpha = rr / p.dot(q);
    x.update(alpha, p, 1.0);
    r.update(-alpha, q, 1.0);
    const double rrNew = r.dot(r);
    p.update(1.0, r, rrNew / rr);
    rr = rrNew;
  }
}

}  // namespace

const std::vector<std::string>& DualPreconditioner::kinds() {
  static const std::vector<std::string> k{"None", "Lumped", "Dirichlet", "Lumped Unscaled"};
  return k;
}

DualPreconditioner::DualPreconditioner(const FetiDual& dual, const std::string& kind)
    : dual_(dual), kind_(kind), map_(dual.problem().dualMap()), pw_(dual.problem().primalMap()),
      v_(dual.problem().primalMap()), Kv_(dual.problem().primalMap()), tmp_(map_), scaled_(map_), y_(map_) {
  const auto& k = kinds();
  TRIBOS_REQUIRE(std::find(k.begin(), k.end(), kind) != k.end(), "unknown FETI preconditioner \"" << kind << "\"");
}

void DualPreconditioner::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, SC alpha, SC beta) const {
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    applyOne(*X.getVector(j), y_);
    Y.getVectorNonConst(j)->update(alpha, y_, beta);
  }
}

void DualPreconditioner::applyOne(const Vector& w, Vector& y) const {
  if (kind_ == "None") {
    y.assign(w);
    return;
  }
  const FetiProblem& prob = dual_.problem();
  const CrsMatrix& B = *prob.B();
  B.apply(w, pw_, Teuchos::TRANS);
  if (kind_ == "Lumped Unscaled") {
    prob.applyK(pw_, Kv_);
    B.apply(Kv_, tmp_);
    dual_.coarse().project(tmp_, y);
    return;
  }
  auto BtB = [&](const Vector& x, Vector& out) {
    B.apply(x, tmp_);
    B.apply(tmp_, out, Teuchos::TRANS);
  };
  auto BBt = [&](const Vector& x, Vector& out) {  // pw_ is free once v_ = (B'B)^+ B'w
    B.apply(x, pw_, Teuchos::TRANS);
    B.apply(pw_, out);
  };
  gramSolve(BtB, pw_, v_);
  if (kind_ == "Lumped") prob.applyK(v_, Kv_);
  else prob.applySchur(v_, Kv_);
  B.apply(Kv_, tmp_);
  gramSolve(BBt, tmp_, scaled_);
  dual_.coarse().project(scaled_, y);
}

}  // namespace Feti
}  // namespace Tribos
