// Tribos_SubdomainPseudoInverse.hpp: K+ of the floating subdomains, the
// one solve FETI's dual operator F = B K+ B' needs.
//
// Per subdomain K_reg = K + rho sum_{i in I} e_i e_i' (I: the fixing dofs of
// R, rho = max |diag K|) is factored; K+ = (I - RR') K_reg^-1 (I - RR') is a
// symmetric generalized inverse of K (K K+ K = K, docs/feti.md). Optionally
// the block (K+)_bb on the dofs b that B touches is formed densely once, so
// that B K+ B' is one packed symmetric product per subdomain.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

class SubdomainPseudoInverse {
 public:
  // systems: this rank's subdomains (K, R; kept by reference); boundary[k]:
  // the dofs of subdomain k that B touches (ascending); subdomains with at
  // most denseRowLimit of them get a dense block (K+)_bb (-1: none), stored
  // in single precision when singleBlocks (formed in double, then rounded:
  // the application of F then moves half the bytes; the rounded block is
  // applied in double, so F stays one symmetric operator, within about 6e-8
  // relative of the exact one entry by entry).
  // Factors every subdomain (collective only through the progress display).
  SubdomainPseudoInverse(const std::vector<Fem::SubdomainSystem>& systems, std::vector<std::vector<int>> boundary,
                         const std::string& localSolver, long denseRowLimit, bool singleBlocks = false);

  // z = K+ p on this rank's subdomains.
  void apply(const Vector& p, Vector& z) const;
  // z = K+ p as F = B K+ B' needs it: p = B'x lives on the boundary dofs and
  // only those entries of z are computed where a dense block exists (the
  // others are left as they are).
  void applyOnBoundary(const Vector& p, Vector& z) const;

  // True when some local subdomain has a dense block (K+)_bb.
  bool hasDenseBlocks() const;
  // True when those blocks are rounded to single precision.
  bool hasSingleBlocks() const { return singleBlocks_ && hasDenseBlocks(); }
  bool hasDenseBlock(size_t k) const { return !KplusBB_[k].empty() || !KplusBBf_[k].empty(); }
  // Entry (i, j) of the dense block (K+)_bb of local subdomain k, i and j
  // positions in its boundary list; hasDenseBlock(k) must hold.
  double denseBlockEntry(size_t k, int i, int j) const {
    if (i < j) std::swap(i, j);
    const size_t nb = boundary_[k].size();
    const size_t at = static_cast<size_t>(i) + static_cast<size_t>(j) * (2 * nb - j - 1) / 2;  // packed lower
    return singleBlocks_ ? static_cast<double>(KplusBBf_[k][at]) : KplusBB_[k][at];
  }
  // The subdomains' K have new values on the same patterns: a numeric
  // refactorization of each (the local solver keeps its ordering and
  // symbolic analysis where it can) and the dense blocks formed again.
  void refactor();
  double factorSeconds() const { return factorSeconds_; }
  double memoryMb() const;
  // The dense blocks alone: the bytes one application of F reads from them.
  double denseBlockMemoryMb() const;

 private:
  void applySubdomain(size_t k, const double* p, double* z) const;
  void applyDenseBlock(size_t k, const double* p, double* z) const;
  // Z: the caller's buffer for the unpacked block, reused from one
  // subdomain to the next so that no block touches fresh pages.
  void formDenseBlock(size_t k, std::vector<double>& Z);

  const std::vector<Fem::SubdomainSystem>& systems_;
  std::vector<std::vector<int>> boundary_;
  std::vector<RCP<LocalSolver>> Kreg_;           // factors of K_reg
  std::vector<std::vector<double>> KplusBB_;     // packed lower triangle of (K+)_bb, or empty
  std::vector<std::vector<float>> KplusBBf_;     // the same in single precision (singleBlocks)
  bool singleBlocks_ = false;
  mutable std::vector<double> work_;
  double factorSeconds_ = 0;
};

// The r rows of R (n x r, column-major; r = 6 in TFETI) chosen by greedy complete pivoting:
// R_I is then nonsingular and well conditioned, so adding rho to those
// diagonal entries of K makes it nonsingular and its inverse a generalized
// inverse of K (K K_reg^-1 K = K, see docs/feti.md).
std::vector<int> fixingDofs(const std::vector<double>& R, int n);

}  // namespace Feti
}  // namespace Tribos
