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
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
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

// What a process does while another one cleans up: under mpirun, the
// ranks get the same signal, and mpirun kills the whole job by SIGKILL as
// soon as one rank has died; a rank that dies of the signal at once can so
// cut short rank 0's cleanup (a Gmsh child and its directory). While a
// SignalGrace lives, SIGTERM, SIGINT and SIGHUP end the process only when
// the object ends or `seconds` after the signal, whichever comes first, and
// then by the signal as before; rank 0's death, which makes mpirun end the
// job, usually comes first. A CleanupOnSignal: not beside another one.
class SignalGrace {
 public:
  explicit SignalGrace(double seconds);
  ~SignalGrace();
  SignalGrace(const SignalGrace&) = delete;
  SignalGrace& operator=(const SignalGrace&) = delete;

 private:
  void wait();

  std::chrono::duration<double> grace_;
  std::mutex mutex_;
  std::condition_variable ended_;
  bool over_ = false;
  CleanupOnSignal onSignal_;  // last: it ends first, while the above lives
};

}  // namespace Tribos
