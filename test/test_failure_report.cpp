// test_failure_report.cpp: the ranks telling a failure every rank found from
// one a rank found alone (Tribos_FailureReport.hpp). When every rank fails
// within the grace time, rank 0 gets each distinct message once, with the
// ranks that gave it when they differ, and the failure is an input error only
// when every rank's was; ranks failing at different moments within the grace
// time still agree.
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>

#include <chrono>
#include <string>
#include <thread>

#include "Tribos_FailureReport.hpp"

using namespace Tribos;

namespace {

int rank() { return Teuchos::DefaultComm<int>::getComm()->getRank(); }
int size() { return Teuchos::DefaultComm<int>::getComm()->getSize(); }

TEUCHOS_UNIT_TEST(FailureReport, EveryRankAlikeIsSaidOnce) {
  FailureChannel channel(MPI_COMM_WORLD);
  const auto shared = channel.agree({"\"Material/Young's Modulus\" = 1e300", true}, 5.0);
  TEST_ASSERT(shared.everyRank);
  if (rank() == 0) {
    TEST_EQUALITY(shared.messages.size(), 1u);
    TEST_EQUALITY(shared.messages[0].first, "\"Material/Young's Modulus\" = 1e300");
    TEST_EQUALITY(shared.messages[0].second, "");  // every rank gave it
    TEST_ASSERT(shared.inputError);
  } else {
    TEST_ASSERT(shared.messages.empty());  // rank 0 alone speaks
  }
}

TEUCHOS_UNIT_TEST(FailureReport, DistinctMessagesNameTheirRanks) {
  if (size() < 2) return;
  FailureChannel channel(MPI_COMM_WORLD);
  // Rank 0 found an input error, the others a failure of the run, later.
  std::this_thread::sleep_for(std::chrono::milliseconds(100 * rank()));
  const RankFailure mine = rank() == 0 ? RankFailure{"first", true} : RankFailure{"second", false};
  const auto shared = channel.agree(mine, 5.0);
  TEST_ASSERT(shared.everyRank);
  if (rank() != 0) return;
  TEST_EQUALITY(shared.messages.size(), 2u);
  TEST_EQUALITY(shared.messages[0].first, "first");
  TEST_EQUALITY(shared.messages[0].second, "0");
  TEST_EQUALITY(shared.messages[1].first, "second");
  TEST_EQUALITY(shared.messages[1].second, size() == 2 ? "1" : "1-" + std::to_string(size() - 1));
  TEST_ASSERT(!shared.inputError);  // not every rank's failure was an input error
}

}  // namespace

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
