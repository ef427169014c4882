// Tribos_AllGather.hpp: every rank's vector, concatenated in rank order, on
// every rank (MPI_Allgatherv through Teuchos, so any Teuchos::Comm works).
#pragma once

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {

// Collective. Vectors of different lengths are padded to the longest for the
// exchange and compacted afterwards.
template <class T>
std::vector<T> allGatherv(const std::vector<T>& local, const Comm& comm) {
  const int size = comm.getSize();
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(size, 0);
  Teuchos::gatherAll<int, int>(comm, 1, &count, size, counts.data());
  const int longest = *std::max_element(counts.begin(), counts.end());
  std::vector<T> padded(local);
  padded.resize(static_cast<size_t>(longest));
  std::vector<T> all(static_cast<size_t>(longest) * size);
  if (longest > 0) Teuchos::gatherAll<int, T>(comm, longest, padded.data(), longest * size, all.data());
  std::vector<T> out;
  for (int r = 0; r < size; ++r)
    out.insert(out.end(), all.begin() + static_cast<size_t>(r) * longest,
               all.begin() + static_cast<size_t>(r) * longest + counts[r]);
  return out;
}

}  // namespace Tribos
