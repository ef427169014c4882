#include "Tribos_LocalSolver.hpp"

#include <Amesos2.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>

#include <Tacho_Driver.hpp>
#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <memory>

#include "Tribos_DenseBlas.hpp"
#include "Tribos_DenseCholesky.hpp"
#include "Tribos_CholmodStatus.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {

void LocalSolver::inverseBlock(const std::vector<int>& dofs, std::vector<double>& Z) const {
  const int n = size(), nb = static_cast<int>(dofs.size());
  Z.resize(static_cast<size_t>(nb) * nb);
  const int chunk = 64;  // unit right-hand sides per solve
  std::vector<double> E, X;
  for (int j0 = 0; j0 < nb; j0 += chunk) {
    const int m = std::min(chunk, nb - j0);
    E.assign(static_cast<size_t>(n) * m, 0.0);
    X.resize(E.size());
    for (int j = 0; j < m; ++j) E[static_cast<size_t>(j) * n + dofs[j0 + j]] = 1.0;
    solve(E.data(), X.data(), m);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < nb; ++i) Z[static_cast<size_t>(j0 + j) * nb + i] = X[static_cast<size_t>(j) * n + dofs[i]];
  }
}

void LocalSolver::solveFactor(double*, bool) const {
  throw Error(name() + ": no Cholesky factor to solve with (use CHOLMOD)");
}

void LocalSolver::trailingFactor(std::vector<double>&) const {
  throw Error(name() + ": no Cholesky factor to read a trailing block from (use CHOLMOD)");
}

double LocalSolver::pivotRatio() const { throw Error(name() + ": no Cholesky factor (use CHOLMOD)"); }

namespace {

// A CHOLMOD view (no copy) of a symmetric CSR matrix: it is its own CSC, and
// stype = 1 makes CHOLMOD read the upper triangle. Pattern only when !values.
cholmod_sparse cholmodView(const LocalCsr& A, bool values) {
  cholmod_sparse S;
  std::memset(&S, 0, sizeof S);
  S.nrow = S.ncol = A.rows;
  S.nzmax = A.val.size();
  S.p = const_cast<int*>(A.rowptr.data());
  S.i = const_cast<int*>(A.col.data());
  S.x = values ? const_cast<double*>(A.val.data()) : nullptr;
  S.stype = 1;
  S.itype = CHOLMOD_INT;
  S.xtype = values ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = 1;
  S.packed = 1;
  return S;
}

// A small matrix with rows ordered last, factored densely by LAPACK in the
// order (other rows, last rows): the trailing block of L is then the Cholesky
// factor of the Schur complement, as in CHOLMOD's constrained ordering.
// Subdomains of a few hundred dofs have nearly every dof on their boundary,
// so the sparse factor is nearly dense and CHOLMOD's supernodal bookkeeping
// costs more than its flops (4 x 4 x 4 cubes, 375 dofs: 1.5 ms against 4 ms
// for the factor and the inverse block).
class DenseBoundaryLast {
 public:
  DenseBoundaryLast(const LocalCsr& A, const std::vector<int>& last) : n_(A.rows), nb_(static_cast<int>(last.size())) {
    std::vector<char> isLast(n_, 0);
    for (int i : last) isLast[i] = 1;
    for (int i = 0; i < n_; ++i)
      if (!isLast[i]) perm_.push_back(i);
    perm_.insert(perm_.end(), last.begin(), last.end());  // `last` in the caller's order
    std::vector<int> position(n_);
    for (int k = 0; k < n_; ++k) position[perm_[k]] = k;
    std::vector<double> D(static_cast<size_t>(n_) * n_, 0.0);
    for (int i = 0; i < n_; ++i)
      for (int a = A.rowptr[i]; a < A.rowptr[i + 1]; ++a)
        D[static_cast<size_t>(position[A.col[a]]) * n_ + position[i]] += A.val[a];  // duplicates add up
    DenseCholesky chol;
    chol.tryFactor(std::move(D), n_);
    // As CHOLMOD: refused only when the factorization breaks down.
    TRIBOS_REQUIRE(chol.positiveDefinite(), "dense Cholesky: the matrix is not positive definite");
    pivotRatio_ = chol.pivotRatio();
    // Kept packed: half of n^2, near what a sparse factor of this size holds.
    Lp_ = Blas::packLower<double>(n_, chol.factor());
  }
  void solve(const double* b, double* x, int nrhs) const {
    std::vector<double> y(static_cast<size_t>(n_) * nrhs);
    for (int j = 0; j < nrhs; ++j)
      for (int k = 0; k < n_; ++k) y[static_cast<size_t>(j) * n_ + k] = b[static_cast<size_t>(j) * n_ + perm_[k]];
    Blas::packedCholeskySolve(n_, nrhs, Lp_.data(), y.data());
    for (int j = 0; j < nrhs; ++j)
      for (int k = 0; k < n_; ++k) x[static_cast<size_t>(j) * n_ + perm_[k]] = y[static_cast<size_t>(j) * n_ + k];
  }
  // x <- L^-1 P x, or P' L^-T x.
  void solveFactor(double* x, bool transpose) const {
    std::vector<double> y(n_);
    if (!transpose) {
      for (int k = 0; k < n_; ++k) y[k] = x[perm_[k]];
      Blas::packedTriangularSolve(n_, false, Lp_.data(), y.data());
      std::copy(y.begin(), y.end(), x);
    } else {
      y.assign(x, x + n_);
      Blas::packedTriangularSolve(n_, true, Lp_.data(), y.data());
      for (int k = 0; k < n_; ++k) x[perm_[k]] = y[k];
    }
  }
  // The trailing nb x nb block of L, column-major, zero above the diagonal.
  void trailingFactor(std::vector<double>& Z) const {
    const int first = n_ - nb_;
    Z.assign(static_cast<size_t>(nb_) * nb_, 0.0);
    for (int j = first; j < n_; ++j) {
      // Column j of the packed lower triangle starts at j n - j (j - 1) / 2.
      const double* col = Lp_.data() + static_cast<size_t>(j) * n_ - static_cast<size_t>(j) * (j - 1) / 2;
      std::copy(col, col + (n_ - j), Z.begin() + static_cast<size_t>(j - first) * nb_ + (j - first));
    }
  }
  double pivotRatio() const { return pivotRatio_; }
  double memoryMb() const { return static_cast<double>(Lp_.size()) * 8.0 / 1048576.0; }

