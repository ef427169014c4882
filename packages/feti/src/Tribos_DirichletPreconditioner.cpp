#include "Tribos_DirichletPreconditioner.hpp"

#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

DirichletPreconditioner::DirichletPreconditioner(const std::vector<Fem::SubdomainSystem>& systems,
                                                 const std::vector<std::vector<int>>& boundary,
                                                 const std::string& localSolver)
    : systems_(systems) {
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& sys = systems_[k];
    std::vector<int> interior;
    for (int i = 0, j = 0; i < sys.numDofs(); ++i) {
      if (j < static_cast<int>(boundary[k].size()) && boundary[k][j] == i)
        ++j;
      else
        interior.push_back(i);
    }
    const LocalCsr Kii = sys.K.principalSubmatrix(interior);
    auto solver = createLocalSolver(localSolver);
    if (Kii.rows > 0) {
      try {
        solver->factor(Kii);
      } catch (const Error& e) {
        throw Error("Dirichlet preconditioner: the interior block of subdomain " + std::to_string(sys.id) +
                    " is singular (its interface does not fix it): " + e.what());
      }
    }
    interior_.push_back(interior);
    Kii_.push_back(solver);
  }
}

void DirichletPreconditioner::apply(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  std::vector<double> x, t, w, s;
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& K = systems_[k].K;
    const auto& interior = interior_[k];
    const int n = systems_[k].numDofs(), ni = static_cast<int>(interior.size());
    // t = K [x_b; 0]; w = K_ii^-1 t_i; z_b = t_b - (K [0; w])_b; z_i = 0.
    x.assign(pv.getRawPtr() + offset, pv.getRawPtr() + offset + n);
    for (int i : interior) x[i] = 0.0;
    t.assign(n, 0.0);
    K.multiply(x.data(), t.data());
    std::vector<double> ti(ni), wi(ni);
    for (int j = 0; j < ni; ++j) ti[j] = t[interior[j]];
    if (ni > 0) Kii_[k]->solve(ti.data(), wi.data(), 1);
    w.assign(n, 0.0);
    for (int j = 0; j < ni; ++j) w[interior[j]] = wi[j];
    s.assign(n, 0.0);
    K.multiply(w.data(), s.data());
    for (int i = 0; i < n; ++i) zv[offset + i] = t[i] - s[i];
    for (int i : interior) zv[offset + i] = 0.0;
    offset += n;
  }
}

}  // namespace Feti
}  // namespace Tribos
