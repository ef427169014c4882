#include "Tribos_DenseBlas.hpp"

#include <cstring>

namespace Tribos {
namespace Blas {

// The helpers below pass 32-byte vectors; they are always inlined into the
// clones, so the ABI of such returns (GCC's -Wpsabi note) never applies.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {
// Four lanes of a column: its floats widened to double.
typedef float Float4 __attribute__((vector_size(16)));
typedef double Double4 __attribute__((vector_size(32)));

__attribute__((always_inline)) inline Double4 load(const double* p) {
  Double4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
__attribute__((always_inline)) inline Double4 loadWidened(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, Double4);
}
__attribute__((always_inline)) inline void store(double* p, Double4 v) { std::memcpy(p, &v, sizeof v); }
}  // namespace

// Column j of the packed lower triangle holds a_jj, a_(j+1)j, ..., a_(n-1)j.
// It adds a_jj x_j + sum_i a_ij x_i to y_j (a dot product, in eight partial
// sums so that its additions do not wait on each other) and a_ij x_j to y_i
// (an axpy), both from one pass over the column.
__attribute__((target_clones("arch=x86-64-v3", "default")))
void spmvMixed(int n, const float* Ap, const double* x, double* y) {
  for (int i = 0; i < n; ++i) y[i] = 0.0;
  for (int j = 0; j < n; ++j) {
    const float* a = Ap;
    const int m = n - j;  // the column's length, diagonal first
    double* yc = y + j;
    const double* xc = x + j;
    const double xj = x[j];
    const Double4 xj4 = {xj, xj, xj, xj};
    Double4 t0 = {0, 0, 0, 0}, t1 = t0;
    double t = a[0] * xj;
    int i = 1;
    for (; i + 7 < m; i += 8) {
      const Double4 a0 = loadWidened(a + i), a1 = loadWidened(a + i + 4);
      store(yc + i, load(yc + i) + a0 * xj4);
      store(yc + i + 4, load(yc + i + 4) + a1 * xj4);
      t0 += a0 * load(xc + i);
      t1 += a1 * load(xc + i + 4);
    }
    for (; i < m; ++i) {
      const double ai = a[i];
      yc[i] += ai * xj;
      t += ai * xc[i];
    }
    const Double4 s = t0 + t1;
    yc[0] += t + ((s[0] + s[1]) + (s[2] + s[3]));
    Ap += m;
  }
}

}  // namespace Blas
}  // namespace Tribos
