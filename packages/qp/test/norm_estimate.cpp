// norm_estimate.cpp: QP::estimateNorm against operators whose largest
// eigenvalue is known. A diagonal operator with its spectrum crowded towards
// the top (where the power method crawls: 20 power steps of this one stay
// 2.4 % low, 60 steps 0.8 %; 10 Lanczos steps 1.2 %) and a small dense SPD matrix, on 1 or 2 ranks.
#include "QPTestUtils.hpp"
#include "Tribos_QP_Utils.hpp"

using namespace qptest;

namespace {

// diag(d(gid)), d spread over [1, 100] with its eigenvalues crowded at 100.
class CrowdedDiagonal : public Operator {
 public:
  explicit CrowdedDiagonal(RCP<const Map> map) : map_(map) {}
  static double value(long long gid, long long n) { return 1.0 + 99.0 * std::sqrt(double(gid) / double(n - 1)); }
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    const long long n = static_cast<long long>(map_->getGlobalNumElements());
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      auto x = X.getData(j);
      auto y = Y.getDataNonConst(j);
      for (LO i = 0; i < static_cast<LO>(x.size()); ++i)
        y[i] = alpha * value(map_->getGlobalElement(i), n) * x[i] + (beta == 0.0 ? 0.0 : beta * y[i]);
    }
  }

 private:
  RCP<const Map> map_;
};

}  // namespace

TEUCHOS_UNIT_TEST(EstimateNorm, LanczosReachesTheTopOfACrowdedSpectrum) {
  auto comm = Tpetra::getDefaultComm();
  const Tpetra::global_size_t n = 20000;
  auto map = rcp(new Map(n, 0, comm));
  const CrowdedDiagonal A(map);
  const double lambdaMax = 100.0;
  long n_A = 0;
  const double theta = Tribos::QP::estimateNorm(A, Tribos::QP::kNormSteps, n_A, 1.0);
  out << "largest Ritz value after " << Tribos::QP::kNormSteps << " Lanczos steps: " << theta << "\n";
  TEST_EQUALITY(n_A, static_cast<long>(Tribos::QP::kNormSteps));
  TEST_COMPARE(theta, <=, lambdaMax * (1 + 1e-12));  // a Ritz value: from below
  TEST_COMPARE(theta, >=, 0.985 * lambdaMax);        // within 1.5 % (20 power steps: 2.4 % low)
  // With the default safety the estimate bounds ||A|| from above.
  TEST_COMPARE(Tribos::QP::estimateNorm(A, Tribos::QP::kNormSteps, n_A), >=, lambdaMax);
}

TEUCHOS_UNIT_TEST(EstimateNorm, AtMostNStepsOnASmallMatrix) {
  auto comm = Tpetra::getDefaultComm();
  const int n = 6;
  const Dense D = randomSPD(n, 7);
  // The largest eigenvalue by the power method run to convergence.
  Vec v(n, 1.0), w(n);
  double lambda = 0;
  for (int it = 0; it < 5000; ++it) {
    for (int i = 0; i < n; ++i) {
      w[i] = 0;
      for (int j = 0; j < n; ++j) w[i] += D(i, j) * v[j];
    }
    lambda = 0;
    for (double x : w) lambda += x * x;
    lambda = std::sqrt(lambda);
    for (int i = 0; i < n; ++i) v[i] = w[i] / lambda;
  }
  CountingOperator A(toCrs(pairMap(n, comm), D));
  long n_A = 0;
  const double theta = Tribos::QP::estimateNorm(A, Tribos::QP::kNormSteps, n_A, 1.0);
  out << "n = 6: " << n_A << " Lanczos steps, theta " << theta << ", lambda_max " << lambda << "\n";
  TEST_COMPARE(n_A, <=, static_cast<long>(n));
  TEST_EQUALITY(A.count, n_A);
  TEST_FLOATING_EQUALITY(theta, lambda, 1e-10);
}
