#include "Tribos_ConjugateProjector.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>

#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

namespace {

// C += A'B over this rank's rows for row-sparse A and B (n x n, column-major).
template <class Rows>
void addTransposeProduct(const Rows& A, const Rows& B, int n, std::vector<double>& C) {
  for (size_t i = 0; i + 1 < A.ptr.size(); ++i)
    for (int a = A.ptr[i]; a < A.ptr[i + 1]; ++a)
      for (int b = B.ptr[i]; b < B.ptr[i + 1]; ++b)
        C[static_cast<size_t>(B.col[b]) * n + A.col[a]] += A.val[a] * B.val[b];
}

std::vector<double> sumOverRanks(std::vector<double> mine, const Comm& comm) {
  std::vector<double> all(mine.size(), 0.0);
  if (!mine.empty()) Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
  return all;
}

}  // namespace

void ConjugateProjector::Rows::add(const MultiVector& M, int first,
                                   std::vector<std::vector<std::pair<int, double>>>& pending) const {
  for (size_t j = 0; j < M.getNumVectors(); ++j) {
    const auto col = M.getData(j);
    for (size_t i = 0; i < pending.size(); ++i)
      if (col[i] != 0.0) pending[i].emplace_back(first + static_cast<int>(j), col[i]);
  }
}

void ConjugateProjector::Rows::finish(std::vector<std::vector<std::pair<int, double>>>& pending) {
  for (auto& row : pending) {
    for (const auto& [j, v] : row) col.push_back(j), val.push_back(v);
    ptr.push_back(static_cast<int>(col.size()));
    std::vector<std::pair<int, double>>().swap(row);
  }
}

std::vector<double> ConjugateProjector::Rows::transposeTimes(const Vector& x, int columns, const Comm& comm) const {
  std::vector<double> y(static_cast<size_t>(columns), 0.0);
  const auto v = x.getData();
  for (size_t i = 0; i + 1 < ptr.size(); ++i)
    for (int k = ptr[i]; k < ptr[i + 1]; ++k) y[col[k]] += val[k] * v[i];
  return sumOverRanks(std::move(y), comm);
}

void ConjugateProjector::Rows::subtractTimes(const std::vector<double>& c, Vector& y) const {
  auto v = y.getDataNonConst();
  for (size_t i = 0; i + 1 < ptr.size(); ++i) {
    double s = 0;
    for (int k = ptr[i]; k < ptr[i + 1]; ++k) s += val[k] * c[col[k]];
    v[i] -= s;
  }
}

bool ConjugateProjector::applies(const FetiProblem& problem) {
  if (!problem.hasContact() || problem.kernelOffsets().back() > 0) return false;
  const auto& eq = problem.isEqualityRow();
  const double mine = std::count(eq.begin(), eq.end(), 1) > 0 ? 1.0 : 0.0;
  double any = 0;
  Teuchos::reduceAll(*problem.comm(), Teuchos::REDUCE_MAX, mine, Teuchos::outArg(any));
  return any > 0 && 6 * problem.numSubdomains() <= kMaxColumns;
}

ConjugateProjector::ConjugateProjector(RCP<const FetiProblem> problem, RCP<const DualOperator> F)
    : problem_(problem), F_(F) {
  static const auto timer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::conjugate projector setup");
  Teuchos::TimeMonitor time(*timer);
  const FetiProblem& p = *problem;
  columns_ = 6 * p.numSubdomains();
  // R: the six rigid motions of each subdomain (columns 6 s .. 6 s + 5) on
  // its own dofs; U = B_E R, the rows that are not equality rows cleared;
  // FU. In blocks of kBlock columns, kept by row (their nonzeros only).
  constexpr int kBlock = 48;
  const auto& eq = p.isEqualityRow();
  std::vector<std::vector<std::pair<int, double>>> pendingU(eq.size()), pendingFU(eq.size());
  for (int first = 0; first < columns_; first += kBlock) {
    const int nb = std::min(kBlock, columns_ - first);
    MultiVector R(p.primalMap(), static_cast<size_t>(nb));
    size_t offset = 0;
    for (int k = 0; k < p.numLocalSubdomains(); ++k) {
      const auto& sys = p.subdomain(k);
      const size_t n = static_cast<size_t>(sys.numDofs());
      if (6 * sys.id + 5 >= first && 6 * sys.id < first + nb) {
        const std::vector<double> modes = Fem::rigidBodyModes(sys.coords);
        for (int j = 0; j < 6; ++j) {
          const int c = 6 * sys.id + j - first;
          if (c < 0 || c >= nb) continue;
          auto col = R.getDataNonConst(static_cast<size_t>(c));
          for (size_t i = 0; i < n; ++i) col[offset + i] = modes[j * n + i];
        }
      }
      offset += n;
    }
    MultiVector U(p.dualMap(), static_cast<size_t>(nb)), FU(p.dualMap(), static_cast<size_t>(nb));
    p.B()->apply(R, U);
    for (int j = 0; j < nb; ++j) {
      auto col = U.getDataNonConst(static_cast<size_t>(j));
      for (size_t i = 0; i < eq.size(); ++i)
        if (!eq[i]) col[i] = 0.0;
    }
    F->apply(U, FU);
    U_.add(U, first, pendingU);
    FU_.add(FU, first, pendingFU);
  }
  U_.finish(pendingU);
  FU_.finish(pendingFU);
  // The independent combinations of U's columns: the eigenvectors of U'U
  // above round-off of its largest eigenvalue (U'U has the geometry's
  // scale; U'FU's spans 1 / (c m) to the elastic h / E).
  std::vector<double> UtU(static_cast<size_t>(columns_) * columns_, 0.0);
  addTransposeProduct(U_, U_, columns_, UtU);
  UtU = sumOverRanks(std::move(UtU), *p.comm());
  const int n = columns_;
  std::vector<double> w(static_cast<size_t>(n));
  int info = 0, lwork = -1;
  double query = 0;
  Teuchos::LAPACK<int, double> lapack;
  lapack.SYEV('V', 'L', n, UtU.data(), n, w.data(), &query, lwork, &info);
  lwork = static_cast<int>(query);
  std::vector<double> work(static_cast<size_t>(std::max(lwork, 1)));
  lapack.SYEV('V', 'L', n, UtU.data(), n, w.data(), work.data(), lwork, &info);
  TRIBOS_REQUIRE(info == 0, "ConjugateProjector: the eigen-decomposition of U'U failed (LAPACK info " << info << ")");
  const double largest = w.empty() ? 0.0 : w.back();
  for (int j = 0; j < n; ++j)
    if (w[j] > 1e-10 * largest) {
      inverseEigen_.push_back(1 / w[j]);
      V_.insert(V_.end(), UtU.begin() + static_cast<size_t>(j) * n, UtU.begin() + static_cast<size_t>(j + 1) * n);
    }
  rank_ = static_cast<int>(V_.size() / std::max(n, 1));
  // V'U'FU V, r x r.
  std::vector<double> UtFU(static_cast<size_t>(n) * n, 0.0);
  addTransposeProduct(U_, FU_, n, UtFU);
  UtFU = sumOverRanks(std::move(UtFU), *p.comm());
  std::vector<double> T(static_cast<size_t>(n) * rank_, 0.0), reduced(static_cast<size_t>(rank_) * rank_, 0.0);
  Teuchos::BLAS<int, double> blas;
  if (rank_ > 0) {
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::NO_TRANS, n, rank_, n, 1.0, UtFU.data(), n, V_.data(), n, 0.0, T.data(), n);
    blas.GEMM(Teuchos::TRANS, Teuchos::NO_TRANS, rank_, rank_, n, 1.0, V_.data(), n, T.data(), n, 0.0, reduced.data(),
              rank_);
  }
  TRIBOS_REQUIRE(factor_.tryFactor(reduced, rank_),
                 "ConjugateProjector: U'FU is singular on the independent rigid-motion jumps (pivot ratio "
                     << factor_.pivotRatio() << ")");
}

