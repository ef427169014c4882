// Tribos_LocalCsr.hpp: a plain compressed-row matrix for data that lives on one
// rank (subdomain stiffness matrices before they are wrapped in Tpetra, input
// to direct solvers that want raw CSR arrays).
#pragma once

#include <vector>

namespace Tribos {

struct LocalCsr {
  int rows = 0, cols = 0;
  std::vector<int> rowptr{0}, col;
  std::vector<double> val;

  // y = A x
  void multiply(const double* x, double* y) const {
    for (int i = 0; i < rows; ++i) {
      double s = 0;
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k) s += val[k] * x[col[k]];
      y[i] = s;
    }
  }
  double maxAbsDiagonal() const {
    double m = 0;
    for (int i = 0; i < rows; ++i)
      for (int k = rowptr[i]; k < rowptr[i + 1]; ++k)
        if (col[k] == i && (val[k] > m || -val[k] > m)) m = val[k] > 0 ? val[k] : -val[k];
    return m;
  }
};

}  // namespace Tribos
