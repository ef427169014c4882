// friction_test_main.cpp: runs every TEUCHOS_UNIT_TEST of the friction tests
// (--group-name=MSA or --test-name=... select some), on any number of ranks.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>
#include "Tribos_MpiStartup.hpp"

int main(int argc, char* argv[]) {
  Tribos::prepareMpiStartup();  // before MPI_Init
  Teuchos::GlobalMPISession mpi(&argc, &argv);
  Tpetra::ScopeGuard tpetra(&argc, &argv);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
