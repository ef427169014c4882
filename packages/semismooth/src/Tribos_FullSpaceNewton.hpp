// Tribos_FullSpaceNewton.hpp: the "CG+MueLu" Newton solver of semismooth*:
// K_rr is never factored. It keeps a full-space iterate u (rotated frame,
// free dofs) whose contact part is x and whose interior part is in
// equilibrium, (K u - f)_r = 0 up to a CG tolerance. Then
//     S x - l = (K u - f)_c,
// since for any u_r, (K u - f)_c - K_cr K_rr^-1 (K u - f)_r = S x - l.
// Both operations below recompute K u - f from u (never by increments), so
// errors in interior equilibrium cannot accumulate over the iteration.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <array>
#include <memory>
#include <vector>

#include "Tribos_ContactReduction.hpp"

namespace Tribos {
namespace Semismooth {

class MueLuCG;

class FullSpaceNewton {
 public:
  // Builds the MueLu hierarchy (rigid-body near null space from
  // problem.coords, rotated into the contact frames) and solves
  // u_r = K_rr^-1 f_r (x = 0), which gives l = -(K u - f)_c.
  // params: the SemismoothStarNewton list ("MueLu Smoother", "MueLu Algorithm",
  // "MueLu Reuse", "Equilibrium Tolerance", "CG Maximum Iterations").
  FullSpaceNewton(const ContactProblem& problem, const Teuchos::ParameterList& params);
  ~FullSpaceNewton();

  const RotatedSystem& system() const { return sys_; }
  const std::vector<double>& l() const { return l_; }

  // Sets the contact part of u to x and restores interior equilibrium by one
  // CG solve with K_rr for the correction of u_r, to ||(K u - f)_r|| <= absTol
  // (absTol < 0: relative "Equilibrium Tolerance" of the correction's
  // right-hand side). Returns S x - l = (K u - f)_c.
  std::vector<double> equilibrate(const std::vector<double>& x, double absTol);

  // Newton step at x^: sets the contact part of u to x^ (u_r as it is, not
  // in equilibrium) and solves N du = -(K u - f + [0; y^]) with N = K, fixed
  // contact components decoupled (only the diagonal of K left in their rows
  // and columns, du = 0 there) and G added on the tangential pair of sliding
  // nodes, to ||residual|| <= absTol. Eliminating du_r gives
  // (S_FF + G_FF) dx_F = -(S x^ - l + y^)_F for any u_r: the step also
  // restores equilibrium, so no correction solve precedes it. Then
  // u <- u + du; returns x (the new contact part) and S x - l = (K u - f)_c.
  void newtonStep(const std::vector<double>& xHat, const std::vector<char>& freeComp,
                  const std::vector<std::array<double, 4>>& G, const std::vector<double>& y, double absTol,
                  std::vector<double>& x, std::vector<double>& Sxl);

  // u in global coordinates, 3 per node, prescribed values included.
  std::vector<double> displacement() const { return sys_.globalDisplacement(u_); }

  int cgIterations() const { return cgIterations_; }
  double setupSeconds() const;  // all MueLu setups so far
  double initialSeconds() const { return initialSeconds_; }
  double cgSeconds() const { return cgSeconds_; }  // all CG solves so far

 private:
  // K u - f on the free dofs (every rank forms its rows). Collective.
  std::vector<double> residual() const;
  // u_c = x at the contact components that are free dofs.
  void setContactPart(const std::vector<double>& x);
  // Values of K on the full graph with the contact components that fixed[]
  // marks decoupled: their rows and columns keep only the diagonal of K (so
  // that the scaling the smoothers see does not change), their couplings
  // scaled by couplingScale.
  std::vector<double> graphValues(const std::vector<char>& fixed, double couplingScale = 0.0) const;
  // K_rr with a nonzero at every entry a Newton matrix may hold: the values
  // the hierarchy is built on.
  std::vector<double> firstValues() const;
  // Where this rank holds entry q (row-major 2 x 2) of the tangential block
  // of contact node i in the value array; -1 when another rank holds it or
  // a tangential direction is prescribed.
  int ownedTangentialPos(int i, int q) const;
  // A solve on the full graph with b and x given on the free dofs.
  int solve(const MueLuCG& solver, const std::vector<double>& bFree, std::vector<double>& xFree, double absTol);
  // The contact part (3 per contact node) of a vector on the free dofs, with
  // atPrescribed at the prescribed tangential directions (not free dofs).
  std::vector<double> contactPart(const std::vector<double>& vFree, const std::vector<double>& atPrescribed) const;

  RotatedSystem sys_;
  std::vector<int> fullPos_;     // position in the owned rows' value array of each Kfree entry (-1: not owned)
  std::vector<double> baseValues_;  // K on the owned rows of the full graph, prescribed dofs as unit rows
  int firstDof_ = 0, endDof_ = 0;   // owned full dofs [firstDof_, endDof_)
  int freeBegin_ = 0, freeEnd_ = 0; // their free dofs [freeBegin_, freeEnd_)
  RCP<const Map> map_, replicated_;
  RCP<const Import> gather_;
  std::unique_ptr<MueLuCG> newton_;  // the hierarchy of K_rr and the Newton matrices
  bool holdsKrr_ = false;             // whether newton_ holds K_rr now
  std::vector<double> u_, l_;    // u on the free dofs (rotated frame)
  std::vector<double> zeroAtPrescribed_;  // 3m zeros: residual entries at prescribed directions
  int maxIt_ = 0;
  double equilibriumTolerance_ = 0;
  int cgIterations_ = 0;
  double initialSeconds_ = 0, cgSeconds_ = 0;
};

}  // namespace Semismooth
}  // namespace Tribos
