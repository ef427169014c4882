// Tribos_AgreeOnError.hpp: ranks agreeing on a failure that some of them
// found alone (a check of rank-local data), so that every rank throws the
// same CollectiveError instead of the others waiting forever in the next
// collective call.
#pragma once

#include <Teuchos_CommHelpers.hpp>

#include <string>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// Collective: the error of the lowest rank that has one, on every rank ("" if
// no rank failed).
inline std::string agreeOnError(const Comm& comm, const std::string& localError) {
  const int size = comm.getSize();
  int mine = localError.empty() ? size : comm.getRank(), first = size;
  Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(first));
  if (first == size) return "";
  std::string message = localError;
  int length = static_cast<int>(message.size());
  Teuchos::broadcast<int, int>(comm, first, Teuchos::outArg(length));
  message.resize(static_cast<size_t>(length));
  if (length > 0) Teuchos::broadcast<int, char>(comm, first, length, &message[0]);
  return message;
}

// Collective: runs check(), which may throw Tribos::Error on some ranks;
// then every rank throws CollectiveError with the lowest failing rank's
// message, or none does.
template <class Check>
void checkOnEveryRank(const Comm& comm, Check&& check) {
  std::string error;
  try {
    check();
  } catch (const Error& e) {
    error = e.what();
  }
  error = agreeOnError(comm, error);
  if (!error.empty()) throw CollectiveError(error);
}

}  // namespace Tribos
