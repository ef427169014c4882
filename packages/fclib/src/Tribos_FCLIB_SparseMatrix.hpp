// Tribos_FCLIB_SparseMatrix.hpp: the sparse matrix as FCLIB problems are held
// in memory. Whatever the storage in the file (compressed rows, compressed
// columns or triplets), a matrix is kept in one canonical CSR form: column
// indices ascending within each row, duplicates summed, explicit zeros kept.
// One canonical form makes write-then-read round trips exact and lets the
// rest of the code deal with a single layout.
#pragma once

#include <string>
#include <vector>

namespace Tribos {
namespace FCLIB {

struct SparseMatrix {
  int m = 0;                  // rows
  int n = 0;                  // columns
  std::vector<int> rowptr;    // size m+1
  std::vector<int> col;       // size nnz, ascending within a row
  std::vector<double> val;    // size nnz

  int nnz() const { return rowptr.empty() ? 0 : rowptr.back(); }

  // y = A x (y is resized to m).
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;
  // y = A' x (y is resized to n).
  void multiplyTranspose(const std::vector<double>& x, std::vector<double>& y) const;

  // Builders from the three FCLIB storages. They validate the index arrays
  // and throw Tribos::Error (with 'what' as context) when inconsistent.
  static SparseMatrix fromCSR(int m, int n, const std::vector<int>& rowptr,
                              const std::vector<int>& col,
                              const std::vector<double>& val, const std::string& what);
  static SparseMatrix fromCSC(int m, int n, const std::vector<int>& colptr,
                              const std::vector<int>& row,
                              const std::vector<double>& val, const std::string& what);
  static SparseMatrix fromTriplets(int m, int n, const std::vector<int>& row,
                                   const std::vector<int>& col,
                                   const std::vector<double>& val, const std::string& what);

  // Triplet view of the canonical CSR (row-major order).
  void toTriplets(std::vector<int>& row, std::vector<int>& column) const;

  // The entry farthest from its mirror: the largest |A_rc - A_cr| (a mirror
  // that is not stored is 0), row = col = -1 when A is symmetric.
  struct Asymmetry {
    int row = -1, col = -1;
    double value = 0, mirror = 0;  // A_rc, A_cr
  };
  Asymmetry largestAsymmetry() const;
  // max |A_ij - A_ji| over the stored entries, and max |A_ij| (for a relative
  // measure). Require a square matrix.
  double asymmetry() const;
  double maxAbs() const;
  // Every stored entry is 0 (stops at the first that is not).
  bool isZero() const;
};

bool bitwiseEqual(const SparseMatrix& a, const SparseMatrix& b);
bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace FCLIB
}  // namespace Tribos
