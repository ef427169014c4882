#include "Tribos_FetiOperators.hpp"

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <sstream>

#include "Tribos_AllGather.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_SplitCholesky.hpp"

namespace Tribos {
namespace Feti {

DualOperator::DualOperator(RCP<const FetiProblem> problem) : problem_(problem) {
  p_ = rcp(new Vector(problem->primalMap()));
  z_ = rcp(new Vector(problem->primalMap()));
  rounded_ = maxOver(problem->singlePrecisionBlocks() ? 1.0 : 0.0, *problem->comm()) > 0;
}

void DualOperator::applyExact(const Vector& x, Vector& y) const {
  static const auto counter = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::F apply exact");
  Teuchos::TimeMonitor timer(*counter);
  Vector p(problem_->primalMap()), z(problem_->primalMap());
  problem_->B()->apply(x, p, Teuchos::TRANS);
  problem_->applyKplus(p, z);
  problem_->B()->apply(z, y);
}

void DualOperator::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, SC alpha, SC beta) const {
  static const auto counter = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::F apply");
  Teuchos::TimeMonitor timer(*counter);
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    auto x = X.getVector(j);
    auto y = Y.getVectorNonConst(j);
    static const auto bt = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::F apply: B");
    static const auto kt = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::F apply: K+");
    {
      Teuchos::TimeMonitor t(*bt);
      problem_->B()->apply(*x, *p_, Teuchos::TRANS);  // B' x
    }
    {
      Teuchos::TimeMonitor t(*kt);
      problem_->applyDualKplus(*p_, *z_);  // K+ B' x
    }
    Teuchos::TimeMonitor t(*bt);
    problem_->B()->apply(*z_, *y, Teuchos::NO_TRANS, alpha, beta);
    ++n_A_;
  }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
  const auto& ko = problem->kernelOffsets();
  blockLength_.assign(static_cast<size_t>(n_), 0);
  for (size_t s = 0; s + 1 < ko.size(); ++s)
    if (ko[s + 1] > ko[s]) blockLength_[ko[s]] = ko[s + 1] - ko[s];
  segPtr_.push_back(0);
  valPtr_.push_back(0);
  std::vector<std::pair<int, int>> entries;  // (subdomain, column of B) of one row
  for (LO i = 0; i < static_cast<LO>(B.getNodeNumRows()); ++i) {
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    B.getLocalRowView(i, cols, vals);
    entries.clear();
    for (size_t k = 0; k < cols.extent(0); ++k) {
      const GO gid = colMap->getGlobalElement(cols(k));
      const int s = static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), gid) - offsets.begin()) - 1;
      if (ko[s + 1] > ko[s]) entries.emplace_back(s, static_cast<int>(k));
    }
    std::sort(entries.begin(), entries.end());
    // One segment per subdomain: the sum over its entries of B_ik R_s(k, :).
    for (size_t e = 0; e < entries.size(); ++e) {
      const int s = entries[e].first, r = ko[s + 1] - ko[s];
      if (e == 0 || entries[e - 1].first != s) {
        segStart_.push_back(ko[s]);
        segVal_.resize(segVal_.size() + r, 0.0);
      }
      double* v = segVal_.data() + segVal_.size() - r;
      const int k = entries[e].second;
      for (int j = 0; j < r; ++j) v[j] += vals(k) * Rc[j][cols(k)];
    }
    segPtr_.push_back(static_cast<int>(segStart_.size()));
    valPtr_.push_back(static_cast<int>(segVal_.size()));
  }
  // GG' is regular unless some rigid motion touches no row of B at all.
  GGt_ = factorGramian(nullptr);
  if (GGt_.is_null()) {
    const auto motions = freeMotions(nullptr);
    std::string list;
    for (const auto& m : motions) list += (list.empty() ? "" : ", ") + m;
    throw CollectiveError("the body is free to move rigidly (" + list +
                "): no Dirichlet condition or contact holds this motion, so the displacement is not determined; "
                "add a Dirichlet condition that holds it");
  }
  GEGEt_ = factorGramian(&problem->isEqualityRow());
  equalityHoldsKernel_ = !GEGEt_.is_null();
}

