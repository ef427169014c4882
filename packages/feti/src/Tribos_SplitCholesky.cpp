#include "Tribos_SplitCholesky.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <metis.h>
#include <mpi.h>

#include <algorithm>
#include <numeric>
#include <utility>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_AllGather.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"

namespace Tribos {
namespace Feti {

namespace {

// At least this many row blocks per rank before a split can pay.
constexpr int kMinBlocksPerRank = 8;

// x <- L x or L' x, L lower triangular n x n column-major.
void triangularProduct(const std::vector<double>& L, int n, bool transpose, double* x) {
  if (n == 0) return;
  Teuchos::BLAS<int, double>().TRMV(Teuchos::LOWER_TRI, transpose ? Teuchos::TRANS : Teuchos::NO_TRANS,
                                    Teuchos::NON_UNIT_DIAG, n, L.data(), n, x, 1);
}

}  // namespace

SplitCholesky::SplitCholesky(RCP<const Comm> comm, std::vector<int> blockStart, int maxSeparatorRows)
    : comm_(std::move(comm)), blockStart_(std::move(blockStart)), maxSeparatorRows_(maxSeparatorRows) {
  TRIBOS_REQUIRE(!comm_.is_null(), "SplitCholesky: no communicator");
  TRIBOS_REQUIRE(!blockStart_.empty() && blockStart_.front() == 0 &&
                     std::is_sorted(blockStart_.begin(), blockStart_.end()),
                 "SplitCholesky: row blocks must start at 0 and increase");
}

std::vector<int> SplitCholesky::partition(const LocalCsr& A) const {
  const int ranks = comm_->getSize();
  const int numBlocks = static_cast<int>(blockStart_.size()) - 1;
  if (ranks == 1 || numBlocks < kMinBlocksPerRank * ranks) return {};
  TRIBOS_REQUIRE(blockStart_.back() == A.rows, "SplitCholesky: the row blocks cover " << blockStart_.back()
                                                  << " rows of a matrix of " << A.rows);
  std::vector<int> blockOf(A.rows);
  for (int b = 0; b < numBlocks; ++b)
    std::fill(blockOf.begin() + blockStart_[b], blockOf.begin() + blockStart_[b + 1], b);
  // The block graph (no self loops), on every rank: the separator needs it.
  std::vector<std::vector<int>> neighbours(numBlocks);
  for (int i = 0; i < A.rows; ++i)
    for (int k = A.rowptr[i]; k < A.rowptr[i + 1]; ++k)
      if (blockOf[A.col[k]] != blockOf[i]) neighbours[blockOf[i]].push_back(blockOf[A.col[k]]);
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  // METIS on rank 0, its parts broadcast: every rank splits alike.
  std::vector<int> blockPart(numBlocks, 0);
  int ok = 1;
  if (comm_->getRank() == 0) {
    std::vector<idx_t> xadj(1, 0), adjncy, vwgt(numBlocks), part(numBlocks, 0);
    for (int b = 0; b < numBlocks; ++b) {
      adjncy.insert(adjncy.end(), neighbours[b].begin(), neighbours[b].end());
      xadj.push_back(static_cast<idx_t>(adjncy.size()));
      vwgt[b] = blockStart_[b + 1] - blockStart_[b];
    }
    idx_t nvtxs = numBlocks, ncon = 1, nparts = ranks, objval = 0;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    // Recursive bisection for a few parts (METIS' advice below 8).
    const auto partGraph = ranks < 8 ? METIS_PartGraphRecursive : METIS_PartGraphKway;
    ok = partGraph(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr, &nparts, nullptr,
                   nullptr, options, &objval, part.data()) == METIS_OK;
    std::copy(part.begin(), part.end(), blockPart.begin());
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, rawComm(*comm_));
  if (!ok) return {};
  MPI_Bcast(blockPart.data(), numBlocks, MPI_INT, 0, rawComm(*comm_));
  // A block coupled to a block of a later part joins the separator: then no
  // entry of A couples two parts.
  std::vector<int> rowPart(A.rows);
  int separatorRows = 0;
  for (int b = 0; b < numBlocks; ++b) {
    const bool separates = std::any_of(neighbours[b].begin(), neighbours[b].end(),
                                       [&](int c) { return blockPart[c] > blockPart[b]; });
    const int rows = blockStart_[b + 1] - blockStart_[b];
    if (separates) separatorRows += rows;
    std::fill(rowPart.begin() + blockStart_[b], rowPart.begin() + blockStart_[b + 1], separates ? -1 : blockPart[b]);
  }
  if (separatorRows > maxSeparatorRows_ || separatorRows == 0) return {};
  return rowPart;
}

void SplitCholesky::factor(const LocalCsr& A) {
  TRIBOS_REQUIRE(A.rows == A.cols, "SplitCholesky: matrix is not square (" << A.rows << " x " << A.cols << ")");
  n_ = A.rows;
  whole_ = local_ = Teuchos::null;
  std::vector<int> rowPart;
  {
    Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::split Cholesky: partition"));
    rowPart = partition(A);
  }
  if (rowPart.empty()) {
    whole_ = createLocalSolver("CHOLMOD");
    checkOnEveryRank(*comm_, [&] { whole_->factor(A); });
    pivotRatio_ = whole_->pivotRatio();
    return;
  }
  factorSplit(A, rowPart);
}

void SplitCholesky::factorSplit(const LocalCsr& A, const std::vector<int>& rowPart) {
  const int rank = comm_->getRank();
  part_.clear();
  separator_.clear();
  for (int i = 0; i < n_; ++i) {
    if (rowPart[i] == rank) part_.push_back(i);
    if (rowPart[i] < 0) separator_.push_back(i);
  }
  const int np = static_cast<int>(part_.size()), ns = static_cast<int>(separator_.size());
  // M_p = [A_pp A_ps; A_sp A_ss]: A on the part's and the separator's rows,
  // in increasing order, the separator's positions ordered last.
  std::vector<int> rows(part_);
  rows.insert(rows.end(), separator_.begin(), separator_.end());
  std::sort(rows.begin(), rows.end());
  const LocalCsr M = A.principalSubmatrix(rows);
  partPosition_.clear();
  std::vector<int> last;
  for (int k = 0; k < np + ns; ++k) (rowPart[rows[k]] < 0 ? last : partPosition_).push_back(k);
  local_ = createLocalSolver("CHOLMOD");
  local_->setOrdering(LocalSolver::Ordering::OwnOrderingFirst);
  {
    Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::split Cholesky: factor of the part"));
    checkOnEveryRank(*comm_, [&] { local_->factor(M, last); });
  }
  Teuchos::TimeMonitor separatorTime(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::split Cholesky: separator"));
  local_->trailingFactor(Lt_);
  // sum_p (Lt_p Lt_p' - A_ss) + A_ss, summed on rank 0 and broadcast so that
  // every rank factors the same matrix to the last bit.
  std::vector<double> S(static_cast<size_t>(ns) * ns, 0.0), Ass(S.size(), 0.0);
  if (ns > 0)
    Teuchos::BLAS<int, double>().SYRK(Teuchos::LOWER_TRI, Teuchos::NO_TRANS, ns, ns, 1.0, Lt_.data(), ns, 0.0,
                                      S.data(), ns);
  const LocalCsr separatorBlock = A.principalSubmatrix(separator_);
  for (int r = 0; r < ns; ++r)
    for (int k = separatorBlock.rowptr[r]; k < separatorBlock.rowptr[r + 1]; ++k)
      Ass[static_cast<size_t>(separatorBlock.col[k]) * ns + r] = separatorBlock.val[k];
  for (int j = 0; j < ns; ++j)
    for (int i = j; i < ns; ++i) {
      const size_t at = static_cast<size_t>(j) * ns + i;
      S[at] -= Ass[at];
    }
  MPI_Reduce(rank == 0 ? MPI_IN_PLACE : S.data(), S.data(), ns * ns, MPI_DOUBLE, MPI_SUM, 0, rawComm(*comm_));
  MPI_Bcast(S.data(), ns * ns, MPI_DOUBLE, 0, rawComm(*comm_));
  for (int j = 0; j < ns; ++j)
    for (int i = j; i < ns; ++i) {
      const size_t at = static_cast<size_t>(j) * ns + i;
      S[at] += Ass[at];
    }
  const bool regular = schur_.tryFactor(std::move(S), ns);
  if (!schur_.positiveDefinite()) throw CollectiveError("SplitCholesky: the matrix is not positive definite");
  double ratio = std::min(local_->pivotRatio(), regular ? schur_.pivotRatio() : 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &ratio, 1, MPI_DOUBLE, MPI_MIN, rawComm(*comm_));
  pivotRatio_ = ratio;
  // The parts of every rank, for gathering solutions.
  partRows_ = allGatherv(part_, *comm_);
  partCounts_.assign(comm_->getSize(), 0);
  MPI_Allgather(&np, 1, MPI_INT, partCounts_.data(), 1, MPI_INT, rawComm(*comm_));
  partOffsets_.assign(1, 0);
  for (int c : partCounts_) partOffsets_.push_back(partOffsets_.back() + c);
  w_.assign(static_cast<size_t>(np) + ns, 0.0);
  yp_.assign(np, 0.0);
  zs_.assign(ns, 0.0);
  gathered_.assign(partRows_.size(), 0.0);
}

void SplitCholesky::forward(const double* b) const {
  const int np = static_cast<int>(part_.size()), ns = static_cast<int>(separator_.size());
  std::fill(w_.begin(), w_.end(), 0.0);
  for (int k = 0; k < np; ++k) w_[partPosition_[k]] = b[part_[k]];
  local_->solveFactor(w_.data(), false);  // to M_p's order: the part, then the separator
  // t_p = w_[np..]: -Lt_p t_p = L_sp z_p, summed over the ranks.
  std::copy(w_.begin() + np, w_.end(), zs_.begin());
  triangularProduct(Lt_, ns, false, zs_.data());
  MPI_Allreduce(MPI_IN_PLACE, zs_.data(), ns, MPI_DOUBLE, MPI_SUM, rawComm(*comm_));
  for (int k = 0; k < ns; ++k) zs_[k] += b[separator_[k]];  // b_s - sum_p L_sp z_p
  schur_.solveLower(zs_);
}

void SplitCholesky::backward() const {
  const int np = static_cast<int>(part_.size()), ns = static_cast<int>(separator_.size());
  schur_.solveUpperT(zs_);  // y_s
  std::copy(zs_.begin(), zs_.end(), w_.begin() + np);
  triangularProduct(Lt_, ns, true, w_.data() + np);  // Lt_p' y_s
  local_->solveFactor(w_.data(), true);               // back to M_p's rows
  for (int k = 0; k < np; ++k) yp_[k] = w_[partPosition_[k]];
}

void SplitCholesky::gatherSolution(double* x) const {
  const int np = static_cast<int>(part_.size());
  MPI_Allgatherv(yp_.data(), np, MPI_DOUBLE, gathered_.data(), partCounts_.data(), partOffsets_.data(), MPI_DOUBLE,
                 rawComm(*comm_));
  for (size_t k = 0; k < partRows_.size(); ++k) x[partRows_[k]] = gathered_[k];
  for (size_t k = 0; k < separator_.size(); ++k) x[separator_[k]] = zs_[k];
}

void SplitCholesky::solve(const double* b, double* x, int nrhs) const {
  if (!whole_.is_null()) return whole_->solve(b, x, nrhs);
  for (int j = 0; j < nrhs; ++j) {
    forward(b + static_cast<size_t>(j) * n_);
    backward();
    gatherSolution(x + static_cast<size_t>(j) * n_);
  }
}

void SplitCholesky::solveFactor(double* x, bool transpose) const {
  if (!whole_.is_null()) return whole_->solveFactor(x, transpose);
  const int np = static_cast<int>(part_.size()), ns = static_cast<int>(separator_.size());
  const int rank = comm_->getRank(), tail = partOffsets_.back();
  if (!transpose) {
    forward(x);
    // [z_0 | z_1 | ... | z_s]
    MPI_Allgatherv(w_.data(), np, MPI_DOUBLE, x, partCounts_.data(), partOffsets_.data(), MPI_DOUBLE,
                   rawComm(*comm_));
    std::copy(zs_.begin(), zs_.end(), x + tail);
    return;
  }
  std::copy(x + partOffsets_[rank], x + partOffsets_[rank] + np, w_.begin());
  std::copy(x + tail, x + tail + ns, zs_.begin());
  backward();
  gatherSolution(x);
}

double SplitCholesky::factorMemoryMb() const {
  if (!whole_.is_null()) return whole_->factorMemoryMb();
  const double dense = 2.0 * static_cast<double>(separator_.size()) * separator_.size() * 8.0 / 1048576.0;
  return (local_.is_null() ? 0.0 : local_->factorMemoryMb()) + dense;
}

}  // namespace Feti
}  // namespace Tribos
