// Tribos_Exchange.hpp: every rank sends each other rank a list of its own
// length (MPI_Alltoallv): what a directory of nodes needs, where a rank asks
// the owners of some nodes and each owner answers only those that asked.
#pragma once

#include <Teuchos_DefaultMpiComm.hpp>

#include <mpi.h>

#include <cstring>
#include <type_traits>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// received[r] is what rank r put in its sendTo[myRank]. sendTo has one list
// per rank (comm.getSize()). T must be trivially copyable. A serial
// communicator returns sendTo itself. Collective.
template <class T>
std::vector<std::vector<T>> exchangeWithRanks(const std::vector<std::vector<T>>& sendTo, const Comm& comm) {
  static_assert(std::is_trivially_copyable<T>::value, "exchange sends raw bytes");
  const int size = comm.getSize();
  TRIBOS_REQUIRE(static_cast<int>(sendTo.size()) == size, "exchangeWithRanks: " << sendTo.size() << " lists for " << size
                                                                        << " ranks");
  if (size == 1) return sendTo;
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  TRIBOS_REQUIRE(mpi != nullptr, "exchangeWithRanks: a communicator of several ranks that is not an MPI communicator");
  const MPI_Comm raw = *mpi->getRawMpiComm();
  std::vector<int> sendBytes(size), recvBytes(size), sendOffset(size + 1, 0), recvOffset(size + 1, 0);
  for (int r = 0; r < size; ++r) sendBytes[r] = static_cast<int>(sendTo[r].size() * sizeof(T));
  MPI_Alltoall(sendBytes.data(), 1, MPI_INT, recvBytes.data(), 1, MPI_INT, raw);
  for (int r = 0; r < size; ++r) {
    sendOffset[r + 1] = sendOffset[r] + sendBytes[r];
    recvOffset[r + 1] = recvOffset[r] + recvBytes[r];
  }
  std::vector<char> out(static_cast<size_t>(sendOffset[size])), in(static_cast<size_t>(recvOffset[size]));
  for (int r = 0; r < size; ++r)
    if (sendBytes[r] > 0) std::memcpy(out.data() + sendOffset[r], sendTo[r].data(), sendBytes[r]);
  MPI_Alltoallv(out.data(), sendBytes.data(), sendOffset.data(), MPI_BYTE, in.data(), recvBytes.data(),
                recvOffset.data(), MPI_BYTE, raw);
  std::vector<std::vector<T>> received(size);
  for (int r = 0; r < size; ++r) {
    received[r].resize(recvBytes[r] / sizeof(T));
    if (recvBytes[r] > 0) std::memcpy(received[r].data(), in.data() + recvOffset[r], recvBytes[r]);
  }
  return received;
}

}  // namespace Tribos
