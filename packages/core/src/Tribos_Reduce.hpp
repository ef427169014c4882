// Tribos_Reduce.hpp: a value reduced over the ranks (the largest, the sum),
// and the MPI communicator under a Teuchos one for the calls Teuchos does
// not wrap (MPI_Allreduce in place, MPI_Exscan, parallel HDF5).
#pragma once

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>

#include <mpi.h>

#include "Tribos_Types.hpp"

namespace Tribos {

// Collective: the largest v of all ranks, on every rank.
inline double maxOver(double v, const Comm& comm) {
  double out = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, v, Teuchos::outArg(out));
  return out;
}

// Collective: the sum of v over all ranks, on every rank.
inline double sumOver(double v, const Comm& comm) {
  double out = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, v, Teuchos::outArg(out));
  return out;
}

// Every Tribos communicator is a Teuchos::MpiComm (Tpetra is built with
// MPI); another kind throws std::bad_cast.
inline MPI_Comm rawComm(const Comm& comm) {
  return *dynamic_cast<const Teuchos::MpiComm<int>&>(comm).getRawMpiComm();
}

}  // namespace Tribos
