// Tribos_Monolithic.hpp: the assembled global elasticity problem K u = f with
// Dirichlet conditions, distributed by node ownership and solved by Belos CG
// preconditioned with MueLu (rigid-body modes as near null space) or by an
// Amesos2 direct solver. It is the reference FETI is checked against.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_PreconditionedCG.hpp"
#include "Tribos_Registry.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Fem {

struct MonolithicResult {
  NodalVector u;           // at the nodes of the rank's part
  int iterations = 0;      // Belos iterations (0 for a direct solve)
  double relativeResidual = 0;
  bool converged = false;
};

// One way of solving K u = f (registered by name in monolithicSolvers()).
// Returns whether it converged; iterations: 0 for a direct solve.
class MonolithicLinearSolver {
 public:
  virtual ~MonolithicLinearSolver() = default;
  virtual bool solve(const CrsMatrix& K, const Vector& f, const ElasticityModes& modes, Vector& u,
                     const Teuchos::ParameterList& params, int& iterations) const = 0;
};
using MonolithicSolverRegistry = Registry<MonolithicLinearSolver>;
const MonolithicSolverRegistry& monolithicSolvers();

class MonolithicSystem {
 public:
  MonolithicSystem(const Mesh::Discretization& disc, const BodyMaterials& mat, const LoadCase& loads,
                   const RCP<const Comm>& comm);

  // "Linear Solver": "CG+MueLu" | "Direct"; "Tolerance"; "Maximum Iterations".
  MonolithicResult solve(const Teuchos::ParameterList& params) const;
  static RCP<const Teuchos::ParameterList> getValidParameters();

  RCP<const CrsMatrix> matrix() const { return K_; }
  // The rigid-body modes at the owned dofs (near null space of K) and the
  // coordinates of the owned nodes.
  ElasticityModes modes() const;
  RCP<const Vector> rhs() const { return f_; }
  // A vector on the owned dofs, at every node of the rank's part. Collective.
  NodalVector atPartNodes(const Vector& owned) const;

 private:
  const Mesh::Discretization& disc_;
  RCP<const Comm> comm_;
  RCP<const Map> map_, partMap_;  // dofs of the owned nodes; of the part's nodes
  RCP<const NodalLayout> layout_;  // the part's nodes
  RCP<CrsMatrix> K_;
  RCP<Vector> f_;
};

}  // namespace Fem
}  // namespace Tribos
