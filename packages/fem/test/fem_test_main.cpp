// fem_test_main.cpp: runs every TEUCHOS_UNIT_TEST of the fem tests
// (--group-name=... or --test-name=... select some).
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>
#include "Tribos_MpiStartup.hpp"

int main(int argc, char* argv[]) {
  Tribos::prepareMpiStartup();  // before MPI_Init
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  Tpetra::ScopeGuard tpetra(&argc, &argv);
  // A check that fails on one rank fails the test on every rank.
  Teuchos::UnitTestRepository::setGloballyReduceTestResult(true);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
