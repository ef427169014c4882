// test_reduce.cpp: maxOver, sumOver and rawComm of Tribos_Reduce.hpp on
// every rank count the test runs with: each rank's own value, the result the
// same on every rank, and the MPI communicator the same group.
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_UnitTestRepository.hpp>

#include "Tribos_Reduce.hpp"

namespace {

TEUCHOS_UNIT_TEST(Reduce, MaxAndSumOverRanks) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const int p = comm->getSize(), r = comm->getRank();
  // Rank r holds -(r - 1)^2 + 0.5: the largest is rank 1's when there is one.
  const double mine = -double(r - 1) * (r - 1) + 0.5;
  TEST_EQUALITY(Tribos::maxOver(mine, *comm), p > 1 ? 0.5 : -0.5);
  double sum = 0;
  for (int k = 0; k < p; ++k) sum += -double(k - 1) * (k - 1) + 0.5;
  TEST_EQUALITY(Tribos::sumOver(mine, *comm), sum);
  TEST_EQUALITY(Tribos::maxOver(-1e300, *comm), -1e300);
}

TEUCHOS_UNIT_TEST(Reduce, RawCommIsTheSameGroup) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const MPI_Comm raw = Tribos::rawComm(*comm);
  int size = 0, rank = -1;
  MPI_Comm_size(raw, &size);
  MPI_Comm_rank(raw, &rank);
  TEST_EQUALITY(size, comm->getSize());
  TEST_EQUALITY(rank, comm->getRank());
  int one = 1, all = 0;
  MPI_Allreduce(&one, &all, 1, MPI_INT, MPI_SUM, raw);
  TEST_EQUALITY(all, comm->getSize());
}

}  // namespace

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
