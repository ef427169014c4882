#include "Tribos_MueLuCG.hpp"

#include "Tribos_PreconditionedCG.hpp"

#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_Time.hpp>

#include <algorithm>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Semismooth {

MueLuCG::MueLuCG(const RCP<const CrsGraph>& graph, const Fem::ElasticityModes& modes,
                 const Teuchos::ParameterList& mueluParams, bool keepPreconditioner)
    : A_(rcp(new CrsMatrix(graph))), modes_(modes), mueluParams_(mueluParams),
      keepPreconditioner_(keepPreconditioner) {
  TRIBOS_REQUIRE(graph->isFillComplete(), "MueLuCG: the graph must be filled");
  A_->fillComplete();
  // For each value setValues() receives (owned rows in order, global columns
  // increasing), its position in the local matrix's value array.
  const auto& colMap = *graph->getColMap();
  const auto rowMap = A_->getLocalMatrixHost().graph.row_map;
  for (LO row = 0; row < static_cast<LO>(graph->getNodeNumRows()); ++row) {
    Teuchos::ArrayView<const LO> cols;
    graph->getLocalRowView(row, cols);
    std::vector<std::pair<GO, LO>> order;
    for (LO k = 0; k < cols.size(); ++k) order.emplace_back(colMap.getGlobalElement(cols[k]), k);
    std::sort(order.begin(), order.end());
    for (const auto& o : order) valuePos_.push_back(rowMap(row) + o.second);
  }
}

MueLuCG::~MueLuCG() = default;

void MueLuCG::setValues(const std::vector<double>& values, bool updatePreconditioner) {
  Teuchos::Time timer("MueLu setup");
  timer.start();
  const CrsGraph& graph = *A_->getCrsGraph();
  TRIBOS_REQUIRE(values.size() == graph.getNodeNumEntries(),
                 "MueLuCG: " << values.size() << " values for a graph of " << graph.getNodeNumEntries() << " entries");
  A_->resumeFill();
  {
    // Straight into the local matrix (host memory on the Serial node): a
    // replaceLocalValues per row searched every column.
    const auto local = A_->getLocalMatrixHost();
    for (size_t k = 0; k < values.size(); ++k) local.values(valuePos_[k]) = values[k];
  }
  A_->fillComplete();
  if (M_.is_null()) {
    M_ = Fem::mueluPreconditioner(A_, modes_, mueluParams_);
  } else if (keepPreconditioner_ || !updatePreconditioner) {
    // The hierarchy of the first matrix, unchanged; its finest level applies
    // the new values of A_ (the same object).
  } else if (mueluParams_.get<std::string>("reuse: type", "none") == "none") {
    // A fresh hierarchy (the only way to honour "reuse: type" = "none").
    M_ = Fem::mueluPreconditioner(A_, modes_, mueluParams_);
  } else {
    MueLu::ReuseTpetraPreconditioner<SC, LO, GO, Node>(A_, *M_);
  }
  timer.stop();
  setupSeconds_ += timer.totalElapsedTime();
}

int MueLuCG::solve(const Vector& b, Vector& x, double absTol, int maxIt) const {
  TRIBOS_REQUIRE(!M_.is_null(), "MueLuCG: solve() before setValues()");
  x.putScalar(0.0);
  if (b.norm2() <= absTol) return 0;
  // An absolute tolerance on the unpreconditioned residual: the caller ties
  // it to quantities (||l||, the current residual) that b does not know.
  const auto r = Fem::preconditionedCG(A_, M_, b, x, absTol, true, maxIt);
  TRIBOS_REQUIRE(r.converged, "MueLuCG: CG did not reach " << absTol << " in " << maxIt
                                                             << " steps (CG Maximum Iterations)");
  return r.iterations;
}

}  // namespace Semismooth
}  // namespace Tribos
