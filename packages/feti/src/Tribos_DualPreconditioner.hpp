// Tribos_DualPreconditioner.hpp: FETI's preconditioners of the projected dual
// operator P F P, as one Tpetra operator on the dual map,
//   M^-1 = P B_D X B_D' P,  B_D = (BB')^+ B,
// with X = K (Lumped), X = S, the Schur complements of the subdomains on
// their interface dofs (Dirichlet), or X = I with B_D = B (None is M^-1 = I;
// Lumped Unscaled is P B K B' P, for comparison only). The projected CG of
// the linear FETI solve and the Newton method of the contact problem
// (Tribos_NewtonPCG.hpp) precondition with it.
//
// The scaling (BB')^+ matters: with the non-redundant chain gluing and the
// Dirichlet rows BB' is not a multiple of the identity (cond(BB') = 32 on
// 2x2x2 subdomains), and the unscaled P B K B' P is a worse operator than
// none (cond 1970 against 82 for PFP, docs/feti.md). The right factor is
// computed on the primal side, (B'B)^+ (B'w): B'w lies in range B' to
// round-off relative to ||w||, whereas w = Pg carries round-off relative to
// ||g|| >> ||w|| along ker B' once PCG has gained a few digits, which stalls
// a dual-side solve when redundant gluing makes BB' singular.
//
// With the orthonormal gluing (the default) BB' is the identity on the
// equality rows, and (BB')^+ is taken as diag(BB')^-1 (Jacobi): exact
// there, an approximation on the contact rows, which overlap where they
// share master nodes or a slave node on an interface. The exact (BB')^+
// took 16-33 CG iterations per application on contact problems (each with
// B, B' and two reductions): ten times an application of F on the lap
// joint, for the same iterations of the Newton method's CG
// (docs/semismooth.md, "Preconditioning"). B K B' reads K only on the dofs
// B touches, K_bb (FetiProblem::applyKBoundary).
#pragma once

#include <string>
#include <vector>

#include "Tribos_FetiDual.hpp"

namespace Tribos {
namespace Feti {

class DualPreconditioner : public Operator {
 public:
  // kind: "None", "Lumped", "Dirichlet" or "Lumped Unscaled".
  DualPreconditioner(const FetiDual& dual, const std::string& kind);
  // The kinds by name, for validators.
  static const std::vector<std::string>& kinds();
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override;

 private:
  const FetiDual& dual_;
  std::string kind_;
  RCP<const Map> map_;
  mutable Vector pw_, v_, Kv_, tmp_, scaled_, y_;
  mutable std::vector<double> jacobi_;  // 1 / diag(BB') per local dual row, on first use
  void applyOne(const Vector& w, Vector& y) const;
  // v = B_D' w = B' (BB')^+ w (primal).
  void scaledTranspose(const Vector& w, Vector& v) const;
  // y = B_D u = (BB')^+ B u (dual).
  void scaled(const Vector& u, Vector& y) const;
  // x <- diag(BB')^-1 x.
  void scaleByJacobi(Vector& x) const;
};

}  // namespace Feti
}  // namespace Tribos
