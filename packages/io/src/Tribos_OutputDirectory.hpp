// Tribos_OutputDirectory.hpp: the directory a run writes its results to,
// checked and locked before any work, so that a run which cannot write its
// results fails at once, and two runs never write into one directory.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// The directory of a run's result files, held for the run's lifetime.
class OutputDirectory {
 public:
  // Collective over comm. Rank 0 creates `path` (and its parents), takes an
  // exclusive advisory lock (flock on path/.tribos.lock, held by an open
  // descriptor until destruction, so a killed run never leaves a stale lock),
  // probes that a file can be created and removed there, and removes the
  // temporaries that earlier killed runs left (the names temporary() makes).
  // Every rank gets the same outcome: throws Tribos::CollectiveError naming
  // the directory and the cause (a regular file in the way, permission
  // denied, "in use by another run (process P on host H)", ...).
  OutputDirectory(const std::string& path, const RCP<const Comm>& comm);
  // Releases the lock (rank 0). Not collective.
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::string& path() const { return path_; }
  // The name of the lock file inside the directory (".tribos.lock").
  static const char* lockName();
  // path/.name.<pid>.tmp, pid of rank 0: where this run writes the file
  // `name` before it is renamed to path/name. Unique to this run and
  // recognised as a leftover by the next run if this one is killed.
  std::string temporary(const std::string& name) const;
  const RCP<const Comm>& comm() const { return comm_; }

 private:
  std::string path_;
  RCP<const Comm> comm_;
  long rootPid_ = 0;
  int lockFd_ = -1;  // rank 0 only
};

// Checks before any work that `path` can be written as a file: it is not a
// directory, its directory exists, and a probe file can be created and
// removed beside it. Collective (rank 0 probes, the result is broadcast);
// throws Tribos::CollectiveError naming `what` (e.g. "--summary") and the cause.
void requireWritableFile(const std::string& path, const std::string& what, const RCP<const Comm>& comm);

// A file a run reads or writes, with the name messages give it (e.g.
// "--summary", "the input file", "the result file solution.h5").
struct RunFile {
  std::string role;
  std::string path;
  bool written = false;  // the run writes it (else reads it)
};

// Collective (rank 0 looks, every rank gets its verdict): refuses, with a
// CollectiveError naming both roles and the file, a file the run writes that
// is also another file of the list, read or written. Two files read may be
// one (harmless). Links and ".." are seen through (sameFile).
void requireDistinctFiles(const std::vector<RunFile>& files, const RCP<const Comm>& comm);

}  // namespace IO
}  // namespace Tribos
