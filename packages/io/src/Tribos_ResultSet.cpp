#include "Tribos_ResultSet.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "Tribos_Error.hpp"
#include "Tribos_FileSystem.hpp"

namespace Tribos {
namespace IO {

namespace {

using Entry = ResultSet::Entry;

// Every temporary exists and is on the device before any old file goes.
std::string checkWritten(const std::vector<Entry>& files) {
  for (const auto& f : files) {
    if (f.temporary.empty()) continue;
    struct stat st;
    if (::stat(f.temporary.c_str(), &st) != 0)
      return fileNameOf(f.path) + " was not written (" + f.temporary + " is missing)";
    const std::string error = syncPath(f.temporary);
    if (!error.empty()) return error;
  }
  return "";
}

// Text written into an existing file at offset (its end when negative), then
// flushed: the file never goes, it only grows by the step's part.
std::string writeInto(const std::string& path, const std::string& text, long long offset) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | (offset < 0 ? O_APPEND : 0));
  if (fd < 0) return "cannot open " + path + " to extend it: " + systemReason(errno);
  std::string error;
  for (size_t done = 0; error.empty() && done < text.size();) {
    const ssize_t n = offset < 0 ? ::write(fd, text.data() + done, text.size() - done)
                                 : ::pwrite(fd, text.data() + done, text.size() - done, offset + done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) error = "cannot write " + path + ": " + systemReason(n < 0 ? errno : ENOSPC);
    else done += static_cast<size_t>(n);
  }
  if (error.empty() && ::fsync(fd) != 0) error = "cannot flush " + path + ": " + systemReason(errno);
  ::close(fd);
  return error;
}

// Files of the directory whose names `stale` accepts, removed.
std::string removeStale(const std::string& dir, const std::function<bool(const std::string&)>& stale) {
  if (!stale) return "";
  DIR* d = ::opendir(dir.c_str());
  if (!d) return "cannot list " + dir + ": " + systemReason(errno);
  std::vector<std::string> found;
  while (const dirent* e = ::readdir(d))
    if (stale(e->d_name)) found.push_back(dir + "/" + e->d_name);
  ::closedir(d);
  std::string error;
  for (auto f = found.begin(); error.empty() && f != found.end(); ++f) error = removeIfExists(*f);
  return error;
}

// removeOldFirst: the old set may be another run's, whose files the new ones
// would contradict: it loses its completion marker (the last file) first,
// then every other file, then the stale files outside it. Otherwise the old
// set is a part of the new one and each file is replaced by its rename.
std::string replace(const std::vector<Entry>& files, const std::string& dir, bool removeOldFirst,
                    const std::function<bool(const std::string&)>& stale) {
  std::string error = checkWritten(files);
  if (removeOldFirst) {
    for (auto f = files.rbegin(); error.empty() && f != files.rend(); ++f) error = removeIfExists(f->path);
    if (error.empty()) error = removeStale(dir, stale);
  }
  for (auto f = files.begin(); error.empty() && f != files.end(); ++f)
    error = f->temporary.empty() ? writeInto(f->path, f->text, f->offset) : renameFile(f->temporary, f->path);
  if (error.empty()) error = syncPath(dir);
  return error;
}

}  // namespace

ResultSet::ResultSet(const OutputDirectory& dir, const RCP<const Comm>& comm) : dir_(dir), comm_(comm) {}

std::string ResultSet::add(const std::string& name) {
  // The same names on every rank: the complaint is collective.
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw CollectiveError("result file name '" + name + "' is not a plain file name");
  for (const auto& f : files_)
    if (fileNameOf(f.path) == name) throw CollectiveError("result file " + name + " added twice");
  files_.push_back({dir_.path() + "/" + name, dir_.temporary(name), "", -1});
  return files_.back().temporary;
}

void ResultSet::append(const std::string& name, const std::string& text, long long offset) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw CollectiveError("result file name '" + name + "' is not a plain file name");
  files_.push_back({dir_.path() + "/" + name, "", text, offset});
}

void ResultSet::commit() { commitBy(true); }

void ResultSet::commitExtension() { commitBy(false); }

void ResultSet::removeAtCommit(std::function<bool(const std::string&)> stale) { stale_ = std::move(stale); }

void ResultSet::commitBy(bool removeOldFirst) {
  for (const auto& f : files_)
    if (removeOldFirst && f.temporary.empty())
      throw CollectiveError("result file " + fileNameOf(f.path) + " is extended in place, which only a set that extends the last one can do");
  const std::string error =
      rootError(*comm_, comm_->getRank() == 0 ? replace(files_, dir_.path(), removeOldFirst, stale_) : "");
  if (!error.empty()) throw RunFailure("cannot replace the results in " + dir_.path() + ": " + error);
}

ResultSet::~ResultSet() {
  // After a commit nothing is left; after a failure the temporaries go, and
  // the next run of this directory would remove any that cannot be removed now.
  if (comm_->getRank() != 0) return;
  for (const auto& f : files_)
    if (!f.temporary.empty()) removeIfExists(f.temporary);
}

void writeTextFile(const std::string& path, const std::string& text, const RCP<const Comm>& comm) {
  std::string error = comm->getRank() == 0 ? writeWholeFile(path, text) : "";
  if (!error.empty()) removeIfExists(path);
  error = rootError(*comm, error);
  if (!error.empty()) throw RunFailure(error);
}

}  // namespace IO
}  // namespace Tribos
