// Tribos_QP_EqualityConstraint.hpp: the linear constraint G x = 0 of SMALBE,
// G mapping dual vectors to (small) coarse vectors.
#pragma once

#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

class EqualityConstraint {
 public:
  virtual ~EqualityConstraint() = default;
  virtual RCP<const Map> rangeMap() const = 0;
  virtual void apply(const Vector& x, Vector& Gx) const = 0;
  virtual void applyTranspose(const Vector& y, Vector& Gty) const = 0;
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
