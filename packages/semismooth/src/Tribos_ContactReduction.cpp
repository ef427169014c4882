#include "Tribos_ContactReduction.hpp"


#include <Teuchos_Time.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "Tribos_ArrayScan.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_RigidMotions.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

// A LocalSolver on a fixed pattern: the first factor() analyses and factors,
// later ones refactor numerically (CHOLMOD keeps its symbolic analysis).
class LocalPatternSolver : public PatternSolver {
 public:
  LocalPatternSolver(const std::string& name, const LocalCsr& pattern)
      : A_(pattern), solver_(createLocalSolver(name)) {}
  void factor(const std::vector<double>& values) override {
    A_.val = values;
    if (factored_) solver_->refactor(A_);
    else solver_->factor(A_);
    factored_ = true;
  }
  void solve(const double* b, double* x, int nrhs) const override { solver_->solve(b, x, nrhs); }

 private:
  LocalCsr A_;
  RCP<LocalSolver> solver_;
  bool factored_ = false;
};

// Columns (t1, t2 = n x t1, n) of the rotation of a contact frame, row-major.
std::array<double, 9> frameMatrix(const std::array<double, 3>& n, const std::array<double, 3>& t1) {
  const Vec3 t2 = cross(n, t1);
  std::array<double, 9> R{};
  for (int a = 0; a < 3; ++a) {
    R[3 * a + 0] = t1[a];
    R[3 * a + 1] = t2[a];
    R[3 * a + 2] = n[a];
  }
  return R;
}

// Orthonormal frame (t1, t2, n) with n the normalized outward normal: the
// tangents of the FETI contact rows (Feti::tangents), so that a node's
// tangential forces and slip have the same components whichever method
// solved it.
std::array<double, 9> tangentFrame(const std::array<double, 3>& normal) {
  TRIBOS_REQUIRE(norm(normal) > 0, "contact node with a zero normal");
  const Vec3 n = normalized(normal);
  std::array<double, 3> t1, t2;
  Feti::tangents(n, t1, t2);
  return frameMatrix(n, t1);
}

// The frame of a contact node whose prescribed global components (fixed)
// are tangent directions: t1 = the first fixed axis, t2 = n x t1 (the
// second fixed axis, if any, up to its sign), n with its (round-off sized)
// components along the fixed axes removed, so that each fixed axis is
// exactly a frame vector and its prescribed value stays exact in the frame.
std::array<double, 9> prescribedTangentFrame(const std::array<double, 3>& normal, const std::array<bool, 3>& fixed) {
  std::array<double, 3> n = normal;
  for (int c = 0; c < 3; ++c)
    if (fixed[c]) n[c] = 0;
  n = normalized(n);
  const int c1 = fixed[0] ? 0 : (fixed[1] ? 1 : 2);
  std::array<double, 3> t1{0, 0, 0};
  t1[c1] = 1;
  return frameMatrix(n, t1);
}

// K~ = Q' K Q with Q = diag(R_I) (identity on nodes without a frame). K must
// have the node-block structure of an elasticity matrix: the three rows of a
// node share their columns, which come in complete node triples.
LocalCsr rotate(const LocalCsr& K, const std::vector<const std::array<double, 9>*>& R) {
  const int N = K.rows / 3;
  LocalCsr Kt = K;
  for (int I = 0; I < N; ++I) {
    const int len = K.rowptr[3 * I + 1] - K.rowptr[3 * I];
    for (int p = 0; p < 3; ++p)
      TRIBOS_REQUIRE(K.rowptr[3 * I + p + 1] - K.rowptr[3 * I + p] == len && len % 3 == 0,
                     "semismooth*: K must consist of full 3x3 node blocks (row " << 3 * I + p << ")");
    for (int k = 0; k < len; k += 3) {
      const int J = K.col[K.rowptr[3 * I] + k] / 3;
      if (!R[I] && !R[J]) continue;
      double B[3][3], C[3][3];
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) {
          const int pos = K.rowptr[3 * I + p] + k + q;
          TRIBOS_REQUIRE(K.col[pos] == 3 * J + q, "semismooth*: K must consist of full 3x3 node blocks");
          B[p][q] = K.val[pos];
        }
      for (int p = 0; p < 3; ++p)  // C = B R_J
        for (int b = 0; b < 3; ++b) {
          double s = 0;
          for (int q = 0; q < 3; ++q) s += B[p][q] * (R[J] ? (*R[J])[3 * q + b] : double(q == b));
          C[p][b] = s;
        }
      for (int a = 0; a < 3; ++a)  // R_I' C
        for (int b = 0; b < 3; ++b) {
          double s = 0;
          for (int p = 0; p < 3; ++p) s += (R[I] ? (*R[I])[3 * p + a] : double(p == a)) * C[p][b];
          Kt.val[K.rowptr[3 * I + a] + k + b] = s;
        }
    }
  }
  return Kt;
}

}  // namespace