std::vector<double> ConjugateProjector::coefficients(const Vector& x) const {
  const int n = columns_;
  std::vector<double> c(static_cast<size_t>(n), 0.0);
  if (rank_ == 0) return c;
  const std::vector<double> Utx = U_.transposeTimes(x, n, *problem_->comm());
  std::vector<double> s(static_cast<size_t>(rank_), 0.0);
  Teuchos::BLAS<int, double> blas;
  blas.GEMV(Teuchos::TRANS, n, rank_, 1.0, V_.data(), n, Utx.data(), 1, 0.0, s.data(), 1);
  factor_.solve(s);
  blas.GEMV(Teuchos::NO_TRANS, n, rank_, 1.0, V_.data(), n, s.data(), 1, 0.0, c.data(), 1);
  return c;
}

void ConjugateProjector::applyQ(const Vector& x, Vector& y) const {
  const int n = columns_;
  std::vector<double> c(static_cast<size_t>(n), 0.0);
  y.assign(x);
  if (rank_ == 0) return;
  const std::vector<double> Utx = U_.transposeTimes(x, n, *problem_->comm());
  std::vector<double> s(static_cast<size_t>(rank_), 0.0);
  Teuchos::BLAS<int, double> blas;
  blas.GEMV(Teuchos::TRANS, n, rank_, 1.0, V_.data(), n, Utx.data(), 1, 0.0, s.data(), 1);
  for (int j = 0; j < rank_; ++j) s[j] *= inverseEigen_[j];
  blas.GEMV(Teuchos::NO_TRANS, n, rank_, 1.0, V_.data(), n, s.data(), 1, 0.0, c.data(), 1);
  U_.subtractTimes(c, y);
}

void ConjugateProjector::applyP(const Vector& x, const Vector& Fx, Vector& y) const {
  const std::vector<double> c = coefficients(Fx);
  y.assign(x);
  U_.subtractTimes(c, y);
}

void ConjugateProjector::applyHessian(const Vector& x, Vector& y) const {
  Vector Qx(x.getMap()), FPQx(x.getMap());
  applyQ(x, Qx);
  F_->apply(Qx, FPQx);
  FU_.subtractTimes(coefficients(FPQx), FPQx);  // F P z = F z - FU (U'FU)^+ U'F z
  applyQ(FPQx, y);
}

void ConjugateProjector::applyRightHandSide(const Vector& x, Vector& y) const {
  Vector Ptx(x, Teuchos::Copy);
  FU_.subtractTimes(coefficients(x), Ptx);
  applyQ(Ptx, y);
}

void ConjugateProjector::applyBack(const Vector& x, Vector& y) const {
  Vector Qx(x.getMap()), FQx(x.getMap());
  applyQ(x, Qx);
  F_->apply(Qx, FQx);
  applyP(Qx, FQx, y);
}

void ConjugateProjector::particular(const Vector& h, Vector& lambdaU) const {
  lambdaU.putScalar(0.0);
  U_.subtractTimes(coefficients(h), lambdaU);
  lambdaU.scale(-1.0);
}

}  // namespace Feti
}  // namespace Tribos
