// Tribos_UnitTestMain.cpp: the main of every test program made of
// TEUCHOS_UNIT_TESTs (tribos_add_test(... UNIT_TESTS)): runs them all, or
// those --group-name=... or --test-name=... select, on any number of ranks.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>

#include "Tribos_ProcessStartup.hpp"

int main(int argc, char* argv[]) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  Tpetra::ScopeGuard tpetra(&argc, &argv);
  // A check that fails on one rank fails the test on every rank.
  Teuchos::UnitTestRepository::setGloballyReduceTestResult(true);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
