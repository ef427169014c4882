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
  if (kind_ == "Lumped Unscaled") {
    B.apply(w, pw_, Teuchos::TRANS);
    prob.applyKBoundary(pw_, Kv_);
    B.apply(Kv_, tmp_);
    dual_.coarse().project(tmp_, y);
    return;
  }
  scaledTranspose(w, v_);
  if (kind_ == "Lumped") prob.applyKBoundary(v_, Kv_);
  else prob.applySchur(v_, Kv_);
  scaled(Kv_, scaled_);
  dual_.coarse().project(scaled_, y);
}

void DualPreconditioner::scaleByJacobi(Vector& x) const {
  if (jacobi_.empty()) {
    const CrsMatrix& B = *dual_.problem().B();
    jacobi_.assign(B.getNodeNumRows(), 0.0);
    for (size_t i = 0; i < jacobi_.size(); ++i) {
      CrsMatrix::local_inds_host_view_type columns;
      CrsMatrix::values_host_view_type values;
      B.getLocalRowView(static_cast<LO>(i), columns, values);
      double norm2 = 0;
      for (size_t k = 0; k < values.extent(0); ++k) norm2 += values(k) * values(k);
      jacobi_[i] = norm2 > 0 ? 1.0 / norm2 : 0.0;
    }
  }
  auto xv = x.getDataNonConst();
  for (size_t i = 0; i < jacobi_.size(); ++i) xv[i] *= jacobi_[i];
}

void DualPreconditioner::scaledTranspose(const Vector& w, Vector& v) const {
  const CrsMatrix& B = *dual_.problem().B();
  if (dual_.problem().orthonormalEqualityRows()) {
    scaled_.assign(w);
    scaleByJacobi(scaled_);
    B.apply(scaled_, v, Teuchos::TRANS);
    return;
  }
  B.apply(w, pw_, Teuchos::TRANS);
  gramSolve(
      [&](const Vector& x, Vector& out) {
        B.apply(x, tmp_);
        B.apply(tmp_, out, Teuchos::TRANS);
      },
      pw_, v);
}

void DualPreconditioner::scaled(const Vector& u, Vector& y) const {
  const CrsMatrix& B = *dual_.problem().B();
  B.apply(u, tmp_);
  if (dual_.problem().orthonormalEqualityRows()) {
    y.assign(tmp_);
    scaleByJacobi(y);
    return;
  }
  gramSolve(
      [&](const Vector& x, Vector& out) {
        B.apply(x, pw_, Teuchos::TRANS);
        B.apply(pw_, out);
      },
      tmp_, y);
}

}  // namespace Feti
}  // namespace Tribos
