// Tribos_DirichletPreconditioner.hpp: FETI's Dirichlet preconditioner
// B S B', S per subdomain the Schur complement of K on the dofs B touches:
//   S = K_bb - K_bi K_ii^-1 K_ib   (zero on interior dofs).
#pragma once

#include <string>
#include <vector>

#include "Tribos_Assembly.hpp"
#include "Tribos_LocalSolver.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Feti {

class DirichletPreconditioner {
 public:
  // systems: this rank's subdomains (kept by reference); boundary[k]: the
  // dofs of subdomain k that B touches (ascending). Factors every K_ii;
  // throws naming the subdomain whose interior block is singular.
  DirichletPreconditioner(const std::vector<Fem::SubdomainSystem>& systems,
                          const std::vector<std::vector<int>>& boundary, const std::string& localSolver);
  // z = S p (block diagonal over the local subdomains).
  void apply(const Vector& p, Vector& z) const;

 private:
  const std::vector<Fem::SubdomainSystem>& systems_;
  std::vector<std::vector<int>> interior_;
  std::vector<RCP<LocalSolver>> Kii_;
};

}  // namespace Feti
}  // namespace Tribos