 private:
  int n_, nb_;
  std::vector<int> perm_;   // position k of the factor holds row perm_[k]
  std::vector<double> Lp_;  // L, packed lower triangle
  double pivotRatio_ = 1;
};

class CholmodSolver : public LocalSolver {
 public:
  CholmodSolver() {
    cholmod_start(&common_);
    common_.print = 0;
    // Simplicial factors (small matrices) are kept as LL', not LDL', so that
    // solveFactor's L is the Cholesky factor whatever the factor's kind.
    common_.final_ll = 1;
  }
  ~CholmodSolver() override {
    for (cholmod_dense** d : {&X_, &Y_, &E_})
      if (*d) cholmod_free_dense(d, &common_);
    if (L_) cholmod_free_factor(&L_, &common_);
    cholmod_finish(&common_);
  }
  void factor(const LocalCsr& A) override {
    TRIBOS_REQUIRE(A.rows == A.cols, "CHOLMOD: matrix is not square (" << A.rows << " x " << A.cols << ")");
    n_ = A.rows;
    last_.clear();
    dense_.reset();
    cholmod_sparse S = cholmodView(A, true);
    if (L_) cholmod_free_factor(&L_, &common_);
    L_ = cholmod_analyze(&S, &common_);
    requireCholmodOk(common_, "analysis");
    TRIBOS_REQUIRE(L_ != nullptr, "CHOLMOD: analysis failed");
    numericFactor(S);
  }
  // The rows of `last` are ordered after all others by constrained minimum
  // degree (CAMD; on subdomain matrices it fills less than METIS on the other
  // rows followed by `last`). The trailing block of L is then the Cholesky
  // factor of the Schur complement S_ll = A_ll - A_lo A_oo^-1 A_ol, and
  // (A^-1)_ll = S_ll^-1, so inverseBlock(last) costs one dense inversion.
  void factor(const LocalCsr& A, const std::vector<int>& last) override {
    TRIBOS_REQUIRE(A.rows == A.cols, "CHOLMOD: matrix is not square (" << A.rows << " x " << A.cols << ")");
    n_ = A.rows;
    std::vector<int> set(n_, 0), perm(n_);
    for (int i : last) {
      TRIBOS_REQUIRE(i >= 0 && i < n_ && !set[i], "CHOLMOD: row " << i << " listed twice or out of range");
      set[i] = 1;
    }
    if (n_ <= kDenseFactorRows) {
      if (L_) cholmod_free_factor(&L_, &common_);
      dense_ = std::make_unique<DenseBoundaryLast>(A, last);
      last_ = last;
      return;
    }
    dense_.reset();
    cholmod_sparse S = cholmodView(A, true);
    if (ordering_ == Ordering::OwnOrderingFirst) {
      orderOthersAlone(A, set, perm);
    } else {
      cholmod_camd(&S, nullptr, 0, set.data(), perm.data(), &common_);
      requireCholmodOk(common_, "constrained ordering");
    }
    for (auto it = perm.end() - last.size(); it != perm.end(); ++it)
      TRIBOS_REQUIRE(set[*it], "CHOLMOD: the constrained ordering did not put the given rows last");
    std::copy(last.begin(), last.end(), perm.end() - last.size());  // `last` in the caller's order
    if (L_) cholmod_free_factor(&L_, &common_);
    // The given ordering exactly: a postorder of the elimination tree could
    // move rows of `last` forward.
    const int nmethods = common_.nmethods, ordering = common_.method[0].ordering, postorder = common_.postorder;
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    common_.postorder = 0;
    L_ = cholmod_analyze_p(&S, perm.data(), nullptr, 0, &common_);
    common_.nmethods = nmethods;
    common_.method[0].ordering = ordering;
    common_.postorder = postorder;
    requireCholmodOk(common_, "analysis");
    TRIBOS_REQUIRE(L_ != nullptr, "CHOLMOD: analysis failed");
    TRIBOS_REQUIRE(std::equal(perm.begin(), perm.end(), static_cast<const int*>(L_->Perm)),
                   "CHOLMOD did not keep the given ordering");
    numericFactor(S);
    last_ = last;
  }
  void refactor(const LocalCsr& A) override {
    if (dense_) return factor(A, std::vector<int>(last_));
    if (!L_ || A.rows != n_) return factor(A);
    cholmod_sparse S = cholmodView(A, true);
    numericFactor(S);
  }
  void inverseBlock(const std::vector<int>& dofs, std::vector<double>& Z) const override {
    if (dofs != last_ || dofs.empty()) return LocalSolver::inverseBlock(dofs, Z);
    trailingFactor(Z);
    const int nb = static_cast<int>(dofs.size());
    const int info = Blas::choleskyInverse(nb, Z.data());
    TRIBOS_REQUIRE(info == 0, "CHOLMOD: inverse of the trailing Cholesky block failed (LAPACK info " << info << ")");
  }
  void solveFactor(double* x, bool transpose) const override {
    if (dense_) return dense_->solveFactor(x, transpose);
    // P then L^-1, or L^-T then P': two calls of cholmod_solve2.
    const int first = transpose ? CHOLMOD_Lt : CHOLMOD_P, second = transpose ? CHOLMOD_Pt : CHOLMOD_L;
    solveSystem(first, x, x, 1);
    solveSystem(second, x, x, 1);
  }
  double pivotRatio() const override {
    if (dense_) return dense_->pivotRatio();
    if (!L_ || n_ == 0) return 1.0;
    return cholmod_rcond(L_, &common_);
  }
  void solve(const double* b, double* x, int nrhs) const override {
    if (dense_) return dense_->solve(b, x, nrhs);
    solveSystem(CHOLMOD_A, b, x, nrhs);
  }
  std::string name() const override { return "CHOLMOD"; }
  void trailingFactor(std::vector<double>& Z) const override {
    if (dense_)
      dense_->trailingFactor(Z);
    else
      sparseTrailingFactor(Z);
  }

