// Tribos_FileSystem.hpp: the POSIX file operations behind every output
// that is written atomically (the result set of io, the files of fclib),
// each reporting failure as a message (empty on success) that names the
// operation, the path and the system's reason, so that the message can be
// shared by all ranks before anyone throws. And the two ways ranks agree on
// an outcome: rank 0 decides, or the lowest failing rank speaks.
#pragma once

#include <string>
#include <vector>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// "No space left on device" etc. for an errno value.
std::string systemReason(int errnoValue);

// dir/.name.<pid>.tmp: a hidden name that no result file has and that
// isTemporaryName() recognises, so a later run can remove it.
std::string temporaryName(const std::string& dir, const std::string& name, long pid);
bool isTemporaryName(const std::string& fileName);
// The temporary of this process for a file about to be written at path, in
// the same directory (so that the rename onto path is atomic).
std::string temporaryPathFor(const std::string& path);
// True when both paths name the same file: the same device and inode when
// both exist, else the same path once the part that exists is resolved
// (links, "..") and the rest normalized.
bool sameFile(const std::string& a, const std::string& b);

// The names in a directory ("." and ".." aside); on failure none, and
// `error` says why.
std::vector<std::string> directoryEntries(const std::string& dir, std::string& error);

// The directory part of a path ("." when it has none) and the last component.
std::string directoryOf(const std::string& path);
std::string fileNameOf(const std::string& path);

// Creates or truncates path, writes text, flushes it to the device.
std::string writeWholeFile(const std::string& path, const std::string& text);
// Flushes a written file (or a directory, after renames in it) to the device.
std::string syncPath(const std::string& path);
// Removes a file; a file that is already gone is not an error.
std::string removeIfExists(const std::string& path);
std::string renameFile(const std::string& from, const std::string& to);

// Collective: rank 0's error on every rank. Used after steps that only rank 0 does.
std::string rootError(const Comm& comm, const std::string& errorOnRoot);
// Collective: rank 0's value on every rank.
std::string broadcastFromRoot(const Comm& comm, const std::string& value);
long broadcastFromRoot(const Comm& comm, long value);

}  // namespace Tribos
