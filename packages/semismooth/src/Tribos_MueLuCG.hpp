// Tribos_MueLuCG.hpp: conjugate gradients (Belos) preconditioned by smoothed
// aggregation (MueLu) for a sequence of SPD matrices on one fixed graph. The
// first setValues() builds the hierarchy; later ones reuse it as the MueLu
// option "reuse: type" says ("RP": keep the prolongators, recompute the
// Galerkin products and the smoothers; "none": rebuild from scratch), or,
// with keepPreconditioner, keeps the first hierarchy as it is.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <vector>

#include "Tribos_PreconditionedCG.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Semismooth {

class MueLuCG {
 public:
  // graph: filled, rows distributed over the graph's communicator.
  // modes: near null space of the matrices (rigid-body modes) and the node
  // coordinates.
  MueLuCG(const RCP<const CrsGraph>& graph, const Fem::ElasticityModes& modes, const Teuchos::ParameterList& mueluParams,
          bool keepPreconditioner = false);
  ~MueLuCG();

  // New matrix values of the owned rows: row by row in the graph's local row
  // order, within a row in increasing global column order.
  // updatePreconditioner = false keeps the hierarchy as it is (for a small
  // change of the values).
  void setValues(const std::vector<double>& values, bool updatePreconditioner = true);
  // x = A^-1 b by preconditioned CG from x = 0 until ||b - A x|| <= absTol;
  // returns the number of CG steps. Throws if maxIt steps do not suffice.
  int solve(const Vector& b, Vector& x, double absTol, int maxIt) const;
  double setupSeconds() const { return setupSeconds_; }

 private:
  RCP<CrsMatrix> A_;
  std::vector<size_t> valuePos_;  // per value of setValues(): its position in the local matrix
  RCP<MueLu::TpetraOperator<SC, LO, GO, Node>> M_;
  Fem::ElasticityModes modes_;
  Teuchos::ParameterList mueluParams_;
  bool keepPreconditioner_ = false;
  double setupSeconds_ = 0;
};

}  // namespace Semismooth
}  // namespace Tribos
