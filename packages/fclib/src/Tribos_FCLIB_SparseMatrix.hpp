// Tribos_FCLIB_SparseMatrix.hpp: the sparse matrices of FCLIB problems, held
// as core's LocalCsr in one canonical form. Whatever the storage in the file
// (compressed rows, compressed columns or triplets), the readers below give
// column indices ascending within each row, duplicates summed, explicit
// zeros kept. One canonical form makes write-then-read round trips exact and
// lets the rest of the code deal with a single layout.
#pragma once

#include <string>
#include <vector>

#include "Tribos_LocalCsr.hpp"

namespace Tribos {
namespace FCLIB {

// Readers of the three FCLIB storages (m x n). They validate the index
// arrays and throw Tribos::Error (with 'what' as context) when inconsistent.
LocalCsr fromCSR(int m, int n, const std::vector<int>& rowptr, const std::vector<int>& col,
                 const std::vector<double>& val, const std::string& what);
LocalCsr fromCSC(int m, int n, const std::vector<int>& colptr, const std::vector<int>& row,
                 const std::vector<double>& val, const std::string& what);
LocalCsr fromTriplets(int m, int n, const std::vector<int>& row, const std::vector<int>& col,
                      const std::vector<double>& val, const std::string& what);

// Triplet view of a canonical matrix (row-major order).
void toTriplets(const LocalCsr& A, std::vector<int>& row, std::vector<int>& column);

// The entry farthest from its mirror: the largest |A_rc - A_cr| (a mirror
// that is not stored is 0), row = col = -1 when A is symmetric. Requires a
// square matrix in canonical form.
struct Asymmetry {
  int row = -1, col = -1;
  double value = 0, mirror = 0;  // A_rc, A_cr
};
Asymmetry largestAsymmetry(const LocalCsr& A);
// max |A_ij - A_ji| over the stored entries, and max |A_ij| (for a relative
// measure).
double asymmetry(const LocalCsr& A);
double maxAbs(const LocalCsr& A);
// Every stored entry is 0 (stops at the first that is not).
bool isZero(const LocalCsr& A);

bool bitwiseEqual(const LocalCsr& a, const LocalCsr& b);
bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace FCLIB
}  // namespace Tribos