 private:
  void solveSystem(int system, const double* b, double* x, int nrhs) const {
    cholmod_dense B;
    std::memset(&B, 0, sizeof B);
    B.nrow = n_;
    B.ncol = nrhs;
    B.nzmax = static_cast<size_t>(n_) * nrhs;
    B.d = n_;
    B.x = const_cast<double*>(b);
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    // cholmod_solve2 keeps its result and workspaces between calls: the
    // F = B K+ B' application solves once per subdomain, many times.
    const int ok = cholmod_solve2(system, L_, &B, nullptr, &X_, nullptr, &Y_, &E_, &common_);
    requireCholmodOk(common_, "solve");
    TRIBOS_REQUIRE(ok && X_ != nullptr, "CHOLMOD: solve failed");
    std::copy(static_cast<double*>(X_->x), static_cast<double*>(X_->x) + static_cast<size_t>(n_) * nrhs, x);
  }
  void numericFactor(cholmod_sparse& S) {
    cholmod_factorize(&S, L_, &common_);
    requireCholmodOk(common_, "factorization", L_);
  }
  // perm: the rows outside `last` (set[i] == 0) in the order CHOLMOD's
  // analysis of their submatrix chooses, then the rows of `last`.
  void orderOthersAlone(const LocalCsr& A, const std::vector<int>& set, std::vector<int>& perm) {
    std::vector<int> others;
    for (int i = 0; i < n_; ++i)
      if (!set[i]) others.push_back(i);
    const LocalCsr B = A.principalSubmatrix(others);
    perm.clear();
    if (B.rows > 0) {
      cholmod_sparse S = cholmodView(B, false);
      cholmod_factor* L = cholmod_analyze(&S, &common_);
      requireCholmodOk(common_, "analysis");
      TRIBOS_REQUIRE(L != nullptr, "CHOLMOD: analysis failed");
      const int* p = static_cast<const int*>(L->Perm);
      for (int k = 0; k < B.rows; ++k) perm.push_back(others[p[k]]);
      cholmod_free_factor(&L, &common_);
    }
    for (int i = 0; i < n_; ++i)
      if (set[i]) perm.push_back(i);
  }
  // The last |last_| rows and columns of the sparse L into Z, dense
  // column-major (lower triangle; the strict upper triangle is zero).
  void sparseTrailingFactor(std::vector<double>& Z) const {
    const int nb = static_cast<int>(last_.size()), first = n_ - nb;
    Z.assign(static_cast<size_t>(nb) * nb, 0.0);
    if (L_->is_super) {
      // Supernode s holds columns super[s]..super[s+1]-1 as a dense
      // nsrow x nscol block at x + px[s], its row indices at s + pi[s].
      const int* super = static_cast<const int*>(L_->super);
      const int* pi = static_cast<const int*>(L_->pi);
      const int* px = static_cast<const int*>(L_->px);
      const int* rows = static_cast<const int*>(L_->s);
      const double* x = static_cast<const double*>(L_->x);
      for (size_t s = 0; s < L_->nsuper; ++s) {
        if (super[s + 1] <= first) continue;
        const int nsrow = pi[s + 1] - pi[s];
        for (int j = std::max(super[s], first); j < super[s + 1]; ++j)
          for (int r = j - super[s]; r < nsrow; ++r)
            Z[static_cast<size_t>(j - first) * nb + (rows[pi[s] + r] - first)] =
                x[px[s] + static_cast<size_t>(j - super[s]) * nsrow + r];
      }
      return;
    }
    // Simplicial (small matrices): an LL' copy, since the factor may be LDL'.
    cholmod_factor* L = cholmod_copy_factor(L_, &common_);
    cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, L, &common_);
    requireCholmodOk(common_, "factor conversion");
    const int* Lp = static_cast<const int*>(L->p);
    const int* Li = static_cast<const int*>(L->i);
    const double* Lx = static_cast<const double*>(L->x);
    for (int j = first; j < n_; ++j)
      for (int k = Lp[j]; k < Lp[j + 1]; ++k) Z[static_cast<size_t>(j - first) * nb + (Li[k] - first)] = Lx[k];
    cholmod_free_factor(&L, &common_);
  }