PrescribedDirections classifyPrescribed(const std::array<double, 3>& normal, const std::array<bool, 3>& fixed) {
  const double len = norm(normal);
  TRIBOS_REQUIRE(len > 0, "contact node with a zero normal");
  // Area-weighted normals of planar faces are exact up to round-off.
  const double tol = 1e-8;
  bool any = false, allTangent = true;
  double outside = 0;  // |n|^2 off the prescribed axes
  for (int c = 0; c < 3; ++c) {
    const double nc = normal[c] / len;
    if (fixed[c]) {
      any = true;
      allTangent = allTangent && std::abs(nc) <= tol;
    } else {
      outside += nc * nc;
    }
  }
  if (!any) return PrescribedDirections::None;
  if (outside <= tol * tol) return PrescribedDirections::Normal;
  return allTangent ? PrescribedDirections::Tangential : PrescribedDirections::Oblique;
}

std::unique_ptr<PatternSolver> createPatternSolver(const std::string& name, const LocalCsr& pattern) {
  return std::make_unique<LocalPatternSolver>(name, pattern);
}

RotatedSystem::RotatedSystem(const ContactProblem& p) : numNodes(p.numNodes()), m(static_cast<int>(p.contact.size())), contact(p.contact) {
  const int n = 3 * numNodes;
  TRIBOS_REQUIRE(p.K.rows == n && p.K.cols == n && static_cast<int>(p.f.size()) == n,
                 "semismooth*: K is " << p.K.rows << " x " << p.K.cols << ", f has " << p.f.size() << " entries");
  TRIBOS_REQUIRE(m > 0, "semismooth*: no contact nodes");
  TRIBOS_REQUIRE(static_cast<int>(p.coords.size()) == numNodes,
                 "semismooth*: ContactProblem::coords must hold the node coordinates (" << p.coords.size() << " for "
                                                                                         << numNodes << " nodes)");
  // Before any factorization: K on the unprescribed dofs must be definite.
  Fem::requireRigidMotionsHeld(p.coords, p.dirichlet, "semismooth*", kSemicoerciveAdvice);

  // Prescribed values by dof; at contact nodes they move into the frame below.
  uPrescribed.assign(n, 0.0);
  std::vector<char> isPrescribed(n, 0);
  for (const auto& [dof, value] : p.dirichlet) {
    TRIBOS_REQUIRE(dof >= 0 && dof < n, "semismooth*: Dirichlet dof " << dof << " out of range");
    isPrescribed[dof] = 1;
    uPrescribed[dof] = value;
  }

  // Frames and the reduced numbering x = (x_1, ..., x_m), x_i = (tau1, tau2, nu).
  std::vector<const std::array<double, 9>*> R(numNodes, nullptr);
  frame.resize(m);
  prescribed.assign(3 * m, 0);
  xPrescribed.assign(3 * m, 0.0);
  std::vector<int> reducedOfDof(n, -1);
  for (int i = 0; i < m; ++i) {
    const int node = contact[i].node;
    TRIBOS_REQUIRE(node >= 0 && node < numNodes, "semismooth*: contact node " << node << " out of range");
    TRIBOS_REQUIRE(reducedOfDof[3 * node] < 0, "semismooth*: contact node " << node << " listed twice");
    TRIBOS_REQUIRE(contact[i].g >= 0, "semismooth*: negative slip bound at node " << node);
    const std::array<bool, 3> fixed{isPrescribed[3 * node] != 0, isPrescribed[3 * node + 1] != 0,
                                    isPrescribed[3 * node + 2] != 0};
    const PrescribedDirections kind = classifyPrescribed(contact[i].normal, fixed);
    TRIBOS_REQUIRE(kind != PrescribedDirections::Normal,
                   "semismooth*: contact node " << node << " has its normal displacement prescribed; exclude it from contact");
    TRIBOS_REQUIRE(kind != PrescribedDirections::Oblique,
                   "semismooth*: contact node " << node << " has a Dirichlet condition on a component that is neither its "
                                                "normal nor a tangent direction (oblique); the contact frame cannot "
                                                "represent it");
    if (kind == PrescribedDirections::None) {
      frame[i] = tangentFrame(contact[i].normal);
    } else {
      // Each fixed axis is a tangent frame vector (+-e_c exactly): its value
      // in the frame is that frame vector's sign times the prescribed value.
      frame[i] = prescribedTangentFrame(contact[i].normal, fixed);
      double u[3];
      for (int c = 0; c < 3; ++c) u[c] = uPrescribed[3 * node + c];
      for (int k = 0; k < 3; ++k) {
        isPrescribed[3 * node + k] = 0;
        uPrescribed[3 * node + k] = 0;
      }
      for (int c = 0; c < 3; ++c)
        if (fixed[c]) {
          const int k = std::abs(frame[i][3 * c]) > 0.5 ? 0 : 1;
          isPrescribed[3 * node + k] = 1;
          uPrescribed[3 * node + k] = frame[i][3 * c + k] * u[c];
          prescribed[3 * i + k] = 1;
          xPrescribed[3 * i + k] = uPrescribed[3 * node + k];
        }
    }
    for (int k = 0; k < 3; ++k) reducedOfDof[3 * node + k] = 3 * i + k;
  }
  for (int i = 0; i < m; ++i) R[contact[i].node] = &frame[i];
  const LocalCsr Kt = rotate(p.K, R);
  std::vector<double> ft = p.f;
  for (int i = 0; i < m; ++i) {
    const double* fi = &p.f[3 * contact[i].node];
    for (int k = 0; k < 3; ++k)
      ft[3 * contact[i].node + k] = frame[i][k] * fi[0] + frame[i][3 + k] * fi[1] + frame[i][6 + k] * fi[2];
  }

  // Free dofs in natural order (keeps CSR columns sorted).
  freeOfDof.assign(n, -1);
  for (int dof = 0; dof < n; ++dof) {
    if (isPrescribed[dof]) continue;
    freeOfDof[dof] = static_cast<int>(dofOfFree.size());
    dofOfFree.push_back(dof);
  }
  const int nf = static_cast<int>(dofOfFree.size());
  reducedOfFree.assign(nf, -1);
  freeOfReduced.assign(3 * m, -1);
  for (int j = 0; j < nf; ++j) {
    reducedOfFree[j] = reducedOfDof[dofOfFree[j]];
    if (reducedOfFree[j] >= 0) freeOfReduced[reducedOfFree[j]] = j;
  }

  // K~ on the free dofs; prescribed values move to the right-hand side.
  Kfree.rows = Kfree.cols = nf;
  Kfree.rowptr.assign(1, 0);
  fFree.assign(nf, 0.0);
  for (int j = 0; j < nf; ++j) {
    const int dof = dofOfFree[j];
    fFree[j] = ft[dof];
    for (int pos = Kt.rowptr[dof]; pos < Kt.rowptr[dof + 1]; ++pos) {
      const int c = freeOfDof[Kt.col[pos]];
      if (c >= 0) {
        Kfree.col.push_back(c);
        Kfree.val.push_back(Kt.val[pos]);
      } else {
        fFree[j] -= Kt.val[pos] * uPrescribed[Kt.col[pos]];
      }
    }
    Kfree.rowptr.push_back(static_cast<int>(Kfree.col.size()));
  }
  tangentialEntries.assign(m, {-1, -1, -1, -1});
  for (int i = 0; i < m; ++i) {
    if (prescribed[3 * i] || prescribed[3 * i + 1]) continue;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const int row = freeOfReduced[3 * i + a], col = freeOfReduced[3 * i + b];
        auto first = Kfree.col.begin() + Kfree.rowptr[row], last = Kfree.col.begin() + Kfree.rowptr[row + 1];
        tangentialEntries[i][2 * a + b] = static_cast<int>(std::lower_bound(first, last, col) - Kfree.col.begin());
      }
  }
}

