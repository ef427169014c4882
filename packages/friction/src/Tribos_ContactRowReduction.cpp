#include "Tribos_ContactRowReduction.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_DenseCholesky.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {
namespace Friction {

namespace {

// Column j of a column-major matrix with ld rows.
inline double* column(std::vector<double>& M, size_t ld, size_t j) { return M.data() + j * ld; }

// Rows of a replicated multivector, one std::vector per column.
std::vector<std::vector<double>> gatherColumns(const MultiVector& X, const RCP<const Map>& replicated, const Import& imp) {
  MultiVector R(replicated, X.getNumVectors());
  R.doImport(X, imp, Tpetra::INSERT);
  std::vector<std::vector<double>> out(X.getNumVectors());
  for (size_t c = 0; c < X.getNumVectors(); ++c) {
    auto v = R.getVector(c)->getData();
    out[c].assign(v.begin(), v.end());
  }
  return out;
}

// A as a dense n x n column-major matrix on every rank, from n applications
// (in blocks of columns, each one collective).
std::vector<double> denseOperator(const Operator& A, const RCP<const Map>& map, const RCP<const Map>& replicated,
                                  const Import& imp, long& applications) {
  const size_t n = map->getGlobalNumElements();
  const size_t block = 32;
  std::vector<double> D(n * n);
  for (size_t j0 = 0; j0 < n; j0 += block) {
    const size_t nb = std::min(block, n - j0);
    MultiVector E(map, nb), Y(map, nb);
    for (size_t c = 0; c < nb; ++c) {
      const GO j = static_cast<GO>(j0 + c);
      if (map->isNodeGlobalElement(j)) E.replaceGlobalValue(j, c, 1.0);
    }
    A.apply(E, Y);
    applications += static_cast<long>(nb);
    const auto cols = gatherColumns(Y, replicated, imp);
    for (size_t c = 0; c < nb; ++c) std::copy(cols[c].begin(), cols[c].end(), column(D, n, j0 + c));
  }
  return D;
}

// G as an r x n column-major matrix on every rank, row by row from G'.
std::vector<double> denseConstraint(const QP::EqualityConstraint& G, const RCP<const Map>& map,
                                    const RCP<const Map>& replicated, const Import& imp, size_t& r) {
  const auto range = G.rangeMap();
  r = range->getGlobalNumElements();
  const size_t n = map->getGlobalNumElements();
  std::vector<double> Gd(r * n);
  Vector y(range), gt(map);
  for (size_t i = 0; i < r; ++i) {
    y.putScalar(0.0);
    if (range->isNodeGlobalElement(static_cast<GO>(i))) y.replaceGlobalValue(static_cast<GO>(i), 1.0);
    G.applyTranspose(y, gt);
    const auto row = gatherColumns(gt, replicated, imp)[0];
    for (size_t j = 0; j < n; ++j) Gd[j * r + i] = row[j];
  }
  return Gd;
}

LocalCsr denseRows(const std::vector<double>& M, int rows, int cols) {  // M column-major
  LocalCsr out;
  out.rows = rows;
  out.cols = cols;
  out.col.reserve(static_cast<size_t>(rows) * cols);
  out.val.reserve(static_cast<size_t>(rows) * cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      out.col.push_back(j);
      out.val.push_back(M[static_cast<size_t>(j) * rows + i]);
    }
    out.rowptr.push_back(static_cast<int>(out.col.size()));
  }
  return out;
}

}  // namespace

