// Tribos_LocalCsr.hpp: a plain compressed-row matrix for data that lives on one
// rank (subdomain stiffness matrices before they are wrapped in Tpetra, input
// to direct solvers that want raw CSR arrays, the matrices of FCLIB files).
#pragma once

#include <string>
#include <algorithm>
#include <utility>
#include <vector>

#include "Tribos_Error.hpp"

namespace Tribos {

// Compressed rows held elsewhere (a LocalCsr, an FCLIB matrix): read-only
// arrays, no copy.
struct CsrView {
  int rows = 0, cols = 0;
  const int* rowptr = nullptr;  // rows + 1
  const int* col = nullptr;
  const double* val = nullptr;
};

struct LocalCsr {
  int rows = 0, cols = 0;
  std::vector<int> rowptr{0}, col;
  std::vector<double> val;

  // The number of stored entries (none without row pointers).
  int nnz() const { return rowptr.empty() ? 0 : rowptr.back(); }

  // y = A x
  void multiply(const double* x, double* y) const {
    for (int i = 0; i < rows; ++i) {
      double s = 0;
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k) s += val[k] * x[col[k]];
      y[i] = s;
    }
  }
  // y = A x and y = A' x on vectors: x must have cols (rows) entries, y is
  // resized to rows (cols).
  void multiply(const std::vector<double>& x, std::vector<double>& y) const {
    requireLength(x, cols, "multiply", "columns");
    y.assign(rows, 0.0);
    multiply(x.data(), y.data());
  }
  void multiplyTranspose(const std::vector<double>& x, std::vector<double>& y) const {
    requireLength(x, rows, "multiplyTranspose", "rows");
    y.assign(cols, 0.0);
    for (int i = 0; i < rows; ++i)
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k) y[col[k]] += val[k] * x[i];
  }
  // The principal submatrix on `keep` (ascending indices), columns renumbered.
  LocalCsr principalSubmatrix(const std::vector<int>& keep) const {
    std::vector<int> position(cols, -1);
    for (size_t j = 0; j < keep.size(); ++j) position[keep[j]] = static_cast<int>(j);
    LocalCsr S;
    S.rows = S.cols = static_cast<int>(keep.size());
    for (int i : keep) {
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k)
        if (position[col[k]] >= 0) S.col.push_back(position[col[k]]), S.val.push_back(val[k]);
      S.rowptr.push_back(static_cast<int>(S.col.size()));
    }
    return S;
  }
  double maxAbsDiagonal() const {
    double m = 0;
    for (int i = 0; i < rows; ++i)
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k)
        if (col[k] == i && (val[k] > m || -val[k] > m)) m = val[k] > 0 ? val[k] : -val[k];
    return m;
  }
  CsrView view() const { return {rows, cols, rowptr.data(), col.data(), val.data()}; }

  // A square matrix from its rows of (column, value) entries in any order:
  // columns ascending, a column given twice summed (as an assembly sums).
  static LocalCsr fromRows(std::vector<std::vector<std::pair<int, double>>> entries) {
    LocalCsr A;
    A.rows = A.cols = static_cast<int>(entries.size());
    for (auto& row : entries) {
      std::sort(row.begin(), row.end());
      for (std::size_t k = 0; k < row.size(); ++k) {
        if (k > 0 && row[k].first == row[k - 1].first) A.val.back() += row[k].second;
        else A.col.push_back(row[k].first), A.val.push_back(row[k].second);
      }
      A.rowptr.push_back(static_cast<int>(A.col.size()));
    }
    return A;
  }

 private:
  static void requireLength(const std::vector<double>& x, int length, const char* product, const char* what) {
    if (x.size() != static_cast<std::size_t>(length))
      throw Error(std::string("LocalCsr::") + product + ": x has " + std::to_string(x.size()) + " entries, matrix has " +
                  std::to_string(length) + " " + what);
  }
};

}  // namespace Tribos