std::vector<double> RotatedSystem::nodalMaxDiagonalKcc() const {
  std::vector<double> dmax(m, 0.0);
  for (int j = 0; j < 3 * m; ++j) {
    const int row = freeOfReduced[j];
    if (row < 0) continue;
    for (int pos = Kfree.rowptr[row]; pos < Kfree.rowptr[row + 1]; ++pos)
      if (Kfree.col[pos] == row) dmax[j / 3] = std::max(dmax[j / 3], Kfree.val[pos]);
  }
  return dmax;
}

std::vector<double> RotatedSystem::diagonalKcc() const {
  std::vector<double> diag(3 * m, 0.0);
  for (int j = 0; j < 3 * m; ++j) {
    const int row = freeOfReduced[j];
    if (row < 0) continue;
    for (int pos = Kfree.rowptr[row]; pos < Kfree.rowptr[row + 1]; ++pos)
      if (Kfree.col[pos] == row) diag[j] = Kfree.val[pos];
  }
  return diag;
}

std::vector<double> RotatedSystem::globalDisplacement(const std::vector<double>& vFree) const {
  std::vector<double> u = uPrescribed;
  for (size_t j = 0; j < dofOfFree.size(); ++j) u[dofOfFree[j]] = vFree[j];
  for (int i = 0; i < m; ++i) {  // u_i = R_i x_i
    const int node = contact[i].node;
    double xi[3];
    for (int k = 0; k < 3; ++k) xi[k] = prescribed[3 * i + k] ? xPrescribed[3 * i + k] : vFree[freeOfReduced[3 * i + k]];
    for (int a = 0; a < 3; ++a)
      u[3 * node + a] = frame[i][3 * a] * xi[0] + frame[i][3 * a + 1] * xi[1] + frame[i][3 * a + 2] * xi[2];
  }
  return u;
}