 public:
  int size() const override { return n_; }
  double factorMemoryMb() const override {
    if (dense_) return dense_->memoryMb();
    if (!L_) return 0;
    // Supernodal factors store xsize values; simplicial ones nzmax.
    const double entries = L_->is_super ? static_cast<double>(L_->xsize) : static_cast<double>(L_->nzmax);
    return entries * 8.0 / 1048576.0;
  }

 private:
  mutable cholmod_common common_;
  cholmod_factor* L_ = nullptr;
  std::vector<int> last_;  // rows ordered last by factor(A, last)
  std::unique_ptr<DenseBoundaryLast> dense_;  // instead of L_ for small factor(A, last)
  mutable cholmod_dense *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;  // reused by solve
  int n_ = 0;
};

// Amesos2 on a serial communicator: the matrix is wrapped once in Tpetra.
class Amesos2Solver : public LocalSolver {
 public:
  explicit Amesos2Solver(std::string solverName) : solverName_(std::move(solverName)) {}
  void factor(const LocalCsr& A) override {
    n_ = A.rows;
    auto comm = rcp(new Teuchos::SerialComm<int>());
    map_ = rcp(new Map(static_cast<Tpetra::global_size_t>(n_), 0, comm));
    Teuchos::ArrayRCP<size_t> rowptr(A.rowptr.size());
    Teuchos::ArrayRCP<LO> col(A.col.size());
    Teuchos::ArrayRCP<SC> val(A.val.size());
    std::copy(A.rowptr.begin(), A.rowptr.end(), rowptr.begin());
    std::copy(A.col.begin(), A.col.end(), col.begin());
    std::copy(A.val.begin(), A.val.end(), val.begin());
    K_ = rcp(new CrsMatrix(map_, map_, rowptr, col, val));
    K_->expertStaticFillComplete(map_, map_);
    X_ = rcp(new MultiVector(map_, 1));
    B_ = rcp(new MultiVector(map_, 1));
    solver_ = Amesos2::create<CrsMatrix, MultiVector>(solverName_, K_, X_, B_);
    solver_->symbolicFactorization().numericFactorization();
  }
  void solve(const double* b, double* x, int nrhs) const override {
    if (static_cast<int>(B_->getNumVectors()) != nrhs) {
      X_ = rcp(new MultiVector(map_, nrhs));
      B_ = rcp(new MultiVector(map_, nrhs));
    }
    for (int j = 0; j < nrhs; ++j) {
      auto col = B_->getDataNonConst(j);
      std::copy(b + static_cast<size_t>(j) * n_, b + static_cast<size_t>(j + 1) * n_, col.begin());
    }
    solver_->setX(X_);
    solver_->setB(B_);
    solver_->solve();
    for (int j = 0; j < nrhs; ++j) {
      auto col = X_->getData(j);
      std::copy(col.begin(), col.end(), x + static_cast<size_t>(j) * n_);
    }
  }
  std::string name() const override { return solverName_; }
  int size() const override { return n_; }

