#include "Tribos_LocalSolver.hpp"

#include <Amesos2.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>

#include <Tacho_Driver.hpp>
#include <cholmod.h>

#include <algorithm>
#include <cstring>

#include "Tribos_Error.hpp"

namespace Tribos {

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

class CholmodSolver : public LocalSolver {
 public:
  CholmodSolver() {
    cholmod_start(&common_);
    common_.print = 0;
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
    cholmod_sparse S = cholmodView(A, true);
    if (L_) cholmod_free_factor(&L_, &common_);
    L_ = cholmod_analyze(&S, &common_);
    TRIBOS_REQUIRE(L_ != nullptr, "CHOLMOD analysis failed (status " << common_.status << ")");
    cholmod_factorize(&S, L_, &common_);
    TRIBOS_REQUIRE(common_.status == CHOLMOD_OK && L_->minor == L_->n,
                   "CHOLMOD: matrix of size " << n_ << " is not positive definite (pivot " << L_->minor << ")");
  }
  void solve(const double* b, double* x, int nrhs) const override {
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
    const int ok = cholmod_solve2(CHOLMOD_A, L_, &B, nullptr, &X_, nullptr, &Y_, &E_, &common_);
    TRIBOS_REQUIRE(ok && X_ != nullptr, "CHOLMOD solve failed");
    std::copy(static_cast<double*>(X_->x), static_cast<double*>(X_->x) + static_cast<size_t>(n_) * nrhs, x);
  }
  std::string name() const override { return "CHOLMOD"; }
  int size() const override { return n_; }
  double factorMemoryMb() const override {
    if (!L_) return 0;
    // Supernodal factors store xsize values; simplicial ones nzmax.
    const double entries = L_->is_super ? static_cast<double>(L_->xsize) : static_cast<double>(L_->nzmax);
    return entries * 8.0 / 1048576.0;
  }

 private:
  mutable cholmod_common common_;
  cholmod_factor* L_ = nullptr;
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
  ~TachoSolver() override {
    if (factored_) solver_.release();
  }
  void factor(const LocalCsr& A) override {
    TRIBOS_REQUIRE(A.rows == A.cols, "Tacho: matrix is not square (" << A.rows << " x " << A.cols << ")");
    if (factored_) solver_.release();
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
    solver_.setSmallProblemThresholdsize(64);
    solver_.analyze(n_, ap_, aj_, perm, peri);
    solver_.initialize();
    solver_.factorize(ax_);
    factored_ = true;
  }
  void solve(const double* b, double* x, int nrhs) const override {
    Driver::value_type_matrix B("b", n_, nrhs), X("x", n_, nrhs), T("t", n_, nrhs);
    std::copy(b, b + static_cast<size_t>(n_) * nrhs, B.data());
    solver_.solve(X, B, T);
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
    TRIBOS_REQUIRE(L != nullptr, "Tacho: ordering by CHOLMOD analysis failed (status " << common.status << ")");
    std::copy(static_cast<const int*>(L->Perm), static_cast<const int*>(L->Perm) + A.rows, perm);
    cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }
  int size() const override { return n_; }

 private:
  mutable Driver solver_;
  Driver::size_type_array ap_;
  Driver::ordinal_type_array aj_;
  Driver::value_type_array ax_;
  int n_ = 0;
  bool factored_ = false;
};

}  // namespace

std::vector<std::string> localSolverNames() { return {"CHOLMOD", "KLU2", "Tacho"}; }

RCP<LocalSolver> createLocalSolver(const std::string& name) {
  if (name == "CHOLMOD") return rcp(new CholmodSolver());
  if (name == "KLU2") return rcp(new Amesos2Solver(name));
  if (name == "Tacho") return rcp(new TachoSolver());
  throw Error("unknown local solver \"" + name + "\"; valid: CHOLMOD, KLU2, Tacho");
}

}  // namespace Tribos