namespace {

// The 6 x 6 blocks (s, t) of G_S G_S', keyed by s * S + t; row-major r_s x r_t
// values in a slot of 36.
using GramBlocks = std::map<long long, std::array<double, 36>>;

// Every rank's blocks summed on every rank (the coarse problem is replicated).
GramBlocks gatherBlocks(const GramBlocks& local, const Comm& comm) {
  std::vector<long long> keys;
  std::vector<double> values;
  for (const auto& [key, block] : local) {
    keys.push_back(key);
    values.insert(values.end(), block.begin(), block.end());
  }
  const std::vector<long long> allKeys = allGatherv(keys, comm);
  const std::vector<double> allValues = allGatherv(values, comm);
  const int total = static_cast<int>(allKeys.size());
  GramBlocks all;
  for (int k = 0; k < total; ++k) {
    auto [it, inserted] = all.try_emplace(allKeys[k]);
    if (inserted) it->second.fill(0.0);
    for (int v = 0; v < 36; ++v) it->second[v] += allValues[36 * static_cast<size_t>(k) + v];
  }
  return all;
}

}  // namespace

LocalCsr CoarseSpace::gramian(const std::vector<char>* rows) const {
  const auto& ko = problem_->kernelOffsets();
  const long long S = static_cast<long long>(ko.size()) - 1;
  // Block row s: its blocks (t, values) in a short list (a subdomain
  // couples to its few neighbours), searched linearly: a tree keyed by
  // (s, t) per product cost 40 % of the coarse factorization at k = 36.
  std::vector<std::vector<std::pair<long long, std::array<double, 36>>>> blockRows(static_cast<size_t>(S));
  struct Segment {
    long long subdomain;
    const double* values;  // r values
    int r;
  };
  std::vector<Segment> segments;
  const size_t numRows = segPtr_.size() - 1;
  for (size_t i = 0; i < numRows; ++i) {
    if (rows && !(*rows)[i]) continue;
    segments.clear();
    const double* v = segVal_.data() + valPtr_[i];
    for (int p = segPtr_[i]; p < segPtr_[i + 1]; ++p) {
      const int r = blockLength_[segStart_[p]];
      segments.push_back({std::upper_bound(ko.begin(), ko.end(), segStart_[p]) - ko.begin() - 1, v, r});
      v += r;
    }
    for (const auto& p : segments) {
      auto& blocks = blockRows[static_cast<size_t>(p.subdomain)];
      for (const auto& q : segments) {
        auto it = std::find_if(blocks.begin(), blocks.end(), [&](const auto& b) { return b.first == q.subdomain; });
        if (it == blocks.end()) {
          blocks.emplace_back(q.subdomain, std::array<double, 36>{});
          it = blocks.end() - 1;
        }
        for (int a = 0; a < p.r; ++a)
          for (int b = 0; b < q.r; ++b) it->second[6 * a + b] += p.values[a] * q.values[b];
      }
    }
  }
  GramBlocks local;
  for (long long s = 0; s < S; ++s)
    for (const auto& [t, block] : blockRows[static_cast<size_t>(s)]) local.emplace(s * S + t, block);
  const GramBlocks all = gatherBlocks(local, *problem_->comm());
  // CSR row by row: the blocks of block row s are consecutive in `all`.
  LocalCsr A;
  A.rows = A.cols = n_;
  A.rowptr.assign(1, 0);
  auto it = all.begin();
  for (long long s = 0; s < S; ++s) {
    auto end = it;
    while (end != all.end() && end->first / S == s) ++end;
    for (int a = 0; a < ko[s + 1] - ko[s]; ++a) {
      for (auto b = it; b != end; ++b) {
        const long long t = b->first % S;
        for (int c = 0; c < ko[t + 1] - ko[t]; ++c) A.col.push_back(ko[t] + c), A.val.push_back(b->second[6 * a + c]);
      }
      A.rowptr.push_back(static_cast<int>(A.col.size()));
    }
    it = end;
  }
  return A;
}

