#include "Tribos_SubdomainPseudoInverse.hpp"

#include <Teuchos_BLAS.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Vector.hpp>

#include <chrono>
#include <cmath>

#include "Tribos_DenseBlas.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"

namespace Tribos {
namespace Feti {

std::vector<int> fixingDofs(const std::vector<double>& R, int n) {
  const int r = n > 0 ? static_cast<int>(R.size() / n) : 0;
  std::vector<double> W(R);  // working copy, column-major n x r
  std::vector<char> used(n, 0);
  std::vector<int> rows(r), colOrder(r);
  for (int j = 0; j < r; ++j) colOrder[j] = j;
  for (int k = 0; k < r; ++k) {
    int bestRow = -1, bestCol = -1;
    double best = -1;
    for (int jj = k; jj < r; ++jj) {
      const int j = colOrder[jj];
      for (int i = 0; i < n; ++i)
        if (!used[i] && std::abs(W[static_cast<size_t>(j) * n + i]) > best)
          best = std::abs(W[static_cast<size_t>(j) * n + i]), bestRow = i, bestCol = jj;
    }
    TRIBOS_REQUIRE(best > 1e-12, "fixing dofs: the rigid-body modes have rank " << k << " < " << r);
    std::swap(colOrder[k], colOrder[bestCol]);
    const int j = colOrder[k];
    rows[k] = bestRow;
    used[bestRow] = 1;
    // Eliminate column j from the remaining columns using the pivot row.
    for (int mm = k + 1; mm < r; ++mm) {
      const int m = colOrder[mm];
      const double factor = W[static_cast<size_t>(m) * n + bestRow] / W[static_cast<size_t>(j) * n + bestRow];
      for (int i = 0; i < n; ++i) W[static_cast<size_t>(m) * n + i] -= factor * W[static_cast<size_t>(j) * n + i];
    }
  }
  return rows;
}

namespace {

// x <- (I - R R') x for orthonormal R (n x r, column-major).
void removeKernel(const std::vector<double>& R, int n, double* x) {
  const int r = n > 0 ? static_cast<int>(R.size() / n) : 0;
  for (int j = 0; j < r; ++j) {
    const double* r = &R[static_cast<size_t>(j) * n];
    double dot = 0;
    for (int i = 0; i < n; ++i) dot += r[i] * x[i];
    for (int i = 0; i < n; ++i) x[i] -= dot * r[i];
  }
}

}  // namespace

SubdomainPseudoInverse::SubdomainPseudoInverse(const std::vector<Fem::SubdomainSystem>& systems,
                                               std::vector<std::vector<int>> boundary, const std::string& localSolver,
                                               long denseRowLimit, bool singleBlocks)
    : systems_(systems), boundary_(std::move(boundary)), singleBlocks_(singleBlocks) {
  TRIBOS_REQUIRE(boundary_.size() == systems_.size(),
                 "K+: " << boundary_.size() << " boundary dof lists for " << systems_.size() << " subdomains");
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::factor K_reg"));
  const auto t0 = std::chrono::steady_clock::now();
  KplusBB_.assign(systems_.size(), {});
  KplusBBf_.assign(systems_.size(), {});
  static const auto sparseTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::factor K_reg: sparse factor");
  static const auto denseTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::factor K_reg: dense block");
  Progress::stage("factorization of " + std::to_string(systems_.size()) + " subdomain matrices");
  std::vector<double> block;  // the unpacked dense block, one buffer for all
  for (size_t k = 0; k < systems_.size(); ++k) {
    Progress::iteration([&] { return "subdomain " + std::to_string(k + 1) + " of " + std::to_string(systems_.size()); });
    const auto& sys = systems_[k];
    LocalCsr Kreg = sys.K;
    const int n = sys.numDofs();
    const double rho = Kreg.maxAbsDiagonal();
    for (int i : fixingDofs(sys.R, n))
      for (int a = Kreg.rowptr[i]; a < Kreg.rowptr[i + 1]; ++a)
        if (Kreg.col[a] == i) Kreg.val[a] += rho;
    // A dense block of many rows costs more to form (|b|^3 flops) and hold
    // than the applications it saves: the caller's limit decides.
    const bool dense = denseRowLimit >= 0 && static_cast<long>(boundary_[k].size()) <= denseRowLimit;
    auto solver = createLocalSolver(localSolver);
    {
      Teuchos::TimeMonitor t(*sparseTimer);
      if (dense)
        solver->factor(Kreg, boundary_[k]);
      else
        solver->factor(Kreg);
    }
    Kreg_.push_back(solver);
    if (dense) {
      Teuchos::TimeMonitor t(*denseTimer);
      formDenseBlock(k, block);
    }
  }
  factorSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SubdomainPseudoInverse::refactor() {
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::refactor K_reg"));
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> block;
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& sys = systems_[k];
    // The same regularization at the same fixing dofs (R depends on the
    // coordinates alone), with the new values' scale.
    LocalCsr Kreg = sys.K;
    const double rho = Kreg.maxAbsDiagonal();
    for (int i : fixingDofs(sys.R, sys.numDofs()))
      for (int a = Kreg.rowptr[i]; a < Kreg.rowptr[i + 1]; ++a)
        if (Kreg.col[a] == i) Kreg.val[a] += rho;
    Kreg_[k]->refactor(Kreg);
    if (hasDenseBlock(k)) formDenseBlock(k, block);
  }
  factorSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double SubdomainPseudoInverse::denseBlockMemoryMb() const {
  double mb = 0;
  for (const auto& Z : KplusBB_) mb += Z.size() * 8.0 / 1048576.0;
  for (const auto& Z : KplusBBf_) mb += Z.size() * 4.0 / 1048576.0;
  return mb;
}

double SubdomainPseudoInverse::memoryMb() const {
  double mb = denseBlockMemoryMb();
  for (const auto& s : Kreg_) mb += s->factorMemoryMb();
  return mb;
}

// (K+)_bb for K+ = (I - RR') Z (I - RR'), Z = K_reg^-1:
//   (K+)_bb = Z_bb - R_b W_b' - W_b R_b' + R_b (R'W) R_b',  W = Z R,
// with Z_bb from the local solver and W from r solves.
void SubdomainPseudoInverse::formDenseBlock(size_t k, std::vector<double>& Z) {
  const auto& sys = systems_[k];
  const auto& b = boundary_[k];
  const int n = sys.numDofs(), nb = static_cast<int>(b.size()), r = n > 0 ? static_cast<int>(sys.R.size() / n) : 0;
  {
    static const auto inverseTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::factor K_reg: inverse block");
    Teuchos::TimeMonitor t(*inverseTimer);
    Kreg_[k]->inverseBlock(b, Z);
  }
  std::vector<double> W(static_cast<size_t>(n) * r);
  if (r > 0) Kreg_[k]->solve(sys.R.data(), W.data(), r);
  std::vector<double> RtW(static_cast<size_t>(r) * r, 0.0), Rb(static_cast<size_t>(nb) * r), Wb(Rb.size());
  for (int a = 0; a < r; ++a)
    for (int c = 0; c < r; ++c)
      for (int i = 0; i < n; ++i) RtW[a * r + c] += sys.R[static_cast<size_t>(a) * n + i] * W[static_cast<size_t>(c) * n + i];
  for (int a = 0; a < r; ++a)
    for (int i = 0; i < nb; ++i) {
      Rb[static_cast<size_t>(a) * nb + i] = sys.R[static_cast<size_t>(a) * n + b[i]];
      Wb[static_cast<size_t>(a) * nb + i] = W[static_cast<size_t>(a) * n + b[i]];
    }
  // V = R_b (R'W)/2 - W_b, so that (K+)_bb = Z_bb + R_b V' + V R_b'.
  std::vector<double> V(Wb.size());
  for (int a = 0; a < r; ++a)
    for (int i = 0; i < nb; ++i) {
      double s = -Wb[static_cast<size_t>(a) * nb + i];
      for (int c = 0; c < r; ++c) s += 0.5 * Rb[static_cast<size_t>(c) * nb + i] * RtW[c * r + a];
      V[static_cast<size_t>(a) * nb + i] = s;
    }
  Teuchos::BLAS<int, double> blas;
  if (r > 0) {
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::TRANS, nb, nb, r, 1.0, Rb.data(), nb, V.data(), nb, 1.0, Z.data(), nb);
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::TRANS, nb, nb, r, 1.0, V.data(), nb, Rb.data(), nb, 1.0, Z.data(), nb);
  }
  if (singleBlocks_)
    KplusBBf_[k] = Blas::packLower<float>(nb, Z);
  else
    KplusBB_[k] = Blas::packLower<double>(nb, Z);
}

// K+ = (I - RR') K_reg^-1 (I - RR') is still a generalized inverse (R'K = 0),
// symmetric, and free of the large near-kernel components of K_reg^-1 (the
// subdomain pinned at six dofs is soft along its rigid modes), which would
// otherwise cancel only after B and the projector and cost accuracy.
void SubdomainPseudoInverse::apply(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (size_t k = 0; k < systems_.size(); ++k) {
    applySubdomain(k, pv.getRawPtr() + offset, zv.getRawPtr() + offset);
    offset += systems_[k].numDofs();
  }
}

void SubdomainPseudoInverse::applySubdomain(size_t k, const double* p, double* z) const {
  const int n = systems_[k].numDofs();
  work_.assign(p, p + n);
  removeKernel(systems_[k].R, n, work_.data());
  Kreg_[k]->solve(work_.data(), z, 1);
  removeKernel(systems_[k].R, n, z);
}

bool SubdomainPseudoInverse::hasDenseBlocks() const {
  bool any = false;
  for (size_t k = 0; k < KplusBB_.size(); ++k) any = any || hasDenseBlock(k);
  return any;
}

// z_b = (K+)_bb p_b with the packed block; a block stored in single
// precision is applied in double (Blas::spmvMixed), so that F is one fixed
// symmetric operator, exact but for the rounding of its stored entries.
void SubdomainPseudoInverse::applyDenseBlock(size_t k, const double* p, double* z) const {
  const auto& b = boundary_[k];
  const int nb = static_cast<int>(b.size());
  work_.resize(2 * static_cast<size_t>(nb));
  double* pb = work_.data();
  double* zb = pb + nb;
  for (int i = 0; i < nb; ++i) pb[i] = p[b[i]];
  if (singleBlocks_)
    Blas::spmvMixed(nb, KplusBBf_[k].data(), pb, zb);
  else
    Blas::spmv(nb, 1.0, KplusBB_[k].data(), pb, 0.0, zb);
  for (int i = 0; i < nb; ++i) z[b[i]] = zb[i];
}

void SubdomainPseudoInverse::applyOnBoundary(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (size_t k = 0; k < systems_.size(); ++k) {
    if (hasDenseBlock(k))
      applyDenseBlock(k, pv.getRawPtr() + offset, zv.getRawPtr() + offset);
    else
      applySubdomain(k, pv.getRawPtr() + offset, zv.getRawPtr() + offset);
    offset += systems_[k].numDofs();
  }
}

}  // namespace Feti
}  // namespace Tribos