ContactReduction::ContactReduction(const ContactProblem& p, const std::string& localSolver)
    : sys_(p), solverName_(localSolver) {
  Teuchos::Time timer("reduction");
  timer.start();
  const int nf = sys_.Kfree.rows;
  // K_rr, padded with the identity on the contact dofs so that it shares the
  // pattern (and the symbolic analysis) with the Newton matrices.
  std::vector<double> vals = sys_.Kfree.val;
  for (int j = 0; j < nf; ++j)
    for (int pos = sys_.Kfree.rowptr[j]; pos < sys_.Kfree.rowptr[j + 1]; ++pos)
      if (sys_.reducedOfFree[j] >= 0 || sys_.reducedOfFree[sys_.Kfree.col[pos]] >= 0) vals[pos] = (sys_.Kfree.col[pos] == j) ? 1.0 : 0.0;
  Krr_ = createPatternSolver(solverName_, sys_.Kfree);
  Krr_->factor(vals);

  // l = f_c - K_cr K_rr^-1 f_r.
  std::vector<double> rhs = sys_.fFree;
  for (int j = 0; j < nf; ++j)
    if (sys_.reducedOfFree[j] >= 0) rhs[j] = 0;
  krrSolve(rhs, zf_);
  std::vector<double> t;
  multiplyFree(zf_, t);
  l_.assign(3 * sys_.m, 0.0);
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) l_[j] = sys_.fFree[sys_.freeOfReduced[j]] - t[sys_.freeOfReduced[j]];
  timer.stop();
  reductionSeconds_ = timer.totalElapsedTime();
}

ContactReduction::~ContactReduction() = default;

void ContactReduction::krrSolve(const std::vector<double>& rhsFree, std::vector<double>& zFree) const {
  zFree.resize(rhsFree.size());
  Krr_->solve(rhsFree.data(), zFree.data(), 1);
}

void ContactReduction::multiplyFree(const std::vector<double>& v, std::vector<double>& y) const {
  y.resize(sys_.Kfree.rows);
  sys_.Kfree.multiply(v.data(), y.data());
}