ContactRowReduction::ContactRowReduction(const ContactDual& dual) : map_(dual.map()) {
  dual.check();
  const size_t n = map_->getGlobalNumElements();
  TRIBOS_REQUIRE(n == 0 || (map_->getMinAllGlobalIndex() == 0 && map_->getMaxAllGlobalIndex() == static_cast<GO>(n) - 1),
                 "the dual's map does not number its rows 0.." << n - 1);
  const auto comm = map_->getComm();
  replicated_ = rcp(new Map(n, 0, comm, Tpetra::LocallyReplicated));
  toReplicated_ = rcp(new Import(map_, replicated_));
  const Import& imp = *toReplicated_;

  // The contact structure on every rank: per row its kind (0 free, 1 normal,
  // 2 tangential) and, on normal rows, the contact's data.
  enum { kKind, kT1, kT2, kLower, kOffset, kFriction, kSlip, kCentre, kColumns };
  MultiVector info(map_, kColumns);
  for (int k = 0; k < dual.numLocalContacts(); ++k) {
    const LO nr = dual.normalRows[k];
    info.replaceLocalValue(nr, kKind, 1.0);
    for (int j = 0; j < 2; ++j) {
      const LO t = dual.tangentRows[2 * k + j];
      info.replaceLocalValue(nr, kT1 + j, t < 0 ? -1.0 : static_cast<double>(map_->getGlobalElement(t)));
      if (t < 0) continue;
      info.replaceLocalValue(t, kKind, 2.0);
      info.replaceLocalValue(t, kCentre, dual.tangentCenter.empty() ? 0.0 : dual.tangentCenter[2 * k + j]);
    }
    info.replaceLocalValue(nr, kLower, dual.normalLower[k]);
    info.replaceLocalValue(nr, kOffset, dual.normalOffset[k]);
    info.replaceLocalValue(nr, kFriction, dual.frictionCoefficient.empty() ? 0.0 : dual.frictionCoefficient[k]);
    info.replaceLocalValue(nr, kSlip, dual.slipBound.empty() ? 0.0 : dual.slipBound[k]);
  }
  const auto all = gatherColumns(info, replicated_, imp);

  ContactDual& rc = reduced_.contacts;
  for (size_t i = 0; i < n; ++i) {
    if (all[kKind][i] == 0.0) freeRows_.push_back(static_cast<int>(i));
    if (all[kKind][i] != 1.0) continue;
    rc.normalRows.push_back(static_cast<LO>(contactRows_.size()));
    contactRows_.push_back(static_cast<int>(i));
    for (int j = 0; j < 2; ++j) {
      const double t = all[kT1 + j][i];
      rc.tangentRows.push_back(t < 0 ? -1 : static_cast<LO>(contactRows_.size()));
      rc.tangentCenter.push_back(t < 0 ? 0.0 : all[kCentre][static_cast<size_t>(t)]);
      if (t >= 0) contactRows_.push_back(static_cast<int>(t));
    }
    rc.normalLower.push_back(all[kLower][i]);
    rc.normalOffset.push_back(all[kOffset][i]);
    rc.frictionCoefficient.push_back(all[kFriction][i]);
    rc.slipBound.push_back(all[kSlip][i]);
  }
  // Empty means "no such data" on every rank; a rank without contacts has
  // empty vectors whatever the law, so the decision is collective (else that
  // rank would solve the replicated problem under another law).
  auto onNoRank = [&comm](bool empty) {
    int local = empty ? 0 : 1, any = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, local, Teuchos::outArg(any));
    return any == 0;
  };
  if (!dual.coulombOnSomeRank()) rc.frictionCoefficient.clear();
  if (onNoRank(dual.slipBound.empty())) rc.slipBound.clear();

  // A~ = A + G'G, dense, and G.
  std::vector<double> At;
  if (dual.denseA) At = dual.denseA();
  if (At.empty()) At = denseOperator(*dual.A, map_, replicated_, imp, applications_);
  TRIBOS_REQUIRE(At.size() == n * n, "the dense form of A has " << At.size() << " entries, not " << n << "^2");
  size_t r = 0;
  std::vector<double> Gd;
  if (!dual.G.is_null()) Gd = denseConstraint(*dual.G, map_, replicated_, imp, r);
  Teuchos::BLAS<int, double> blas;
  const int N = static_cast<int>(n), R = static_cast<int>(r);
  if (r > 0) blas.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, N, N, R, 1.0, Gd.data(), R, Gd.data(), R, 1.0, At.data(), N);
  const auto bv = gatherColumns(*dual.b, replicated_, imp)[0];
  const auto bRef = dual.bReference.is_null() ? bv : gatherColumns(*dual.bReference, replicated_, imp)[0];

  const int m = static_cast<int>(contactRows_.size()), e = static_cast<int>(freeRows_.size());
  const auto& C = contactRows_;
  const auto& E = freeRows_;
  auto at = [&](int i, int j) { return At[static_cast<size_t>(j) * n + i]; };
  auto g = [&](int k, int j) { return Gd[static_cast<size_t>(j) * r + k]; };

  // K = (A~_EE)^-1 by Cholesky; Z = K [A~_EC G_E'], K b_E, K bRef_E.
  std::vector<double> AEE(static_cast<size_t>(e) * e);
  for (int b = 0; b < e; ++b)
    for (int a = 0; a < e; ++a) AEE[static_cast<size_t>(b) * e + a] = at(E[a], E[b]);
  DenseCholesky K;
  TRIBOS_REQUIRE(K.tryFactor(std::move(AEE), e),
                 "the " << e << " rows without contact and the equality constraint leave the multipliers undetermined "
                        "(A + G'G is singular on those rows): the contact alone holds part of the problem");
  Z_.assign(static_cast<size_t>(e) * (m + R), 0.0);
  for (int c = 0; c < m; ++c)
    for (int a = 0; a < e; ++a) Z_[static_cast<size_t>(c) * e + a] = at(E[a], C[c]);
  for (int k = 0; k < R; ++k)
    for (int a = 0; a < e; ++a) Z_[static_cast<size_t>(m + k) * e + a] = g(k, E[a]);
  Kb_.resize(e);
  std::vector<double> KbRef(e);
  for (int a = 0; a < e; ++a) Kb_[a] = bv[E[a]], KbRef[a] = bRef[E[a]];
  K.solve(Z_.data(), m + R);
  K.solve(Kb_);
  K.solve(KbRef);

  // T = [A~_CC G_C'] - A~_CE Z = [W Gh'] (m x (m + r)).
  std::vector<double> T(static_cast<size_t>(m) * (m + R)), ACE(static_cast<size_t>(m) * e);
  for (int c = 0; c < m; ++c)
    for (int i = 0; i < m; ++i) T[static_cast<size_t>(c) * m + i] = at(C[i], C[c]);
  for (int k = 0; k < R; ++k)
    for (int i = 0; i < m; ++i) T[static_cast<size_t>(m + k) * m + i] = g(k, C[i]);
  for (int a = 0; a < e; ++a)
    for (int i = 0; i < m; ++i) ACE[static_cast<size_t>(a) * m + i] = at(C[i], E[a]);
  if (e > 0 && m > 0)
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, m, m + R, e, -1.0, ACE.data(), m, Z_.data(), e, 1.0, T.data(), m);
  reduced_.A = denseRows(T, m, m + R);

  // border = [Gh -Ch], Gh = (Gh')', Ch = G_E Z_alpha; e = -G_E K b_E.
  std::vector<double> Bd(static_cast<size_t>(R) * (m + R), 0.0);
  for (int k = 0; k < R; ++k) {
    for (int i = 0; i < m; ++i) Bd[static_cast<size_t>(i) * R + k] = T[static_cast<size_t>(m + k) * m + i];
    for (int l = 0; l < R; ++l) {
      double s = 0;
      for (int a = 0; a < e; ++a) s += g(k, E[a]) * Z_[static_cast<size_t>(m + l) * e + a];
      Bd[static_cast<size_t>(m + l) * R + k] = -s;
    }
  }
  reduced_.border = denseRows(Bd, R, m + R);
  reduced_.e.assign(R, 0.0);
  for (int k = 0; k < R; ++k)
    for (int a = 0; a < e; ++a) reduced_.e[k] -= g(k, E[a]) * Kb_[a];

  // q = b_C - A~_CE K b_E (and the same of bReference).
  auto serialMap = rcp(new Map(static_cast<size_t>(m), 0, rcp(new Teuchos::SerialComm<int>())));
  auto q = rcp(new Vector(serialMap)), qRef = rcp(new Vector(serialMap));
  {
    auto qv = q->getDataNonConst(), qr = qRef->getDataNonConst();
    for (int i = 0; i < m; ++i) {
      double s = bv[C[i]], sr = bRef[C[i]];
      for (int a = 0; a < e; ++a) s -= ACE[static_cast<size_t>(a) * m + i] * Kb_[a], sr -= ACE[static_cast<size_t>(a) * m + i] * KbRef[a];
      qv[i] = s, qr[i] = sr;
    }
  }
  rc.b = q;
  rc.bReference = qRef;
}

std::vector<double> ContactRowReduction::restrict(const Vector& x) const {
  const auto full = gatherColumns(x, replicated_, *toReplicated_)[0];
  std::vector<double> z(contactRows_.size() + reduced_.e.size(), 0.0);
  for (size_t i = 0; i < contactRows_.size(); ++i) z[i] = full[contactRows_[i]];
  return z;
}

void ContactRowReduction::expand(const std::vector<double>& z, Vector& x) const {
  const size_t m = contactRows_.size(), e = freeRows_.size();
  std::vector<double> full(map_->getGlobalNumElements(), 0.0);
  for (size_t i = 0; i < m; ++i) full[contactRows_[i]] = z[i];
  // x_E = K b_E - Z (x_C; alpha)
  for (size_t a = 0; a < e; ++a) {
    double s = Kb_[a];
    for (size_t c = 0; c < z.size(); ++c) s -= Z_[c * e + a] * z[c];
    full[freeRows_[a]] = s;
  }
  auto xv = x.getDataNonConst();
  for (size_t l = 0; l < xv.size(); ++l) xv[l] = full[map_->getGlobalElement(static_cast<LO>(l))];
}

}  // namespace Friction
}  // namespace Tribos