 private:
  std::string solverName_;
  int n_ = 0;
  RCP<const Map> map_;
  RCP<CrsMatrix> K_;
  mutable RCP<MultiVector> X_, B_;
  RCP<Amesos2::Solver<CrsMatrix, MultiVector>> solver_;
};

// Tacho's supernodal Cholesky called directly. The Amesos2 13.2 adapter
// calls Tacho::Driver::analyze() and factorize() but never initialize(), which
// creates the numeric tools: every matrix of order >= 1024 (Tacho's dense
// "small problem" threshold) then dereferences a null pointer in factorize()
// (see docs/feti.md). Here the driver is used with its documented sequence
// analyze, initialize, factorize, solve.
class TachoSolver : public LocalSolver {
  using Driver = Tacho::Driver<double, Kokkos::Device<Kokkos::Serial, Kokkos::HostSpace>>;

 public:
  ~TachoSolver() override { releaseDriver(); }
  void factor(const LocalCsr& A) override {
    TRIBOS_REQUIRE(A.rows == A.cols, "Tacho: matrix is not square (" << A.rows << " x " << A.cols << ")");
    // A driver of its own for every factorization: Tacho's release() leaves
    // state behind, and a driver analysed and factored again after it does
    // not solve the new matrix (the semismooth* Newton matrices are factored
    // again at every step).
    releaseDriver();
    solver_ = std::make_unique<Driver>();
    n_ = A.rows;
    // The driver keeps views of the graph: they are members.
    ap_ = Driver::size_type_array("ap", A.rowptr.size());
    aj_ = Driver::ordinal_type_array("aj", A.col.size());
    ax_ = Driver::value_type_array("ax", A.val.size());
    std::copy(A.rowptr.begin(), A.rowptr.end(), ap_.data());
    std::copy(A.col.begin(), A.col.end(), aj_.data());
    std::copy(A.val.begin(), A.val.end(), ax_.data());
    // Debian's Tacho is built without METIS, and its fallback GraphTools
    // ordering is the identity (natural ordering: banded fill, ~100x slower on
    // a 10k-dof subdomain). The fill-reducing ordering is taken from CHOLMOD's
    // symbolic analysis instead (AMD/METIS, the same one CHOLMOD factors with).
    Driver::ordinal_type_array perm("perm", n_), peri("peri", n_);
    fillReducingOrdering(A, perm.data());
    for (int i = 0; i < n_; ++i) peri(perm(i)) = i;  // Tacho's (perm, peri) = CHOLMOD's (Perm, its inverse)
    // Below this order Tacho factors a dense copy with LAPACK (O(n^3)), far
    // slower than its sparse path on subdomain matrices of a few hundred dofs.
    solver_->setSmallProblemThresholdsize(64);
    solver_->analyze(n_, ap_, aj_, perm, peri);
    solver_->initialize();
    solver_->factorize(ax_);
  }
  void solve(const double* b, double* x, int nrhs) const override {
    Driver::value_type_matrix B("b", n_, nrhs), X("x", n_, nrhs), T("t", n_, nrhs);
    std::copy(b, b + static_cast<size_t>(n_) * nrhs, B.data());
    TRIBOS_REQUIRE(solver_, "Tacho: solve before factor");
    solver_->solve(X, B, T);
    std::copy(X.data(), X.data() + static_cast<size_t>(n_) * nrhs, x);
  }
  std::string name() const override { return "Tacho"; }

