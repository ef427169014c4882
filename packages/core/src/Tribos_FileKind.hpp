// Tribos_FileKind.hpp: what a path is, in words, for the messages that
// refuse an input or output which is not a regular file (a FIFO would block
// a read, a device be read without end or be replaced by a rename).
#pragma once

#include <sys/stat.h>

#include <string>

namespace Tribos {

// "a regular file", "a directory", "a character device", "a block device",
// "a FIFO (named pipe)", "a socket", or "a special file", for st_mode.
inline std::string fileKind(unsigned mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

}  // namespace Tribos
