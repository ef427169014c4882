#include "Tribos_QP_Utils.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_VerboseObject.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_QP_Status.hpp"

namespace Tribos {
namespace QP {

std::ostream& operator<<(std::ostream& os, const QPStatus& s) {
  os << (s.converged ? "converged" : "NOT converged") << " (" << s.reason << "): iterations " << s.iterations
     << " (cg " << s.cg_steps << ", expansion " << s.expansion_steps << ", proportioning " << s.proportioning_steps
     << "), n_A " << s.n_A << ", ||g^P|| " << s.norm_gP;
  if (s.outer_iterations > 0) os << ", ||Gx|| " << s.norm_Gx << ", outer iterations " << s.outer_iterations;
  return os;
}

void addCommonParameters(Teuchos::ParameterList& pl, const CommonParameters& d) {
  using Teuchos::rcp;
  auto nonneg = rcp(new Teuchos::EnhancedNumberValidator<double>(0.0, 1e300));
  auto positive = rcp(new Teuchos::EnhancedNumberValidator<double>(1e-300, 1e300));
  auto alphaRange = rcp(new Teuchos::EnhancedNumberValidator<double>(1e-12, 2.0));
  auto count = rcp(new Teuchos::EnhancedNumberValidator<int>(0, 1000000000));
  pl.set("Relative Tolerance", d.rtol, "stop at ||g^P|| <= max(rtol ||b||, atol)", nonneg);
  pl.set("Absolute Tolerance", d.atol, "stop at ||g^P|| <= max(rtol ||b||, atol)", nonneg);
  pl.set("Maximum Iterations", d.maxIterations, "iteration limit (converged = false when reached)", count);
  pl.set("Alpha Bar", d.alphaBar, "expansion step length as a multiple of 1/||A||, in (0, 2]", alphaRange);
  pl.set("Gamma", d.Gamma, "proportioning parameter: proportional when ||beta||^2 <= Gamma^2 phit'phi", positive);
  pl.set("Power Iterations", d.powerIterations, "Lanczos steps of the estimate of ||A|| (unless setHessianNorm; the name is kept from the power method)",
         rcp(new Teuchos::EnhancedNumberValidator<int>(1, 100000)));
  Teuchos::setStringToIntegralParameter<int>("Verbosity", "None", "iteration output",
                                             Teuchos::tuple<std::string>("None", "Low", "Medium", "High"),
                                             Teuchos::tuple<int>(0, 1, 2, 3), &pl);
}

CommonParameters readCommonParameters(const Teuchos::ParameterList& pl) {
  CommonParameters c;
  c.rtol = pl.get<double>("Relative Tolerance");
  c.atol = pl.get<double>("Absolute Tolerance");
  c.maxIterations = pl.get<int>("Maximum Iterations");
  c.alphaBar = pl.get<double>("Alpha Bar");
  c.Gamma = pl.get<double>("Gamma");
  c.powerIterations = pl.get<int>("Power Iterations");
  c.verbosity = static_cast<Verbosity>(Teuchos::getIntegralValue<int>(pl, "Verbosity"));
  return c;
}

namespace {

// The largest eigenvalue of the symmetric tridiagonal matrix with diagonal
// alpha and off-diagonal beta (LAPACK's implicit QL/QR).
SC largestTridiagonalEigenvalue(std::vector<SC> alpha, std::vector<SC> beta) {
  const int n = static_cast<int>(alpha.size());
  beta.resize(std::max(n, 1));
  std::vector<SC> work(std::max(1, 2 * n - 2));
  int info = 0;
  Teuchos::LAPACK<int, SC>().STEQR('N', n, alpha.data(), beta.data(), nullptr, 1, work.data(), &info);
  TRIBOS_REQUIRE(info == 0, "estimateNorm: the tridiagonal eigenvalue problem failed (LAPACK info " << info << ")");
  return *std::max_element(alpha.begin(), alpha.end());
}

}  // namespace

SC estimateNorm(const Operator& A, int iterations, long& n_A, SC safety) {
  TRIBOS_REQUIRE(iterations >= 1, "estimateNorm: Power Iterations = " << iterations << " must be >= 1");
  // A start vector that depends on the global index only, so the estimate
  // does not depend on the number of ranks.
  Vector q(A.getDomainMap()), previous(A.getDomainMap()), w(A.getRangeMap());
  {
    auto qv = q.getDataNonConst();
    const auto& map = *A.getDomainMap();
    for (LO i = 0; i < static_cast<LO>(qv.size()); ++i) {
      const GO gid = map.getGlobalElement(i);
      qv[i] = 1.0 + 0.5 * std::sin(1.0 + 0.7 * static_cast<double>(gid));
    }
  }
  q.scale(1.0 / q.norm2());
  previous.putScalar(0.0);
  // Lanczos: the largest eigenvalue theta of the tridiagonal T_k approaches
  // ||A|| from below, faster than the power method (FETI duals: 10 steps
  // give the limit of 60 power steps, where 20 power steps can still be 12 %
  // low, docs/feti.md). No reorthogonalization: its loss
  // adds copies of converged eigenvalues, never a larger one.
  // At most n steps: the Krylov space of an n x n matrix has n dimensions.
  const int steps = static_cast<int>(std::min<Tpetra::global_size_t>(iterations, A.getDomainMap()->getGlobalNumElements()));
  std::vector<SC> alpha, beta;
  for (int k = 0; k < steps; ++k) {
    A.apply(q, w);
    ++n_A;
    alpha.push_back(w.dot(q));
    TRIBOS_REQUIRE(std::isfinite(alpha.back()), "estimateNorm: q'Aq = " << alpha.back() << ": the Hessian A is not finite");
    w.update(-alpha.back(), q, k > 0 ? -beta.back() : 0.0, previous, 1.0);
    const SC b = w.norm2();
    if (!(b > 1e-12 * std::abs(alpha.back())) || k + 1 == steps) break;  // an invariant subspace, or done
    beta.push_back(b);
    Tpetra::deep_copy(previous, q);
    Tpetra::deep_copy(q, w);
    q.scale(1.0 / b);
  }
  const SC theta = largestTridiagonalEigenvalue(alpha, beta);
  TRIBOS_REQUIRE(theta > 0 && std::isfinite(theta), "estimateNorm: the largest Ritz value " << theta
                                                         << ": the Hessian A is zero or not finite");
  return safety * theta;
}

// Default: standard output, printed by rank 0 only.
QPOutput::QPOutput() : out_(Teuchos::VerboseObjectBase::getDefaultOStream()) {}

}  // namespace QP
}  // namespace Tribos
