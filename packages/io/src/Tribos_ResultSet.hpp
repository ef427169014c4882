// Tribos_ResultSet.hpp: the files of one result (HDF5 data, XDMF index,
// summary) replaced as a set. They are written under temporary names and
// renamed together at commit(), the summary last: a directory holds either
// one run's complete set, or part of the new set without its summary, never
// a new data file beside an old summary.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_OutputDirectory.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// The files of one result, written under temporary names and replaced as a set.
class ResultSet {
 public:
  // dir must outlive the set (it holds the directory's lock).
  ResultSet(const OutputDirectory& dir, const RCP<const Comm>& comm);
  ResultSet(const ResultSet&) = delete;
  ResultSet& operator=(const ResultSet&) = delete;

  // The temporary path to write the file `name` (a plain file name, no
  // directory) to; it becomes dir/name at commit(). Add the summary, the
  // marker of a complete set, last.
  std::string add(const std::string& name);

  // For commitExtension() only: at the commit, in the order of add() and
  // append() calls, rank 0 writes `text` into the existing file dir/name at
  // byte `offset` (its end when offset < 0) and flushes it. The files a set
  // extends step by step (a history's rows, an index's closing tags
  // overwritten by the next step and the tags again) grow by what the step
  // adds: a step's commit costs the same at step 10 and at step 10^5. Not
  // collective; call it on every rank alike (rank 0's text is written).
  void append(const std::string& name, const std::string& text, long long offset = -1);

  // Collective. Rank 0 checks that every temporary was written and flushes it
  // to the device, removes the old files of the set (the last-added one, the
  // summary, first), then renames the temporaries in the order added, the
  // last one last, and flushes the directory: what is in the directory is
  // always either one run's complete set or a subset of the new one without
  // its summary. Failure on rank 0 -> every rank throws Tribos::RunFailure.
  void commit();

  // Files of an earlier result under other names than this set's that must
  // not survive beside it (the data files of a time series of more steps, or
  // of one step): at commit(), once the old set's files are removed and
  // before the new ones are renamed, rank 0 removes every file of the
  // directory whose name `stale` accepts. Temporaries never match (their
  // names are hidden). Not collective; call it on every rank alike.
  void removeAtCommit(std::function<bool(const std::string& fileName)> stale);

  // Collective, for a set that extends the one this run committed before
  // (the next step of a time series, whose earlier files stay true): rank 0
  // checks the temporaries as commit() does, then renames each over its
  // final name in the order added, the summary last, and removes nothing:
  // the directory never lacks a summary, and the one it holds (the previous
  // or this set's) describes files that are all complete. Failure on rank 0
  // -> every rank throws Tribos::RunFailure.
  void commitExtension();

  // Removes (rank 0) the temporaries that were not committed: error paths,
  // exceptions. Not collective.
  ~ResultSet();

  // In commit order: a file renamed from its temporary, or text written into it.
  struct Entry {
    std::string path, temporary;  // temporary empty: an edit in place
    std::string text;
    long long offset = -1;
  };

 private:
  void commitBy(bool removeOldFirst);

  const OutputDirectory& dir_;
  RCP<const Comm> comm_;
  std::vector<Entry> files_;
  std::function<bool(const std::string&)> stale_;
};

// Collective: rank 0 writes text to path (e.g. a temporary of a ResultSet) and
// flushes it; every rank throws Tribos::RunFailure if that failed.
void writeTextFile(const std::string& path, const std::string& text, const RCP<const Comm>& comm);

}  // namespace IO
}  // namespace Tribos
