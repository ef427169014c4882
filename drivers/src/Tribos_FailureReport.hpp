// Tribos_FailureReport.hpp: how a run that ends in an exception is reported
// when the ranks did not agree on the failure beforehand (a CollectiveError
// is agreed already).
//
// Two kinds of failure reach a driver this way. An error that every rank
// finds alike (the same bad number, an overflow every subdomain meets) must
// be said once, by rank 0, and end the run on every rank cleanly with its
// exit code. An error that one rank finds alone (a library failure, memory
// exhausted on one machine) leaves the other ranks waiting in a collective
// call forever: only MPI_Abort ends the run. The ranks cannot tell the two
// apart by a collective call on the run's communicator (the healthy ranks are
// inside another collective call on it), so a failing rank enters a barrier
// on a communicator of its own, made for failures only, and waits a short
// grace time for the others: if every rank fails within it, the failure is
// shared; otherwise this rank failed alone.
#pragma once

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace Tribos {

// One rank's failure: its message and whether it is an input error
// (Tribos::Error: exit 1) or a failure of the run (exit 3).
struct RankFailure {
  std::string message;
  bool inputError = false;
};

// What the ranks found together.
struct SharedFailure {
  bool everyRank = false;  // every rank failed within the grace time
  // On rank 0 when everyRank: the distinct messages, each with the ranks
  // that gave it ("" when every rank gave it), in order of first rank.
  std::vector<std::pair<std::string, std::string>> messages;
  bool inputError = false;  // every rank's failure was an input error
};

class FailureChannel {
 public:
  // Collective over `world`: the channel's own communicator (MPI_Comm_dup),
  // made at start, before any rank can fail.
  explicit FailureChannel(MPI_Comm world);
  ~FailureChannel();
  FailureChannel(const FailureChannel&) = delete;
  FailureChannel& operator=(const FailureChannel&) = delete;

  // Called by a rank whose run failed. Waits at most graceSeconds for every
  // rank to call it too; then gathers the failures on rank 0. Returns
  // everyRank = false when some rank did not fail in time: the caller
  // reports its own failure and aborts.
  SharedFailure agree(const RankFailure& mine, double graceSeconds);

  int size() const { return size_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
};

// The grace time a failing rank waits for the others: failures found alike
// happen within milliseconds of each other; a rank failing alone waits this
// long before it aborts the run.
constexpr double kFailureGraceSeconds = 5.0;

}  // namespace Tribos
