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

}  // namespace QP
}  // namespace Tribos