double CoarseSpace::factorMemoryMb() const {
  return (GGt_.is_null() ? 0.0 : GGt_->factorMemoryMb()) + (GEGEt_.is_null() ? 0.0 : GEGEt_->factorMemoryMb());
}

namespace {

// The factor of the 0 x 0 Gram matrix of an empty coarse space (FETI-1
// with every subdomain held by Dirichlet conditions): regular, and every
// solve is empty.
class EmptyFactor : public LocalSolver {
 public:
  void factor(const LocalCsr&) override {}
  void solve(const double*, double*, int) const override {}
  void solveFactor(double*, bool) const override {}
  double pivotRatio() const override { return 1.0; }
  std::string name() const override { return "empty"; }
  int size() const override { return 0; }
};

}  // namespace

namespace {

// A sparse Cholesky factor of a Gram matrix (into `factor`, which is
// returned), or null when it is singular.
RCP<LocalSolver> factorGram(const LocalCsr& A, RCP<LocalSolver> factor) {
  // A row of zeros (a rigid motion that no row touches) is singular before
  // any pivot is taken; CHOLMOD would stop on it, or succeed on round-off.
  for (int i = 0; i < A.rows; ++i)
    if (A.rowptr[i] == A.rowptr[i + 1]) return Teuchos::null;
  try {
    factor->factor(A);
  } catch (const Error&) {
    return Teuchos::null;  // not positive definite: singular
  }
  // A pivot far below the largest is a singular Gram matrix in floating
  // point (the factorization succeeds on round-off).
  return factor->pivotRatio() > 1e-12 ? factor : Teuchos::null;
}

}  // namespace

RCP<LocalSolver> CoarseSpace::factorGramian(const std::vector<char>* rows) const {
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::coarse factor"));
  if (n_ == 0) return rcp(new EmptyFactor);
  LocalCsr A;
  {
    Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::coarse factor: Gram matrix"));
    A = gramian(rows);
  }
  return factorGram(A, newGramFactor());
}

RCP<LocalSolver> CoarseSpace::newGramFactor() const {
  const std::string& how = problem_->coarseProblem();
  const bool split = how == "Split" || (how == "Auto" && problem_->comm()->getSize() > 1 && n_ >= kAutoSplitRows);
  if (!split) return createLocalSolver("CHOLMOD");
  // A subdomain's rigid modes stay in one part.
  std::vector<int> blockStart;
  for (int k : problem_->kernelOffsets())
    if (blockStart.empty() || k > blockStart.back()) blockStart.push_back(k);
  return rcp(new SplitCholesky(problem_->comm(), blockStart));
}

