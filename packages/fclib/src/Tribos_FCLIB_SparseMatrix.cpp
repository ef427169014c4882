#include "Tribos_FCLIB_SparseMatrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace FCLIB {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& why) {
  throw Error(what + ": " + why);
}

// m + 1 row pointers must fit in an int, as FCLIB stores them in int32.
void checkShape(int m, int n, const std::string& what) {
  if (m < 0 || n < 0)
    fail(what, "negative dimension " + std::to_string(m) + " x " + std::to_string(n));
  if (m == std::numeric_limits<int>::max() || n == std::numeric_limits<int>::max())
    fail(what, "dimension " + std::to_string(m) + " x " + std::to_string(n) + " is too large");
}

// Validates a pointer array of 'count'+1 entries that indexes 'nnzAvailable'
// entries: starts at 0, non-decreasing, last entry within the data.
void checkPointers(const std::vector<int>& ptr, int count, std::size_t nnzAvailable,
                   const std::string& what) {
  if (ptr.size() != static_cast<std::size_t>(count) + 1)
    fail(what, "p has " + std::to_string(ptr.size()) + " entries, expected " +
                   std::to_string(static_cast<long long>(count) + 1) + " (one pointer per " +
                   "row or column, plus one)");
  if (ptr[0] != 0) fail(what, "p[0] = " + std::to_string(ptr[0]) + ", expected 0");
  for (int k = 0; k < count; ++k)
    if (ptr[k + 1] < ptr[k])
      fail(what, "p[" + std::to_string(k + 1) + "] = " + std::to_string(ptr[k + 1]) +
                     " is less than p[" + std::to_string(k) + "] = " + std::to_string(ptr[k]) +
                     " (pointers must not decrease)");
  if (static_cast<std::size_t>(ptr[count]) > nnzAvailable)
    fail(what, "p[" + std::to_string(count) + "] = " + std::to_string(ptr[count]) +
                   " entries, but only " + std::to_string(nnzAvailable) +
                   " are stored in i and x");
}

void checkIndices(const std::vector<int>& idx, std::size_t count, int bound,
                  const std::string& arrayName, const std::string& what) {
  for (std::size_t k = 0; k < count; ++k)
    if (idx[k] < 0 || idx[k] >= bound)
      fail(what, arrayName + "[" + std::to_string(k) + "] = " + std::to_string(idx[k]) +
                     " is outside [0, " + std::to_string(bound) + ")");
}

// The row (or column) of every entry of a compressed matrix, from the
// pointers of its count rows (or columns); none without pointers.
std::vector<int> expandPointers(const std::vector<int>& ptr, int count) {
  std::vector<int> index(ptr.empty() ? 0 : ptr[count]);
  for (int r = 0; r < count; ++r)
    for (int k = ptr[r]; k < ptr[r + 1]; ++k) index[k] = r;
  return index;
}

// The first count entries of v (a file may store more than its pointers use).
template <class T>
std::vector<T> firstEntries(const std::vector<T>& v, int count) {
  return std::vector<T>(v.begin(), v.begin() + count);
}

// A matrix compressed by rows (CSR: m + 1 pointers, the column of each
// entry) or by columns (CSC: n + 1 pointers, the row of each entry),
// checked, then expanded to triplets and canonicalized (the file need not
// sort the entries of a row or column).
LocalCsr fromCompressed(int m, int n, bool byRows, const std::vector<int>& ptr, const std::vector<int>& index,
                        const std::vector<double>& value, const std::string& what) {
  checkShape(m, n, what);
  const int outer = byRows ? m : n, inner = byRows ? n : m;
  checkPointers(ptr, outer, std::min(index.size(), value.size()), what);
  const int count = ptr[outer];
  checkIndices(index, count, inner, "i", what);
  const std::vector<int> expanded = expandPointers(ptr, outer), listed = firstEntries(index, count);
  return byRows ? fromTriplets(m, n, expanded, listed, firstEntries(value, count), what)
                : fromTriplets(m, n, listed, expanded, firstEntries(value, count), what);
}

}  // namespace

