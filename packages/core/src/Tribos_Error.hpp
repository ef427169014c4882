// Tribos_Error.hpp: one exception type for input and setup errors, so drivers
// can print the message (which names the file, parameter or mesh entity) and
// exit cleanly instead of crashing.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace Tribos {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// An error that every rank detects identically (a decision taken on
// replicated or reduced data), so a driver can report it once and exit on
// every rank without aborting the others.
class CollectiveError : public Error {
 public:
  explicit CollectiveError(const std::string& what) : Error(what) {}
};

// A failure of the run itself rather than of its input (an output file that
// cannot be written, a disk that fills up, values that overflow), detected
// identically on every rank. Drivers exit with code 3 (docs/exit_codes.md).
class RunFailure : public CollectiveError {
 public:
  explicit RunFailure(const std::string& what) : CollectiveError(what) {}
};

}  // namespace Tribos

// TRIBOS_REQUIRE(cond, "message " << value): throws Tribos::Error when cond fails.
#define TRIBOS_REQUIRE(cond, msg)            \
  do {                                       \
    if (!(cond)) {                           \
      std::ostringstream tribos_os_;         \
      tribos_os_ << msg;                     \
      throw ::Tribos::Error(tribos_os_.str()); \
    }                                        \
  } while (0)
