// feti_spectrum: dense spectral study of the projected FETI operator and its
// preconditioners on a small cube (one rank). Prints the effective condition
// number (largest / smallest eigenvalue on range P) of
//   PFP                      no preconditioner
//   P M P F                  for M = B K B' (lumped), M = B_D K B_D' with
//                            B_D = (BB')^-1 B (lumped, scaled), and the
//                            Dirichlet versions B S B', B_D S B_D'
// and, for orthonormalized equality rows B_o = (BB')^-1/2 B (BB'_o = I), the
// same operators with the projector of G_o = R'B_o'.
//
//   feti_spectrum [--element Hex8|Tet4] [--grid n] [--cells c]   (n^3 subdomains of c^3 cells)
#include <Teuchos_LAPACK.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "Tribos_FetiDual.hpp"
#include "Tribos_ProcessStartup.hpp"

using namespace Tribos;

namespace {

using Dense = std::vector<double>;  // column-major

Dense multiply(const Dense& A, const Dense& B, int m, int k, int n, bool transA = false) {
  // C (m x n) = op(A) B, op(A) m x k
  Dense C(static_cast<size_t>(m) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int l = 0; l < k; ++l) {
      const double b = B[static_cast<size_t>(j) * k + l];
      if (b == 0.0) continue;
      for (int i = 0; i < m; ++i)
        C[static_cast<size_t>(j) * m + i] += (transA ? A[static_cast<size_t>(i) * k + l] : A[static_cast<size_t>(l) * m + i]) * b;
    }
  return C;
}

Dense transpose(const Dense& A, int m, int n) {
  Dense T(A.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) T[static_cast<size_t>(i) * n + j] = A[static_cast<size_t>(j) * m + i];
  return T;
}

// Symmetric eigen decomposition: eigenvalues ascending, A overwritten by eigenvectors.
std::vector<double> eig(Dense& A, int n) {
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> w(n), work(1);
  int info = 0;
  lapack.SYEV('V', 'U', n, A.data(), n, w.data(), work.data(), -1, &info);
  work.resize(static_cast<size_t>(work[0]));
  lapack.SYEV('V', 'U', n, A.data(), n, w.data(), work.data(), static_cast<int>(work.size()), &info);
  return w;
}

// f(A) for symmetric A through its eigen decomposition; eigenvalues below tol -> 0.
Dense matrixFunction(const Dense& A, int n, double (*f)(double), double tol) {
  Dense V(A);
  auto w = eig(V, n);
  Dense C(static_cast<size_t>(n) * n, 0.0);
  for (int k = 0; k < n; ++k) {
    const double fk = w[k] > tol ? f(w[k]) : 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) C[static_cast<size_t>(j) * n + i] += fk * V[static_cast<size_t>(k) * n + i] * V[static_cast<size_t>(k) * n + j];
  }
  return C;
}

double invSqrt(double x) { return 1.0 / std::sqrt(x); }
double sqrtF(double x) { return std::sqrt(x); }
double inv(double x) { return 1.0 / x; }

// P = I - G'(GG')^-1 G for G (c x m).
Dense projector(const Dense& G, int c, int m) {
  Dense GGt = multiply(G, transpose(G, c, m), c, m, c);
  Dense GGtInv = matrixFunction(GGt, c, inv, 1e-12 * 1e-300);
  Dense X = multiply(GGtInv, G, c, c, m);                 // (GG')^-1 G
  Dense P = multiply(G, X, m, c, m, true);                 // G'(GG')^-1 G
  for (auto& v : P) v = -v;
  for (int i = 0; i < m; ++i) P[static_cast<size_t>(i) * m + i] += 1.0;
  return P;
}

// Condition number of A on range P (dimension r), A symmetric.
double condOnRange(const Dense& PAP, int m, int r) {
  Dense V(PAP);
  auto w = eig(V, m);
  return w[m - 1] / w[m - r];
}