RCP<LocalSolver> CoarseSpace::factorFaceGramian(const LocalCsr& fixed) const {
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::coarse factor of a face"));
  if (n_ == 0) return rcp(new EmptyFactor);
  if (sumOver(static_cast<double>(fixed.rows), *problem_->comm()) == 0) return GGt_;
  // (G q)(G q)' per fixed direction q, in blocks keyed by the first coarse
  // columns of the two subdomains: G q sums the segments of q's rows
  // subdomain by subdomain.
  GramBlocks local;
  std::map<int, std::array<double, 6>> Gq;  // first coarse column -> r_s values
  for (int q = 0; q < fixed.rows; ++q) {
    Gq.clear();
    for (int k = fixed.rowptr[q]; k < fixed.rowptr[q + 1]; ++k) {
      const int i = fixed.col[k];
      const double* v = segVal_.data() + valPtr_[i];
      for (int p = segPtr_[i]; p < segPtr_[i + 1]; ++p) {
        const int start = segStart_[p], r = blockLength_[start];
        auto [it, inserted] = Gq.try_emplace(start);
        if (inserted) it->second.fill(0.0);
        for (int j = 0; j < r; ++j) it->second[j] += fixed.val[k] * v[j];
        v += r;
      }
    }
    for (const auto& [s, gs] : Gq)
      for (const auto& [t, gt] : Gq) {
        auto [it, inserted] = local.try_emplace(static_cast<long long>(s) * n_ + t);
        if (inserted) it->second.fill(0.0);
        for (int a = 0; a < blockLength_[s]; ++a)
          for (int b = 0; b < blockLength_[t]; ++b) it->second[6 * a + b] += gs[a] * gt[b];
      }
  }
  const GramBlocks all = gatherBlocks(local, *problem_->comm());
  if (gram_.rows != n_) gram_ = gramian(nullptr);
  // GG' has every block (s, t) that a row couples, so the pattern stays.
  LocalCsr A = gram_;
  for (const auto& [key, block] : all) {
    const int s = static_cast<int>(key / n_), t = static_cast<int>(key % n_);
    for (int a = 0; a < blockLength_[s]; ++a) {
      const int row = s + a;
      const auto first = A.col.begin() + A.rowptr[row], last = A.col.begin() + A.rowptr[row + 1];
      const auto at = std::lower_bound(first, last, t);
      TRIBOS_REQUIRE(at != last && *at == t, "coarse face: block (" << s << ", " << t << ") outside GG'");
      for (int b = 0; b < blockLength_[t]; ++b) A.val[(at - A.col.begin()) + b] -= block[6 * a + b];
    }
  }
  return factorGram(A, newGramFactor());
}

void CoarseSpace::applyFace(const LocalSolver& factor, const Vector& u, Vector& Tu) const {
  applyG(u, work_);
  factor.solve(work_.data(), work_.data(), 1);
  applyGt(work_, Tu);
}

