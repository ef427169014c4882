// Tribos_SemismoothNewton.hpp: Coulomb friction by a semismooth Newton method
// on the Alart-Curnier function (docs/semismooth.md, "Newton for Coulomb").
//
// For a ContactDual without equality constraint, x the forces and
// v = A x - b the velocities, contact k with normal row N, tangential rows T
// (one or two), bound l_k, offset o_k, centre c_k and friction coefficient
// F_k, and rho_N, rho_T > 0:
//   tau_N = x_N - rho_N v_N,                 R = F_k max(0, tau_N + o_k)
//   Phi_N = x_N - max(l_k, tau_N)
//   z     = x_T - c_k - rho_T v_T,           Phi_T = x_T - c_k - P_{B(R)}(z)
// (P_{B(R)} the projection onto the disk of radius R; an interval for one
// tangential row), and Phi_i = rho_i v_i on every other row (free). Phi(x) = 0
// exactly when x solves the Coulomb problem. The Newton step solves
// J d = -Phi(x) with J = D_x + D_v A, an element of the generalized
// (Clarke) Jacobian: D_x, D_v block diagonal, one block per contact, from the
// case of the contact (open / closed, stick / slip); plus mu_k on the
// diagonal of the rows that D_v A makes (Levenberg-Marquardt term mu_k =
// Regularization min(1, ||Phi(x_k)|| / ||Phi(x_0)||), vanishing at the
// solution) when A is singular. The step length t is the first of 1, beta,
// beta^2, ... with psi(x + t d) <= (1 - 2 sigma t) psi(x), psi = 1/2 ||Phi||^2
// (Armijo on the merit function).
//
// Serial: the map of the dual must live on one rank. A is used as an
// explicit sparse matrix: setHessianMatrix() gives it (FCLIB problems give
// W), otherwise it is formed from n applications of dual.A (at most "Dense
// Limit" rows). The Newton systems are solved by the NewtonLinearSolver set,
// by default a dense LU (LAPACK).
#pragma once

#include <algorithm>

#include <Teuchos_ParameterList.hpp>

#include <chrono>
#include <functional>
#include <vector>

#include "Tribos_FrictionSolver.hpp"
#include "Tribos_LocalCsr.hpp"

namespace Tribos {
namespace Friction {

// Solves with the generalized Jacobian J (square, nonsymmetric). factor() is
// called once per Newton step with the same pattern each time (entries that
// vanish in a case stay stored as zeros).
class NewtonLinearSolver {
 public:
  virtual ~NewtonLinearSolver() = default;
  // Returns false when J is numerically singular (no step is taken then).
  virtual bool factor(const LocalCsr& J) = 0;
  virtual void solve(const double* b, double* x) const = 0;
  virtual std::string name() const = 0;
};

// Dense LU with partial pivoting (LAPACK getrf/getrs).
RCP<NewtonLinearSolver> denseLuSolver();

// The Alart-Curnier function of a ContactDual and its generalized Jacobian.
// rho: one value per row (rho_N on normal rows, rho_T on both tangential
// rows of a contact, rho_i on free rows).
class AlartCurnier {
 public:
  AlartCurnier(const ContactDual& dual, std::vector<double> rho);
  // Phi(x) given v = A x - b.
  void value(const std::vector<double>& x, const std::vector<double>& v, std::vector<double>& phi) const;
  // J = D_x + D_v A + mu diag(velocity rows) on a fixed pattern (A's
  // pattern merged over each contact's rows, plus the diagonal blocks).
  void jacobian(const std::vector<double>& x, const std::vector<double>& v, const LocalCsr& A, double mu,
                LocalCsr& J) const;
  const std::vector<double>& rho() const { return rho_; }
  // The same function with every contact's slip bound frozen at its value
  // R = bound + friction max(0, tau_N + offset) at (x, v), as Tresca bounds
  // (friction 0). x, v indexed by the local rows.
  AlartCurnier withSlipBoundsAt(const double* x, const double* v) const;

  // R = bound + friction max(0, tau_N + offset): Coulomb's slip bound, or
  // Tresca's given one (friction = 0).
  struct Contact {
    int normal;
    int tangent[2];
    int tangents;      // 0, 1 or 2
    double lower, offset, centre[2], friction, bound;
  };
  const std::vector<Contact>& contacts() const { return contacts_; }
  // Phi on the rows of one contact and the blocks D_x, D_v of its case
  // (m x m, m = 1 + tangents; index 0 normal, 1.. tangential), from x and
  // v indexed by the contact's rows. Every Alart-Curnier computation of
  // Tribos (this Newton method, the local solves of NSGS) goes through it.
  struct Blocks {
    double phi[3];
    double Dx[3][3], Dv[3][3];
  };
  static void blocks(const Contact& c, const double* x, const double* v, double rhoN, double rhoT, Blocks& out);
  // The slip bound R of contact c at tau_N = x_N - rho_N v_N.
  static double slipBound(const Contact& c, double tauN) { return c.bound + c.friction * std::max(0.0, tauN + c.offset); }

 private:
  std::vector<Contact> contacts_;
  std::vector<int> freeRows_;
  std::vector<double> rho_;
  int n_;
};

// Records Newton step `it` in st (history, steps: the stopping measure,
// ||G x|| relative to the measure's scale, n_A so far, the time since
// start) and on the progress line, and says whether the iteration ends
// there: a measure that is not finite, at most tol (converged), or `it`
// the last step allowed (st.reason says which).
bool newtonStepEnds(FrictionStatus& st, int it, double measure, double normGx, double tol, int maxIter,
                    std::chrono::steady_clock::time_point start);

class SemismoothNewton : public SingleLoopSolver {
 public:
  explicit SemismoothNewton(const Teuchos::ParameterList& params);
  FrictionStatus solve(const ContactDual& dual, Vector& x) override;
  static RCP<const Teuchos::ParameterList> validParameters();
  void checkDualRows(long long rows) const override;      // at most Dense Limit without an explicit matrix
  // Whether the Newton systems of a dual of that many rows are solved
  // matrix-free (Linear Solver).
  bool matrixFree(long long rows) const;

  // A of the dual as an explicit sparse matrix: dual.A = scale * A.
  void setHessianMatrix(const LocalCsr* A, double scale);
  void setLinearSolver(RCP<NewtonLinearSolver> solver) { linear_ = solver; }
  // The stopping test: measure(x, v) <= Relative Tolerance, v = A x - b of
  // the dual given to solve(). Default: ||Phi(x)|| / ||rho b|| (the
  // Alart-Curnier residual relative to the right-hand side in force units).
  // FCLIB sets the natural-map error ||F_nat|| / ||q||.
  using Measure = std::function<double(const std::vector<double>& x, const std::vector<double>& v)>;
  void setStoppingMeasure(Measure m) { measure_ = std::move(m); }

 private:
  struct NewtonSystem;
  void iterate(const NewtonSystem& sys, std::vector<double>& z, FrictionStatus& st,
               std::chrono::steady_clock::time_point start) const;

  const LocalCsr* explicitA_ = nullptr;
  double explicitScale_ = 1.0;
  RCP<NewtonLinearSolver> linear_;
  Measure measure_;
};

}  // namespace Friction
}  // namespace Tribos
