// The natural-map error of the solutions (and guesses) stored in the shipped
// samples. They are known to be loose, so only finiteness is asserted; the
// values are printed for reference.
#include <Teuchos_UnitTestHarness.hpp>
#include <cmath>
#include <iomanip>

#include "Tribos_FCLIB_Accuracy.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos::FCLIB;
using fclib_test::Sample;

namespace {

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

void report(const std::string& label, const NaturalMapError& e, Teuchos::FancyOStream& out, bool& success) {
  std::cout << std::scientific << std::setprecision(3) << "  " << label
            << ": err/||q|| = " << e.relativeToQ << ", err/max(||q||,||r||,||u||) = "
            << e.relativeToMax << " (||phi|| = " << e.absolute << ", ||q|| = " << e.normQ
            << ", ||r|| = " << e.normR << ", ||u|| = " << e.normU << ")" << std::endl;
  if (e.normR == 0.0) std::cout << "    (the stored r is identically zero)" << std::endl;
  TEST_ASSERT(std::isfinite(e.relativeToQ));
  TEST_ASSERT(std::isfinite(e.relativeToMax));
}

void checkLocal(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::samplePath(s);
  const LocalProblem P = readLocal(path);
  std::cout << s.name << " (local)" << std::endl;
  std::vector<Solution> candidates;
  std::vector<std::string> labels;
  if (auto sol = readSolution(path)) {
    candidates.push_back(*sol);
    labels.push_back("solution");
  }
  const std::vector<Solution> guesses = readGuesses(path);
  for (std::size_t k = 0; k < guesses.size(); ++k) {
    candidates.push_back(guesses[k]);
    labels.push_back("guess " + std::to_string(k + 1));
  }
  if (candidates.empty()) std::cout << "  no stored solution" << std::endl;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Solution& c = candidates[k];
    if (c.r.empty()) continue;
    report(labels[k], naturalMapError(P, c.r), out, success);
    if (!c.u.empty()) {
      // How far the stored u is from W r + q (the measure uses the latter).
      std::vector<double> u;
      P.W.multiply(c.r, u);
      for (std::size_t i = 0; i < u.size(); ++i) u[i] += P.q[i];
      std::cout << "    max |u_stored - (W r + q)| = " << maxAbsDifference(u, c.u)
                << "; with stored u: err/||q|| = "
                << naturalMapError(c.r, c.u, P.mu, P.q).relativeToQ << std::endl;
    }
  }
}

void checkGlobal(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::samplePath(s);
  const GlobalProblem P = readGlobal(path);
  std::cout << s.name << " (global)" << std::endl;
  const auto sol = readSolution(path);
  const std::vector<Solution> guesses = readGuesses(path);
  if (!sol && guesses.empty()) {
    std::cout << "  no stored solution" << std::endl;
    return;
  }
  const fclib_test::DenseCholesky chol(P.M);
  const SolveM solve = [&](const std::vector<double>& b, std::vector<double>& x) {
    chol.solve(b, x);
  };
  auto evaluate = [&](const std::string& label, const Solution& c) {
    if (c.r.empty()) return;
    report(label, naturalMapError(P, c.r, solve), out, success);
    const GlobalReduction red = reduceGlobal(P, c.r, solve);
    if (!c.v.empty())
      std::cout << "    max |v_stored - M^-1(H r + f)| = " << maxAbsDifference(red.v, c.v)
                << std::endl;
    if (!c.u.empty())
      std::cout << "    max |u_stored - (H' v + w)| = " << maxAbsDifference(red.u, c.u)
                << std::endl;
    if (!c.u.empty() && !c.v.empty()) {
      // Checks u = H' v + w on the stored pair alone (no solve with M).
      std::vector<double> u;
      P.H.multiplyTranspose(c.v, u);
      for (std::size_t i = 0; i < u.size(); ++i) u[i] += P.w[i];
      std::cout << "    max |u_stored - (H' v_stored + w)| = " << maxAbsDifference(u, c.u)
                << " (max |u_stored| = " << maxAbsDifference(c.u, std::vector<double>(c.u.size()))
                << ")" << std::endl;
    }
    // The measure with the stored u (no reduction), for comparison.
    if (!c.u.empty())
      std::cout << "    with stored u: err/||q|| = "
                << naturalMapError(c.r, c.u, P.mu, red.q).relativeToQ << std::endl;
  };
  if (sol) evaluate("solution", *sol);
  for (std::size_t k = 0; k < guesses.size(); ++k)
    evaluate("guess " + std::to_string(k + 1), guesses[k]);
}

void checkSample(const Sample& s, Teuchos::FancyOStream& out, bool& success) {
  if (s.kind == ProblemKind::Local) checkLocal(s, out, success); else checkGlobal(s, out, success);
}

}  // namespace


FCLIB_SAMPLE_CASES(StoredSolution, checkSample)
