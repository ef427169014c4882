// Tribos_CleanupOnSignal.hpp: what a process must undo when it is told to
// end. SIGTERM, SIGINT and SIGHUP end a process at once, without running a
// destructor: a child process it started in a process group of its own and
// a temporary directory it made would outlive it (mpirun's SIGTERM, the
// Ctrl-C of the terminal, which does not reach another process group).
//
// While a CleanupOnSignal lives, each of these signals first runs its
// cleanup, then ends the process as the signal would have without it (its
// previous action restored and the signal raised again). The handler only
// writes the signal's number to a pipe; a thread of the object's own reads
// it and runs the cleanup, where any call is allowed. What cannot wait for
// that thread (mpirun kills the other ranks' processes as soon as one of
// them has died of the signal) is `urgent`, run in the handler itself: it
// may make async-signal-safe calls only. A signal the process ignores
// (nohup) stays ignored. One object at a time per process.
#pragma once

#include <signal.h>

#include <atomic>
#include <functional>
#include <thread>

namespace Tribos {

class CleanupOnSignal {
 public:
  using Urgent = void (*)(const void* context);
  explicit CleanupOnSignal(std::function<void()> cleanup, Urgent urgent = nullptr, const void* context = nullptr);
  ~CleanupOnSignal();
  CleanupOnSignal(const CleanupOnSignal&) = delete;
  CleanupOnSignal& operator=(const CleanupOnSignal&) = delete;

  // The signal that ran the cleanup, or 0: work that sees its child end
  // under it can say why instead of guessing.
  int signal() const { return received_.load(); }

 private:
  void watch();
  void restore();

  std::function<void()> cleanup_;
  int pipe_[2] = {-1, -1};
  std::atomic<int> received_{0};
  struct sigaction previous_[3];
  bool installed_[3] = {false, false, false};
  std::thread watcher_;
};

}  // namespace Tribos