void ContactReduction::applyS(const std::vector<double>& x, std::vector<double>& Sx) const {
  const int nf = sys_.Kfree.rows;
  std::vector<double> v(nf, 0.0), t, z;
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) v[sys_.freeOfReduced[j]] = x[j];
  multiplyFree(v, t);  // t_r = K_rc x
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) t[sys_.freeOfReduced[j]] = 0;
  krrSolve(t, z);  // z_r = K_rr^-1 K_rc x, z_c = 0
  for (int j = 0; j < nf; ++j)
    if (sys_.reducedOfFree[j] < 0) v[j] = -z[j];
  multiplyFree(v, t);  // t_c = K_cc x - K_cr z_r
  Sx.assign(3 * sys_.m, 0.0);
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) Sx[j] = t[sys_.freeOfReduced[j]];
}

std::vector<double> ContactReduction::denseS() const {
  const int nc = 3 * sys_.m;
  std::vector<double> S(static_cast<size_t>(nc) * nc), e(nc, 0.0), col;
  for (int j = 0; j < nc; ++j) {
    e[j] = 1;
    applyS(e, col);
    std::copy(col.begin(), col.end(), S.begin() + static_cast<size_t>(j) * nc);
    e[j] = 0;
  }
  return S;
}

void ContactReduction::newtonSolve(const std::vector<char>& freeComp, const std::vector<std::array<double, 4>>& G,
                                   const std::vector<double>& rhs, std::vector<double>& dx, std::vector<double>& Sdx) {
  for (int j = 0; j < 3 * sys_.m; ++j)
    TRIBOS_REQUIRE(!(freeComp[j] && sys_.prescribed[j]), "semismooth*: a prescribed direction cannot be free in a Newton step");
  Teuchos::Time timer("newton factor");
  timer.start();
  const int nf = sys_.Kfree.rows;
  // Fixed contact components are decoupled (unit row and column), so the
  // pattern stays that of K~_free.
  std::vector<double> vals = sys_.Kfree.val;
  auto fixed = [&](int j) { return sys_.reducedOfFree[j] >= 0 && !freeComp[sys_.reducedOfFree[j]]; };
  for (int j = 0; j < nf; ++j)
    for (int pos = sys_.Kfree.rowptr[j]; pos < sys_.Kfree.rowptr[j + 1]; ++pos)
      if (fixed(j) || fixed(sys_.Kfree.col[pos])) vals[pos] = (sys_.Kfree.col[pos] == j) ? 1.0 : 0.0;
  for (int i = 0; i < sys_.m; ++i)
    if (freeComp[3 * i] && freeComp[3 * i + 1])
      for (int q = 0; q < 4; ++q) vals[sys_.tangentialEntries[i][q]] += G[i][q];
  if (!newton_) newton_ = createPatternSolver(solverName_, sys_.Kfree);
  newton_->factor(vals);
  timer.stop();
  newtonFactorSeconds_ += timer.totalElapsedTime();

  std::vector<double> b(nf, 0.0), v(nf), t;
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (freeComp[j]) b[sys_.freeOfReduced[j]] = rhs[j];
  newton_->solve(b.data(), v.data(), 1);
  dx.assign(3 * sys_.m, 0.0);
  for (int j = 0; j < 3 * sys_.m; ++j) dx[j] = freeComp[j] ? v[sys_.freeOfReduced[j]] : 0.0;
  // The r-rows give v_r = -K_rr^-1 K_rF dx_F, hence (K~ v)_c = S dx.
  multiplyFree(v, t);
  Sdx.assign(3 * sys_.m, 0.0);
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) Sdx[j] = t[sys_.freeOfReduced[j]];
}

std::vector<double> ContactReduction::displacement(const std::vector<double>& x) const {
  const int nf = sys_.Kfree.rows;
  std::vector<double> v(nf, 0.0), t, ur;
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) v[sys_.freeOfReduced[j]] = x[j];
  multiplyFree(v, t);
  for (int j = 0; j < nf; ++j) t[j] = sys_.reducedOfFree[j] >= 0 ? 0.0 : sys_.fFree[j] - t[j];
  krrSolve(t, ur);
  for (int j = 0; j < nf; ++j)
    if (sys_.reducedOfFree[j] < 0) v[j] = ur[j];
  return sys_.globalDisplacement(v);
}

}  // namespace Semismooth
}  // namespace Tribos