void CoarseSpace::applyG(const Vector& x, std::vector<double>& y, const std::vector<char>* rows) const {
  y.assign(n_, 0.0);
  auto xv = x.getData();
  const size_t numRows = segPtr_.size() - 1;
  for (size_t i = 0; i < numRows; ++i) {
    if (rows && !(*rows)[i]) continue;
    const double xi = xv[i];
    const double* v = segVal_.data() + valPtr_[i];
    for (int p = segPtr_[i]; p < segPtr_[i + 1]; ++p) {
      double* yp = y.data() + segStart_[p];
      const int r = blockLength_[segStart_[p]];
      if (r == 6) {  // a floating subdomain: the common case, unrolled
        for (int j = 0; j < 6; ++j) yp[j] += v[j] * xi;
      } else {
        for (int j = 0; j < r; ++j) yp[j] += v[j] * xi;
      }
      v += r;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, y.data(), n_, MPI_DOUBLE, MPI_SUM, rawComm(*problem_->comm()));
}

void CoarseSpace::applyGt(const std::vector<double>& y, Vector& x, const std::vector<char>* rows) const {
  auto xv = x.getDataNonConst();
  const size_t numRows = segPtr_.size() - 1;
  for (size_t i = 0; i < numRows; ++i) {
    double s = 0;
    if (!rows || (*rows)[i]) {
      const double* v = segVal_.data() + valPtr_[i];
      for (int p = segPtr_[i]; p < segPtr_[i + 1]; ++p) {
        const double* yp = y.data() + segStart_[p];
        const int r = blockLength_[segStart_[p]];
        if (r == 6) {
          for (int j = 0; j < 6; ++j) s += v[j] * yp[j];
        } else {
          for (int j = 0; j < r; ++j) s += v[j] * yp[j];
        }
        v += r;
      }
    }
    xv[i] = s;
  }
}

void CoarseSpace::project(const Vector& x, Vector& Px) const {
  static const auto gTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::coarse projection: G");
  static const auto solveTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::coarse projection: solve");
  {
    Teuchos::TimeMonitor t(*gTimer);
    applyG(x, work_);
  }
  {
    Teuchos::TimeMonitor t(*solveTimer);
    GGt_->solve(work_.data(), work_.data(), 1);
  }
  applyGt(work_, Px);
  Px.update(1.0, x, -1.0);
}

void CoarseSpace::applyOrthonormal(const Vector& x, std::vector<double>& y) const {
  applyG(x, y);
  GGt_->solveFactor(y.data(), false);
}

void CoarseSpace::applyOrthonormalTranspose(const std::vector<double>& y, Vector& x) const {
  work_ = y;
  GGt_->solveFactor(work_.data(), true);
  applyGt(work_, x);
}

void CoarseSpace::particularSolution(const std::vector<double>& e, Vector& lambdaTilde) const {
  std::vector<double> y(e);
  if (equalityHoldsKernel_) {
    GEGEt_->solve(y.data(), y.data(), 1);
    applyGt(y, lambdaTilde, &problem_->isEqualityRow());
  } else {
    GGt_->solve(y.data(), y.data(), 1);
    applyGt(y, lambdaTilde);
  }
}

std::vector<double> CoarseSpace::amplitudes(const Vector& r, const std::vector<char>* rows) const {
  std::vector<double> y;
  if (!rows) {
    TRIBOS_REQUIRE(equalityHoldsKernel_, "rigid-body amplitudes: the Dirichlet and gluing rows do not fix every "
                                         "rigid motion; the rows where the contact holds are needed");
    applyG(r, y, &problem_->isEqualityRow());
    GEGEt_->solve(y.data(), y.data(), 1);
    return y;
  }
  const auto GSGSt = factorGramian(rows);
  TRIBOS_REQUIRE(!GSGSt.is_null(),
                 "rigid-body amplitudes: the constraints active at the solution do not fix every rigid motion");
  applyG(r, y, rows);
  GSGSt->solve(y.data(), y.data(), 1);
  return y;
}

namespace {

const char* kMotionNames[6] = {"translation x", "translation y", "translation z",
                               "rotation about x", "rotation about y", "rotation about z"};

double dotv(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

std::vector<double> CoarseSpace::globalMotion(int j) const {
  // Rotations about the centre of the bounding box of all subdomains.
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{1e300, 1e300, 1e300};  // hi holds -max
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k)
    for (const auto& x : problem_->subdomain(k).coords)
      for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], x[c]), hi[c] = std::min(hi[c], -x[c]);
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), 3, MPI_DOUBLE, MPI_MIN, rawComm(*problem_->comm()));
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), 3, MPI_DOUBLE, MPI_MIN, rawComm(*problem_->comm()));
  for (double& v : hi) v = -v;
  std::vector<double> alpha(static_cast<size_t>(n_), 0.0);
  for (int k = 0; k < problem_->numLocalSubdomains(); ++k) {
    const auto& sys = problem_->subdomain(k);
    const int n = sys.numDofs(), r = FetiProblem::kernelDim(sys);
    // u_j at the subdomain's dofs; its amplitudes R_s'u_j (R_s orthonormal).
    std::vector<double> u(static_cast<size_t>(n), 0.0);
    for (size_t a = 0; a < sys.nodes.size(); ++a) {
      Fem::Point x;
      for (int c = 0; c < 3; ++c) x[c] = sys.coords[a][c] - 0.5 * (lo[c] + hi[c]);
      Fem::Point motion{0, 0, 0};  // translation along axis j, or rotation about axis j - 3
      if (j < 3) motion[j] = 1.0;
      else motion = Fem::rotation(j - 3, x);
      for (int c = 0; c < 3; ++c) u[3 * a + c] = motion[c];
    }
    for (int b = 0; b < r; ++b) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += sys.R[static_cast<size_t>(b) * n + i] * u[i];
      alpha[problem_->kernelOffsets()[sys.id] + b] = s;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, alpha.data(), n_, MPI_DOUBLE, MPI_SUM, rawComm(*problem_->comm()));
  return alpha;
}

