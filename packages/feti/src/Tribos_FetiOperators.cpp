#include "Tribos_FetiOperators.hpp"

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <mpi.h>

#include <algorithm>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

namespace {
MPI_Comm rawComm(const Comm& comm) {
  return *dynamic_cast<const Teuchos::MpiComm<int>&>(comm).getRawMpiComm();
}
}  // namespace

DualOperator::DualOperator(RCP<const FetiProblem> problem) : problem_(problem) {
  p_ = rcp(new Vector(problem->primalMap()));
  z_ = rcp(new Vector(problem->primalMap()));
}

void DualOperator::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, SC alpha, SC beta) const {
  static const auto counter = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::F apply");
  Teuchos::TimeMonitor timer(*counter);
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    auto x = X.getVector(j);
    auto y = Y.getVectorNonConst(j);
    problem_->B()->apply(*x, *p_, Teuchos::TRANS);  // B' x
    problem_->applyDualKplus(*p_, *z_);             // K+ B' x
    problem_->B()->apply(*z_, *y, Teuchos::NO_TRANS, alpha, beta);
    ++n_A_;
  }
}

void DenseCholesky::factor(std::vector<double> A, int n, const char* what) {
  n_ = n;
  L_ = std::move(A);
  if (n == 0) return;
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.POTRF('L', n, L_.data(), n, &info);
  TRIBOS_REQUIRE(info == 0, what << " is singular (Cholesky pivot " << info << " of " << n
                                 << "): the constraints do not fix every rigid-body mode of the subdomains");
}

void DenseCholesky::solve(std::vector<double>& x) const {
  if (n_ == 0) return;
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.POTRS('L', n_, 1, L_.data(), n_, x.data(), n_, &info);
}

void DenseCholesky::solveLower(std::vector<double>& x) const {
  if (n_ == 0) return;
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.TRTRS('L', 'N', 'N', n_, 1, L_.data(), n_, x.data(), n_, &info);
}

void DenseCholesky::solveUpperT(std::vector<double>& x) const {
  if (n_ == 0) return;
  Teuchos::LAPACK<int, double> lapack;
  int info = 0;
  lapack.TRTRS('L', 'T', 'N', n_, 1, L_.data(), n_, x.data(), n_, &info);
}

CoarseSpace::CoarseSpace(RCP<const FetiProblem> problem) : problem_(problem) {
  n_ = problem->kernelOffsets().back();
  const CrsMatrix& B = *problem->B();
  // R rows at every primal dof that this rank's B rows touch.
  MultiVector Rmv(problem->primalMap(), 6);
  {
    size_t offset = 0;
    for (int k = 0; k < problem->numLocalSubdomains(); ++k) {
      const auto& sys = problem->subdomain(k);
      const int n = sys.numDofs();
      for (int j = 0; j < Feti::FetiProblem::kernelDim(sys); ++j) {
        auto col = Rmv.getDataNonConst(j);
        for (int i = 0; i < n; ++i) col[offset + i] = sys.R[static_cast<size_t>(j) * n + i];
      }
      offset += n;
    }
  }
  auto colMap = B.getColMap();
  MultiVector Rcol(colMap, 6);
  Rcol.doImport(Rmv, Import(problem->primalMap(), colMap), Tpetra::INSERT);
  std::vector<Teuchos::ArrayRCP<const SC>> Rc(6);
  for (int j = 0; j < 6; ++j) Rc[j] = Rcol.getData(j);
  const auto& offsets = problem->primalOffsets();
  rowptr_.push_back(0);
  for (LO i = 0; i < static_cast<LO>(B.getNodeNumRows()); ++i) {
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    B.getLocalRowView(i, cols, vals);
    std::vector<std::pair<int, double>> entries;
    for (size_t k = 0; k < cols.extent(0); ++k) {
      const GO gid = colMap->getGlobalElement(cols(k));
      const int s = static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), gid) - offsets.begin()) - 1;
      const auto& ko = problem->kernelOffsets();
      for (int j = 0; j < ko[s + 1] - ko[s]; ++j) entries.emplace_back(ko[s] + j, vals(k) * Rc[j][cols(k)]);
    }
    std::sort(entries.begin(), entries.end());
    for (size_t k = 0; k < entries.size(); ++k) {
      if (k > 0 && entries[k].first == entries[k - 1].first) {
        val_.back() += entries[k].second;
        continue;
      }
      col_.push_back(entries[k].first);
      val_.push_back(entries[k].second);
    }
    rowptr_.push_back(static_cast<int>(col_.size()));
  }
  GGt_.factor(gramian(nullptr), n_, "GG'");
  GEGEt_.factor(gramian(&problem->isEqualityRow()), n_, "G_E G_E'");
}

std::vector<double> CoarseSpace::gramian(const std::vector<char>* rows) const {
  std::vector<double> A(static_cast<size_t>(n_) * n_, 0.0);
  for (size_t i = 0; i + 1 < rowptr_.size(); ++i) {
    if (rows && !(*rows)[i]) continue;
    for (int a = rowptr_[i]; a < rowptr_[i + 1]; ++a)
      for (int b = rowptr_[i]; b < rowptr_[i + 1]; ++b)
        A[static_cast<size_t>(col_[a]) * n_ + col_[b]] += val_[a] * val_[b];
  }
  MPI_Allreduce(MPI_IN_PLACE, A.data(), static_cast<int>(A.size()), MPI_DOUBLE, MPI_SUM, rawComm(*problem_->comm()));
  return A;
}

void CoarseSpace::applyG(const Vector& x, std::vector<double>& y, const std::vector<char>* rows) const {
  y.assign(n_, 0.0);
  auto xv = x.getData();
  for (size_t i = 0; i + 1 < rowptr_.size(); ++i) {
    if (rows && !(*rows)[i]) continue;
    for (int a = rowptr_[i]; a < rowptr_[i + 1]; ++a) y[col_[a]] += val_[a] * xv[i];
  }
  MPI_Allreduce(MPI_IN_PLACE, y.data(), n_, MPI_DOUBLE, MPI_SUM, rawComm(*problem_->comm()));
}

void CoarseSpace::applyGt(const std::vector<double>& y, Vector& x, const std::vector<char>* rows) const {
  auto xv = x.getDataNonConst();
  for (size_t i = 0; i + 1 < rowptr_.size(); ++i) {
    double s = 0;
    if (!rows || (*rows)[i])
      for (int a = rowptr_[i]; a < rowptr_[i + 1]; ++a) s += val_[a] * y[col_[a]];
    xv[i] = s;
  }
}

void CoarseSpace::project(const Vector& x, Vector& Px) const {
  std::vector<double> y;
  applyG(x, y);
  GGt_.solve(y);
  applyGt(y, Px);
  Px.update(1.0, x, -1.0);
}

void CoarseSpace::applyOrthonormal(const Vector& x, std::vector<double>& y) const {
  applyG(x, y);
  GGt_.solveLower(y);
}

void CoarseSpace::applyOrthonormalTranspose(const std::vector<double>& y, Vector& x) const {
  std::vector<double> z(y);
  GGt_.solveUpperT(z);
  applyGt(z, x);
}

void CoarseSpace::particularSolution(const std::vector<double>& e, Vector& lambdaTilde) const {
  std::vector<double> y(e);
  GEGEt_.solve(y);
  applyGt(y, lambdaTilde, &problem_->isEqualityRow());
}

std::vector<double> CoarseSpace::amplitudes(const Vector& r) const {
  std::vector<double> y;
  applyG(r, y, &problem_->isEqualityRow());
  GEGEt_.solve(y);
  return y;
}

}  // namespace Feti
}  // namespace Tribos
