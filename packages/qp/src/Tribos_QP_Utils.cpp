#include "Tribos_QP_Utils.hpp"

#include <cmath>
#include <iostream>

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
  pl.set("Power Iterations", d.powerIterations, "power iterations for ||A|| (unless setHessianNorm)",
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

SC estimateNorm(const Operator& A, int iterations, long& n_A, SC safety) {
  TRIBOS_REQUIRE(iterations >= 1, "estimateNorm: Power Iterations = " << iterations << " must be >= 1");
  // A start vector that depends on the global index only, so the estimate
  // does not depend on the number of ranks.
  Vector v(A.getDomainMap()), w(A.getRangeMap());
  {
    auto vv = v.getDataNonConst();
    const auto& map = *A.getDomainMap();
    for (LO i = 0; i < static_cast<LO>(vv.size()); ++i) {
      const GO gid = map.getGlobalElement(i);
      vv[i] = 1.0 + 0.5 * std::sin(1.0 + 0.7 * static_cast<double>(gid));
    }
  }
  SC lambda = 0;
  for (int k = 0; k < iterations; ++k) {
    v.scale(1.0 / v.norm2());
    A.apply(v, w);
    ++n_A;
    lambda = w.norm2();  // ||A v|| with ||v|| = 1
    TRIBOS_REQUIRE(lambda > 0 && std::isfinite(lambda), "estimateNorm: ||A v|| = " << lambda << ": the Hessian A is zero or not finite");
    Tpetra::deep_copy(v, w);
  }
  return safety * lambda;
}

// Default: standard output, printed by rank 0 only.
QPOutput::QPOutput() : out_(Teuchos::VerboseObjectBase::getDefaultOStream()) {}

}  // namespace QP
}  // namespace Tribos