std::string CoarseSpace::describeMotion(const std::vector<double>& alpha) const {
  // Least-squares fit of alpha by the six global motions (6 x 6 normal equations).
  std::vector<std::vector<double>> m(6);
  for (int j = 0; j < 6; ++j) m[j] = globalMotion(j);
  std::vector<double> M(36), rhs(6);
  for (int a = 0; a < 6; ++a) {
    rhs[a] = dotv(m[a], alpha);
    for (int b = 0; b < 6; ++b) M[a * 6 + b] = dotv(m[a], m[b]);
  }
  Teuchos::LAPACK<int, double> lapack;
  std::vector<int> ipiv(6);
  int info = 0;
  lapack.GESV(6, 1, M.data(), 6, ipiv.data(), rhs.data(), 6, &info);
  if (info != 0) return "a rigid motion of a subdomain";
  double norm = 0;
  for (int j = 0; j < 6; ++j) norm += rhs[j] * rhs[j] * dotv(m[j], m[j]);
  std::ostringstream os;
  bool first = true;
  for (int j = 0; j < 6; ++j) {
    const double part = rhs[j] * rhs[j] * dotv(m[j], m[j]);
    if (part < 1e-6 * norm) continue;
    os << (first ? "" : " + ") << kMotionNames[j];
    first = false;
  }
  return first ? "a rigid motion of a subdomain" : os.str();
}

std::vector<std::vector<double>> CoarseSpace::nullSpace(const std::vector<char>* rows) const {
  if (n_ == 0) return {};  // no floating subdomain (FETI-1, Dirichlet everywhere)
  const LocalCsr sparse = gramian(rows);
  std::vector<double> A(static_cast<size_t>(n_) * n_, 0.0);
  for (int i = 0; i < n_; ++i)
    for (int k = sparse.rowptr[i]; k < sparse.rowptr[i + 1]; ++k) A[static_cast<size_t>(sparse.col[k]) * n_ + i] = sparse.val[k];
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> w(n_);
  int info = 0, lwork = -1;
  double query = 0;
  lapack.SYEV('V', 'L', n_, A.data(), n_, w.data(), &query, lwork, &info);
  lwork = static_cast<int>(query);
  std::vector<double> work(static_cast<size_t>(std::max(lwork, 1)));
  lapack.SYEV('V', 'L', n_, A.data(), n_, w.data(), work.data(), lwork, &info);
  TRIBOS_REQUIRE(info == 0, "rigid motions: the eigen-decomposition of G_S G_S' failed");
  std::vector<std::vector<double>> nullVectors;
  for (int i = 0; i < n_; ++i)
    if (w[i] <= 1e-10 * std::max(w[n_ - 1], 1e-300))
      nullVectors.emplace_back(A.begin() + static_cast<size_t>(i) * n_, A.begin() + static_cast<size_t>(i + 1) * n_);
  return nullVectors;
}

std::vector<std::string> CoarseSpace::freeMotions(const std::vector<char>* rows) const {
  if (!factorGramian(rows).is_null()) return {};
  const auto nullVectors = nullSpace(rows);
  // Name the global motions that lie in the null space; a null space that
  // holds none of them is described by its vectors' fitted motions.
  std::vector<std::string> names;
  for (int j = 0; j < 6; ++j) {
    const auto m = globalMotion(j);
    double inNull = 0;
    for (const auto& v : nullVectors) inNull += dotv(v, m) * dotv(v, m);
    if (inNull > (1 - 1e-6) * dotv(m, m)) names.push_back(kMotionNames[j]);
  }
  if (names.empty())
    for (const auto& v : nullVectors) names.push_back(describeMotion(v));
  return names;
}

}  // namespace Feti
}  // namespace Tribos
