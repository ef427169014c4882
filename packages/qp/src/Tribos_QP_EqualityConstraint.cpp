#include "Tribos_QP_EqualityConstraint.hpp"

#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace QP {

CrsEqualityConstraint::CrsEqualityConstraint(RCP<const CrsMatrix> G) : G_(G) {
  TRIBOS_REQUIRE(!G.is_null(), "CrsEqualityConstraint: matrix G is null");
  TRIBOS_REQUIRE(G->isFillComplete(), "CrsEqualityConstraint: matrix G must be fill-complete");
}

RCP<const Map> CrsEqualityConstraint::rangeMap() const { return G_->getRangeMap(); }

void CrsEqualityConstraint::apply(const Vector& x, Vector& Gx) const { G_->apply(x, Gx); }

void CrsEqualityConstraint::applyTranspose(const Vector& y, Vector& Gty) const { G_->apply(y, Gty, Teuchos::TRANS); }

}  // namespace QP
}  // namespace Tribos