LocalCsr fromTriplets(int m, int n, const std::vector<int>& row, const std::vector<int>& column,
                      const std::vector<double>& value, const std::string& what) {
  checkShape(m, n, what);
  const std::size_t count = row.size();
  if (column.size() != count || value.size() != count)
    fail(what, "triplet arrays have different lengths (" + std::to_string(row.size()) + ", " +
                   std::to_string(column.size()) + ", " + std::to_string(value.size()) + ")");
  if (count > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    fail(what, std::to_string(count) + " entries do not fit in int32 pointers");
  checkIndices(row, count, m, "i", what);
  checkIndices(column, count, n, "p", what);

  // Order the entries by (row, column), keeping file order among duplicates so
  // that the summation order, hence the result, is deterministic.
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return row[a] != row[b] ? row[a] < row[b] : column[a] < column[b];
  });

  LocalCsr A;
  A.rows = m;
  A.cols = n;
  A.rowptr.assign(static_cast<std::size_t>(m) + 1, 0);
  A.col.reserve(count);
  A.val.reserve(count);
  int lastRow = -1, lastCol = -1;
  for (std::size_t k : order) {
    if (row[k] == lastRow && column[k] == lastCol) {
      A.val.back() += value[k];
      continue;
    }
    A.col.push_back(column[k]);
    A.val.push_back(value[k]);
    ++A.rowptr[row[k] + 1];
    lastRow = row[k];
    lastCol = column[k];
  }
  for (int r = 0; r < m; ++r) A.rowptr[r + 1] += A.rowptr[r];
  return A;
}

LocalCsr fromCSR(int m, int n, const std::vector<int>& rowptr, const std::vector<int>& column,
                 const std::vector<double>& value, const std::string& what) {
  return fromCompressed(m, n, true, rowptr, column, value, what);
}

LocalCsr fromCSC(int m, int n, const std::vector<int>& colptr, const std::vector<int>& rowIndex,
                 const std::vector<double>& value, const std::string& what) {
  return fromCompressed(m, n, false, colptr, rowIndex, value, what);
}

void toTriplets(const LocalCsr& A, std::vector<int>& row, std::vector<int>& column) {
  row = expandPointers(A.rowptr, A.rows);
  column = A.col;
}

Asymmetry largestAsymmetry(const LocalCsr& A) {
  if (A.rows != A.cols) throw Error("FCLIB::asymmetry: matrix is not square");
  const auto &rowptr = A.rowptr, &col = A.col;
  const auto& val = A.val;
  // Look up A_ji by binary search in the (sorted) row j; a missing entry is 0.
  auto entry = [&](int r, int c) {
    auto first = col.begin() + rowptr[r], last = col.begin() + rowptr[r + 1];
    auto it = std::lower_bound(first, last, c);
    return (it != last && *it == c) ? val[it - col.begin()] : 0.0;
  };
  Asymmetry worst;
  double largest = 0.0;
  for (int r = 0; r < A.rows; ++r)
    for (int k = rowptr[r]; k < rowptr[r + 1]; ++k) {
      const double mirror = entry(col[k], r), difference = std::abs(val[k] - mirror);
      if (difference > largest) largest = difference, worst = {r, col[k], val[k], mirror};
    }
  return worst;
}

double asymmetry(const LocalCsr& A) {
  const Asymmetry a = largestAsymmetry(A);
  return std::abs(a.value - a.mirror);
}

bool isZero(const LocalCsr& A) {
  return std::all_of(A.val.begin(), A.val.end(), [](double v) { return v == 0.0; });
}

double maxAbs(const LocalCsr& A) {
  double worst = 0.0;
  for (double v : A.val) worst = std::max(worst, std::abs(v));
  return worst;
}

bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool bitwiseEqual(const LocalCsr& a, const LocalCsr& b) {
  return a.rows == b.rows && a.cols == b.cols && a.rowptr == b.rowptr && a.col == b.col && bitwiseEqual(a.val, b.val);
}

}  // namespace FCLIB
}  // namespace Tribos
