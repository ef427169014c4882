#include "Tribos_FailureReport.hpp"

#include <chrono>
#include <thread>

namespace Tribos {

namespace {

// "0, 2-4" for ranks {0, 2, 3, 4}.
std::string rankList(const std::vector<int>& ranks) {
  std::string out;
  for (size_t i = 0; i < ranks.size();) {
    size_t j = i;
    while (j + 1 < ranks.size() && ranks[j + 1] == ranks[j] + 1) ++j;
    out += (out.empty() ? "" : ", ") + std::to_string(ranks[i]);
    if (j > i) out += "-" + std::to_string(ranks[j]);
    i = j + 1;
  }
  return out;
}

}  // namespace

FailureChannel::FailureChannel(MPI_Comm world) {
  MPI_Comm_dup(world, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

FailureChannel::~FailureChannel() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

SharedFailure FailureChannel::agree(const RankFailure& mine, double graceSeconds) {
  SharedFailure shared;
  MPI_Request request;
  MPI_Ibarrier(comm_, &request);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(graceSeconds);
  int done = 0;
  for (;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  // Not every rank failed: the request stays pending, the caller aborts.
  if (!done) return shared;
  shared.everyRank = true;

  // Every rank is here: gather the messages and kinds on rank 0.
  const int length = static_cast<int>(mine.message.size());
  std::vector<int> lengths(size_), kinds(size_);
  const int kind = mine.inputError ? 1 : 0;
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, comm_);
  MPI_Gather(&kind, 1, MPI_INT, kinds.data(), 1, MPI_INT, 0, comm_);
  std::vector<int> offsets(size_, 0);
  for (int r = 1; r < size_; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
  std::string all(rank_ == 0 ? static_cast<size_t>(offsets.back() + lengths.back()) : 0, '\0');
  MPI_Gatherv(mine.message.data(), length, MPI_CHAR, rank_ == 0 ? &all[0] : nullptr, lengths.data(), offsets.data(),
              MPI_CHAR, 0, comm_);
  if (rank_ != 0) return shared;

  shared.inputError = true;
  std::vector<std::string> distinct;
  std::vector<std::vector<int>> ranks;
  for (int r = 0; r < size_; ++r) {
    shared.inputError = shared.inputError && kinds[r] == 1;
    const std::string message = all.substr(static_cast<size_t>(offsets[r]), static_cast<size_t>(lengths[r]));
    size_t k = 0;
    while (k < distinct.size() && distinct[k] != message) ++k;
    if (k == distinct.size()) distinct.push_back(message), ranks.emplace_back();
    ranks[k].push_back(r);
  }
  for (size_t k = 0; k < distinct.size(); ++k)
    shared.messages.emplace_back(distinct[k], distinct.size() == 1 ? "" : rankList(ranks[k]));
  return shared;
}

}  // namespace Tribos
