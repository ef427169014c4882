// Tribos_LocalSolver.hpp: sparse direct solvers for matrices that live on one
// rank (subdomain stiffness matrices, K_rr of the semismooth* reduction).
// Backends: CHOLMOD (supernodal Cholesky, the fast one on 3D elasticity) and
// Tacho (its own driver, see docs/feti.md) and KLU2 (Amesos2, serial
// communicator). Chosen by name.
#pragma once

#include <string>
#include <vector>

#include "Tribos_LocalCsr.hpp"
#include "Tribos_Registry.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// The CHOLMOD backend factors a matrix of at most this many rows densely
// (LAPACK) when asked for rows ordered last, and keeps the factor packed
// (n(n+1)/2 doubles; Tribos_LocalSolver.cpp, DenseBoundaryLast).
constexpr int kDenseFactorRows = 600;

class LocalSolver {
 public:
  virtual ~LocalSolver() = default;
  // A: symmetric positive definite, both triangles stored, sorted columns.
  virtual void factor(const LocalCsr& A) = 0;
  // The same, with the rows `last` ordered after all others, so that
  // inverseBlock(last) can be read off the trailing block of the factor (the
  // CHOLMOD backend; the others ignore the hint).
  virtual void factor(const LocalCsr& A, const std::vector<int>& last) {
    (void)last;
    factor(A);
  }
  // How factor(A, last) orders the other rows: by constrained minimum degree
  // (CAMD: on a subdomain matrix it fills least), or as the factorization of
  // the other rows alone would (CHOLMOD's own choice of AMD or METIS nested
  // dissection: on a 3D grid of subdomains' rigid modes, as FETI's coarse
  // problem, nested dissection fills far less). CHOLMOD backend only.
  enum class Ordering { ConstrainedMinimumDegree, OwnOrderingFirst };
  void setOrdering(Ordering ordering) { ordering_ = ordering; }

 protected:
  Ordering ordering_ = Ordering::ConstrainedMinimumDegree;

 public:
  // New values of A on the pattern of the last factor(A): a numeric
  // refactorization that keeps the ordering and symbolic analysis where the
  // backend can (CHOLMOD); the others factor again.
  virtual void refactor(const LocalCsr& A) { factor(A); }
  // x = A^-1 b for nrhs right-hand sides stored column after column (length n each).
  virtual void solve(const double* b, double* x, int nrhs = 1) const = 0;
  // (A^-1) restricted to the rows and columns `dofs`: dense, symmetric,
  // column-major |dofs| x |dofs|, written to Z (resized; its memory is reused,
  // so a caller forming many blocks keeps one buffer and touches no fresh
  // pages). By default |dofs| solves with unit vectors.
  virtual void inverseBlock(const std::vector<int>& dofs, std::vector<double>& Z) const;
  std::vector<double> inverseBlock(const std::vector<int>& dofs) const {
    std::vector<double> Z;
    inverseBlock(dofs, Z);
    return Z;
  }
  // For A = P'LL'P (a Cholesky factor with its fill-reducing permutation P):
  // x <- L^-1 P x, or x <- P'L^-T x when transpose. These halves of A^-1
  // orthonormalize: with A = GG', the rows of L^-1 P G are orthonormal.
  // Only Cholesky backends have them (CHOLMOD); the others throw.
  virtual void solveFactor(double* x, bool transpose) const;
  // After factor(A, last): the trailing |last| x |last| block of L (the
  // Cholesky factor of the Schur complement on `last`), column-major, zero
  // above the diagonal. Only Cholesky backends have it (CHOLMOD); the others
  // throw.
  virtual void trailingFactor(std::vector<double>& Z) const;
  // (min_i L_ii / max_i L_ii)^2, a cheap estimate of the reciprocal condition
  // number: a tiny value means A is singular in floating point although the
  // factorization succeeded on round-off. Cholesky backends only.
  virtual double pivotRatio() const;
  virtual std::string name() const = 0;
  virtual int size() const = 0;
  // Memory held by the factor, MB (0 when the backend does not report it).
  virtual double factorMemoryMb() const { return 0.0; }
};

// "CHOLMOD" | "KLU2" | "Tacho". Unknown names throw, listing the valid ones.
// The local solvers by name (Tribos_Registry.hpp).
using LocalSolverRegistry = Registry<LocalSolver>;
const LocalSolverRegistry& localSolvers();
RCP<LocalSolver> createLocalSolver(const std::string& name);
std::vector<std::string> localSolverNames();

}  // namespace Tribos
