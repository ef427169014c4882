// Tribos_QP_EqualityConstraint.hpp: the linear constraint G x = 0 of SMALBE,
// G mapping dual vectors to (small) coarse vectors.
#pragma once

#include "Tribos_LocalCsr.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

// G on a face of the feasible set: with Pi the orthogonal projector onto the
// free directions (every direction but a few fixed ones, each a unit
// combination of a few rows of x), the operator
//   T(u) = G'(G Pi G')^-1 G u.
// T depends on the row space of G only, so G and G with orthonormalized rows
// give the same T. u - Pi T(u) is the orthogonal projector onto
// ker(G Pi) within range Pi, and for a right-hand side r in range Pi,
// T(r - Pi A Pi y) is G'mu, the multiplier of the face problem
// (docs/semismooth.md, "The equality constraint on the face").
class FaceConstraint {
 public:
  virtual ~FaceConstraint() = default;
  // The fixed directions: one row of `fixed` per direction, its columns the
  // local rows of x (unit rows; directions on different ranks are
  // independent). Factors G Pi G'. Collective. false: G Pi G' is singular
  // (the free directions do not hold every motion that the rows of G hold).
  virtual bool setFixedDirections(const LocalCsr& fixed) = 0;
  // Tu = G'(G Pi G')^-1 G u. Collective.
  virtual void apply(const Vector& u, Vector& Tu) const = 0;
};

class EqualityConstraint {
 public:
  virtual ~EqualityConstraint() = default;
  virtual RCP<const Map> rangeMap() const = 0;
  virtual void apply(const Vector& x, Vector& Gx) const = 0;
  virtual void applyTranspose(const Vector& y, Vector& Gty) const = 0;
  // A new FaceConstraint of this G, or null when G cannot form G Pi G'.
  virtual RCP<FaceConstraint> face() const { return Teuchos::null; }
};

// G given as an explicit matrix: row map = coarse map, domain map = x map.
class CrsEqualityConstraint : public EqualityConstraint {
 public:
  explicit CrsEqualityConstraint(RCP<const CrsMatrix> G);
  RCP<const Map> rangeMap() const override;
  void apply(const Vector& x, Vector& Gx) const override;
  void applyTranspose(const Vector& y, Vector& Gty) const override;

 private:
  RCP<const CrsMatrix> G_;
};

// No constraint: G has no rows (a dual problem without G x = 0, e.g. FETI-1
// with every subdomain held by Dirichlet conditions, or FCLIB), so that the
// augmented Lagrangian of SMALBE-type loops runs unchanged with mu empty.
class NoEqualityConstraint : public EqualityConstraint {
 public:
  explicit NoEqualityConstraint(const RCP<const Comm>& comm) : map_(Teuchos::rcp(new Map(0, 0, comm))) {}
  RCP<const Map> rangeMap() const override { return map_; }
  void apply(const Vector&, Vector&) const override {}
  void applyTranspose(const Vector&, Vector& Gty) const override { Gty.putScalar(0.0); }

 private:
  RCP<const Map> map_;
};

}  // namespace QP
}  // namespace Tribos
