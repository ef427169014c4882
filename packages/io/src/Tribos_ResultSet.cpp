#include "Tribos_ResultSet.hpp"

#include <sys/stat.h>

#include "Tribos_Error.hpp"
#include "Tribos_FileSystem.hpp"

namespace Tribos {
namespace IO {

namespace {

// Every temporary exists and is on the device before any old file goes.
std::string checkWritten(const std::vector<std::pair<std::string, std::string>>& files) {
  for (const auto& f : files) {
    struct stat st;
    if (::stat(f.second.c_str(), &st) != 0) return fileNameOf(f.first) + " was not written (" + f.second + " is missing)";
    const std::string error = syncPath(f.second);
    if (!error.empty()) return error;
  }
  return "";
}

std::string replace(const std::vector<std::pair<std::string, std::string>>& files, const std::string& dir) {
  std::string error = checkWritten(files);
  // The old set loses its completion marker (the last file) first.
  for (auto f = files.rbegin(); error.empty() && f != files.rend(); ++f) error = removeIfExists(f->first);
  for (auto f = files.begin(); error.empty() && f != files.end(); ++f) error = renameFile(f->second, f->first);
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
    if (fileNameOf(f.first) == name) throw CollectiveError("result file " + name + " added twice");
  files_.emplace_back(dir_.path() + "/" + name, dir_.temporary(name));
  return files_.back().second;
}

void ResultSet::commit() {
  const std::string error = rootError(*comm_, comm_->getRank() == 0 ? replace(files_, dir_.path()) : "");
  if (!error.empty()) throw RunFailure("cannot replace the results in " + dir_.path() + ": " + error);
}

ResultSet::~ResultSet() {
  // After a commit nothing is left; after a failure the temporaries go, and
  // the next run of this directory would remove any that cannot be removed now.
  if (comm_->getRank() != 0) return;
  for (const auto& f : files_) removeIfExists(f.second);
}

void writeTextFile(const std::string& path, const std::string& text, const RCP<const Comm>& comm) {
  std::string error = comm->getRank() == 0 ? writeWholeFile(path, text) : "";
  if (!error.empty()) removeIfExists(path);
  error = rootError(*comm, error);
  if (!error.empty()) throw RunFailure(error);
}

}  // namespace IO
}  // namespace Tribos