// Condition number of the preconditioned operator (P M P)(P A P) on range P:
// eigenvalues of (PAP)^1/2 PMP (PAP)^1/2.
double condPreconditioned(const Dense& PAP, const Dense& PMP, int m, int r) {
  Dense V(PAP);
  auto w = eig(V, m);
  const double tol = w[m - 1] * 1e-10;
  Dense S = matrixFunction(PAP, m, sqrtF, tol);
  Dense C = multiply(S, multiply(PMP, S, m, m, m), m, m, m);
  Dense W(C);
  auto mu = eig(W, m);
  return mu[m - 1] / mu[m - r];
}

Dense sandwich(const Dense& P, const Dense& A, int m) { return multiply(P, multiply(A, P, m, m, m), m, m, m); }

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  std::string element = "Hex8";
  int grid = 2, cells = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--element") element = argv[i + 1];
    else if (a == "--grid") grid = std::stoi(argv[i + 1]);
    else if (a == "--cells") cells = std::stoi(argv[i + 1]);
  }
  Mesh::BoxSpec spec;
  spec.type = Mesh::cellTypeFromName(element);
  spec.cells = {grid * cells, grid * cells, grid * cells};
  Mesh::DecompositionSpec dec;
  dec.grid = {grid, grid, grid};
  Mesh::Discretization disc(Mesh::generateBox(spec), spec, dec, 1, 0);
  Fem::LoadCase loads;
  Fem::DirichletCondition clamp;
  clamp.face = "xmin";
  loads.dirichlet = {clamp};
  loads.tractions = {{"zmax", {0, 0, -1e7}}};
  Teuchos::ParameterList params;
  auto problem = rcp(new Feti::FetiProblem(disc, Fem::Material{2.1e11, 0.3}, loads, std::vector<Feti::ContactConstraint>(),
                                           params, comm));
  Feti::FetiDual dual(problem);
  const int m = static_cast<int>(problem->dualMap()->getGlobalNumElements());
  const int n = static_cast<int>(problem->primalMap()->getGlobalNumElements());
  const int c = dual.coarse().size();
  std::printf("%s: %d subdomains of %d^3 cells, primal %d, dual %d, coarse %d\n", element.c_str(), grid * grid * grid,
              cells, n, m, c);

  // Dense B (m x n), K (n x n), F (m x m), R (n x c).
  Dense B(static_cast<size_t>(m) * n, 0.0), K(static_cast<size_t>(n) * n, 0.0), Kp(static_cast<size_t>(n) * n, 0.0);
  Vector e(problem->primalMap()), y(problem->primalMap()), d(problem->dualMap());
  for (int j = 0; j < n; ++j) {
    e.putScalar(0.0);
    e.replaceGlobalValue(j, 1.0);
    problem->applyK(e, y);
    auto yv = y.getData();
    std::copy(yv.begin(), yv.end(), &K[static_cast<size_t>(j) * n]);
    problem->applyKplus(e, y);
    auto zv = y.getData();
    std::copy(zv.begin(), zv.end(), &Kp[static_cast<size_t>(j) * n]);
    problem->B()->apply(e, d);
    auto dv = d.getData();
    std::copy(dv.begin(), dv.end(), &B[static_cast<size_t>(j) * m]);
  }
  Dense Bt = transpose(B, m, n);
  // R: columns from applyR of unit coarse vectors.
  Dense R(static_cast<size_t>(n) * c, 0.0);
  for (int k = 0; k < c; ++k) {
    std::vector<double> a(c, 0.0);
    a[k] = 1.0;
    problem->applyR(a, y);
    auto yv = y.getData();
    std::copy(yv.begin(), yv.end(), &R[static_cast<size_t>(k) * n]);
  }
  // Schur complement of every subdomain on the dofs B touches (block diagonal):
  // S = K_bb - K_bi K_ii^-1 K_ib, assembled as a dense n x n matrix on the b dofs.
  std::vector<char> boundary(n, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i)
      if (B[static_cast<size_t>(j) * m + i] != 0.0) boundary[j] = 1;
  Dense S(static_cast<size_t>(n) * n, 0.0);
  {
    const auto& off = problem->primalOffsets();
    for (int s = 0; s + 1 < static_cast<int>(off.size()); ++s) {
      std::vector<int> bi, ii;
      for (int j = off[s]; j < off[s + 1]; ++j) (boundary[j] ? bi : ii).push_back(j);
      const int nb = bi.size(), ni = ii.size();
      Dense Kii(static_cast<size_t>(ni) * ni), Kib(static_cast<size_t>(ni) * nb);
      for (int q = 0; q < ni; ++q)
        for (int p = 0; p < ni; ++p) Kii[static_cast<size_t>(q) * ni + p] = K[static_cast<size_t>(ii[q]) * n + ii[p]];
      for (int q = 0; q < nb; ++q)
        for (int p = 0; p < ni; ++p) Kib[static_cast<size_t>(q) * ni + p] = K[static_cast<size_t>(bi[q]) * n + ii[p]];
      Teuchos::LAPACK<int, double> lapack;
      int info = 0;
      if (ni > 0) {
        Dense X(Kib);
        lapack.POSV('L', ni, nb, Kii.data(), ni, X.data(), ni, &info);
        for (int q = 0; q < nb; ++q)
          for (int p = 0; p < nb; ++p) {
            double v = K[static_cast<size_t>(bi[q]) * n + bi[p]];
            for (int l = 0; l < ni; ++l) v -= Kib[static_cast<size_t>(p) * ni + l] * X[static_cast<size_t>(q) * ni + l];
            S[static_cast<size_t>(bi[q]) * n + bi[p]] = v;
          }
      } else {
        for (int q = 0; q < nb; ++q)
          for (int p = 0; p < nb; ++p) S[static_cast<size_t>(bi[q]) * n + bi[p]] = K[static_cast<size_t>(bi[q]) * n + bi[p]];
      }
    }
  }

  auto study = [&](const char* label, const Dense& Bx) {
    const Dense Bxt = transpose(Bx, m, n);
    const Dense F = multiply(Bx, multiply(Kp, Bxt, n, n, m), m, n, m);
    const Dense G = multiply(R, Bxt, c, n, m, true);  // R'B' (c x m)
    const Dense P = projector(G, c, m);
    const int r = m - c;
    const Dense PFP = sandwich(P, F, m);
    const Dense BBt = multiply(Bx, Bxt, m, n, m);
    const Dense BBtInv = matrixFunction(BBt, m, inv, 1e-12);
    const Dense BD = multiply(BBtInv, Bx, m, m, n);  // (BB')^-1 B
    const Dense BDt = transpose(BD, m, n);
    const Dense Ml = multiply(Bx, multiply(K, Bxt, n, n, m), m, n, m);
    const Dense MlD = multiply(BD, multiply(K, BDt, n, n, m), m, n, m);
    const Dense Md = multiply(Bx, multiply(S, Bxt, n, n, m), m, n, m);
    const Dense MdD = multiply(BD, multiply(S, BDt, n, n, m), m, n, m);
    Dense W(BBt);
    const auto bw = eig(W, m);
    std::printf("%-22s cond(BB') = %7.2f  cond(PFP) = %9.1f  lumped: %9.1f  lumped scaled: %8.1f  "
                "Dirichlet: %8.1f  Dirichlet scaled: %7.1f\n",
                label, bw[m - 1] / bw[0], condOnRange(PFP, m, r), condPreconditioned(PFP, sandwich(P, Ml, m), m, r),
                condPreconditioned(PFP, sandwich(P, MlD, m), m, r), condPreconditioned(PFP, sandwich(P, Md, m), m, r),
                condPreconditioned(PFP, sandwich(P, MdD, m), m, r));
    std::fflush(stdout);
  };
  study("B (as assembled)", B);
  // Orthonormal equality rows: B_o = (BB')^-1/2 B.
  const Dense BBt = multiply(B, Bt, m, n, m);
  const Dense T = matrixFunction(BBt, m, invSqrt, 1e-12);
  study("B_o = (BB')^-1/2 B", multiply(T, B, m, m, n));
  return 0;
}