  // CHOLMOD's ordering: row perm[k] of A is row k of the permuted matrix.
  static void fillReducingOrdering(const LocalCsr& A, int* perm) {
    cholmod_common common;
    cholmod_start(&common);
    common.print = 0;
    cholmod_sparse S = cholmodView(A, false);
    cholmod_factor* L = cholmod_analyze(&S, &common);
    requireCholmodOk(common, "analysis (the ordering for Tacho)");
    std::copy(static_cast<const int*>(L->Perm), static_cast<const int*>(L->Perm) + A.rows, perm);
    cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }
  int size() const override { return n_; }

 private:
  void releaseDriver() {
    if (solver_) solver_->release();
    solver_.reset();
  }
  std::unique_ptr<Driver> solver_;
  Driver::size_type_array ap_;
  Driver::ordinal_type_array aj_;
  Driver::value_type_array ax_;
  int n_ = 0;
};

}  // namespace

const LocalSolverRegistry& localSolvers() {
  static const LocalSolverRegistry registry = [] {
    LocalSolverRegistry r("local solver");
    r.add("CHOLMOD", [] { return RCP<LocalSolver>(rcp(new CholmodSolver())); },
          "supernodal Cholesky of SuiteSparse, nested-dissection ordering");
    r.add("KLU2", [] { return RCP<LocalSolver>(rcp(new Amesos2Solver("KLU2"))); }, "Amesos2's sparse LU");
    r.add("Tacho", [] { return RCP<LocalSolver>(rcp(new TachoSolver())); }, "Kokkos' multifrontal Cholesky");
    return r;
  }();
  return registry;
}

std::vector<std::string> localSolverNames() { return localSolvers().names(); }

RCP<LocalSolver> createLocalSolver(const std::string& name) { return localSolvers().create(name); }

}  // namespace Tribos
