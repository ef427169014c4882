// Tribos_NewtonPCG.hpp: the semismooth Newton method of
// Tribos_SemismoothNewton.hpp on a dual of any size, matrix-free
// (docs/semismooth.md, "Newton on the FETI dual").
//
// The equality constraint G x = 0 is taken by the augmented Lagrangian with
// H = A + rho G'G and the linear term b - G'mu; mu <- mu + rho G x after
// every Newton step. For FETI, A = PAP and G'G = I - P, so H is block
// diagonal in ker G and range G' and its inverse is A^+ + (I - P) / rho: with
// FETI's preconditioner M ~ A^+ on ker G, M + (I - P) / rho preconditions H.
//
// A Newton step linearizes the Alart-Curnier function Phi (AlartCurnier::
// blocks) at x with v = H x - (b - G'mu), dropping the dependence of the
// Coulomb slip bound on the normal force within the step (the bound lags by
// one step, as in a Tresca problem whose bound is updated after every step):
// the step is then the solution of a symmetric positive definite system. In
// each contact the directions split into
//   fixed: open contact (x_N = l, x_T = c) and the radial direction z/|z|
//          of a slipping contact (x_T - c = R z/|z|): d takes the value
//          that makes Phi vanish there;
//   free:  closed normal, sticking tangents: (H d)_i = -v_i;
//          the circumferential direction w of a slipping contact:
//          w'(H d) + kappa w'd = -w'Phi / s, kappa = (1 - R/|z|) / s,
//          s = r R/|z| (the curvature of the disk's boundary);
// every other row is free. With Pi the orthogonal projector onto the free
// directions and d = d0 + y (d0 the fixed part), y solves
//   Pi (H + K) Pi y = Pi (rhs - H d0)
// by preconditioned CG (by default with the slip curvature scaling
// ||A|| (||A|| I + K)^-1), to a relative residual
// eta_k (Eisenstat-Walker, choice 2, safeguarded), and the step length comes
// from nonmonotone Armijo backtracking on psi = 1/2 ||Phi||^2, which costs no
// application of H (v is linear in x).
//
// Equality Constraint = Face Projection holds G x = 0 instead by making mu
// an unknown of each step, whose direction stays in ker G (projected CG
// with the projector onto ker(G Pi), QP::FaceConstraint). Auto takes it
// where contact rows alone hold some rigid motion (ContactDual::
// heldWithoutContact false): there mu and the contact state decide each
// other, and a mu that lags the step costs Newton steps.
//
// Stops when ||(Phi(x), G x)|| <= tol ||r b||, r = rho Factor / ||A||, the
// measure of the dense variant with one r for every row.
#pragma once

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_FrictionSolver.hpp"

namespace Tribos {
namespace Friction {

class NewtonPCG {
 public:
  // params: the "Semismooth Newton" list (validated).
  explicit NewtonPCG(const Teuchos::ParameterList& params) : params_(params) {}
  // x: start on input, solution on output (in the feasible set). warm: the
  // multiplier and penalty of a nearby problem (empty: mu = 0, the default
  // penalty); final: those of this solve.
  FrictionStatus solve(const ContactDual& dual, Vector& x, const WarmStart& warm, WarmStart& final,
                       const RCP<Teuchos::FancyOStream>& out) const;

 private:
  Teuchos::ParameterList params_;
};

}  // namespace Friction
}  // namespace Tribos
