// Tribos_QP_Utils.hpp: pieces shared by the QP solvers: the common parameter
// list, the power method for ||A||, and the verbosity-gated output stream.
#pragma once

#include <string>

#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_ParameterList.hpp>

#include "Tribos_QP_Solver.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

// Lanczos steps of estimateNorm that reach ||A|| of the FETI duals measured
// (docs/feti.md, "The norm of the dual operator").
constexpr int kNormSteps = 10;

// Parameters every gradient-projection solver (and SMALBE) understands.
struct CommonParameters {
  SC rtol = 1e-6;
  SC atol = 0.0;
  int maxIterations = 1000;
  SC alphaBar = 1.9;       // alpha_bar = alphaBar / ||A||
  SC Gamma = 1.0;
  int powerIterations = kNormSteps;
  Verbosity verbosity = Verbosity::None;
};

// Adds "Relative Tolerance", "Absolute Tolerance", "Maximum Iterations",
// "Alpha Bar", "Gamma", "Power Iterations", "Verbosity" with validators.
void addCommonParameters(Teuchos::ParameterList& pl, const CommonParameters& defaults);
// Reads them back from a list already validated against addCommonParameters.
CommonParameters readCommonParameters(const Teuchos::ParameterList& pl);

// Upper estimate of ||A|| for SPD A: 'iterations' Lanczos steps (at most n,
// the dimension; fewer at an invariant subspace) from a rank-independent
// start, the largest Ritz value inflated by 'safety' because it approaches
// ||A|| from below.
// Every application of A increments n_A.
SC estimateNorm(const Operator& A, int iterations, long& n_A, SC safety = 1.1);

// Stream that prints only when level <= chosen verbosity.
class QPOutput {
 public:
  QPOutput();
  void setStream(RCP<Teuchos::FancyOStream> out) { out_ = out; }
  void setVerbosity(Verbosity v) { verbosity_ = v; }
  bool wants(Verbosity level) const {
    return verbosity_ != Verbosity::None && static_cast<int>(level) <= static_cast<int>(verbosity_);
  }
  Teuchos::FancyOStream& stream() { return *out_; }

 private:
  RCP<Teuchos::FancyOStream> out_;
  Verbosity verbosity_ = Verbosity::None;
};

}  // namespace QP
}  // namespace Tribos
