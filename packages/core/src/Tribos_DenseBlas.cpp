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
__attribute__((always_inline)) inline Double4 load(const float* p) {
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
      const Double4 a0 = load(a + i), a1 = load(a + i + 4);
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

// Two vectors of four lanes per row, six partial sums in all: enough
// independent additions to keep the multiply-add units busy. T: double, or
// float widened as it is read.
template <class T>
__attribute__((always_inline)) inline void dot3Rows(int n, const T* a0, const T* a1, const T* a2, const double* x,
                                                    double y[3]) {
  Double4 s0 = {0, 0, 0, 0}, s1 = s0, s2 = s0, t0 = s0, t1 = s0, t2 = s0;
  int i = 0;
  for (; i + 7 < n; i += 8) {
    const Double4 x0 = load(x + i), x1 = load(x + i + 4);
    s0 += load(a0 + i) * x0;
    t0 += load(a0 + i + 4) * x1;
    s1 += load(a1 + i) * x0;
    t1 += load(a1 + i + 4) * x1;
    s2 += load(a2 + i) * x0;
    t2 += load(a2 + i + 4) * x1;
  }
  s0 += t0;
  s1 += t1;
  s2 += t2;
  double y0 = (s0[0] + s0[1]) + (s0[2] + s0[3]), y1 = (s1[0] + s1[1]) + (s1[2] + s1[3]),
         y2 = (s2[0] + s2[1]) + (s2[2] + s2[3]);
  for (; i < n; ++i) {
    y0 += a0[i] * x[i];
    y1 += a1[i] * x[i];
    y2 += a2[i] * x[i];
  }
  y[0] = y0, y[1] = y1, y[2] = y2;
}

__attribute__((target_clones("arch=x86-64-v3", "default")))
void dot3(int n, const double* a0, const double* a1, const double* a2, const double* x, double y[3]) {
  dot3Rows(n, a0, a1, a2, x, y);
}

__attribute__((target_clones("arch=x86-64-v3", "default")))
void dot3(int n, const float* a0, const float* a1, const float* a2, const double* x, double y[3]) {
  dot3Rows(n, a0, a1, a2, x, y);
}

}  // namespace Blas
}  // namespace Tribos
