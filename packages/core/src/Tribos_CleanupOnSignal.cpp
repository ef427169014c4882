#include "Tribos_CleanupOnSignal.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#include "Tribos_Error.hpp"

namespace Tribos {

namespace {

constexpr int kSignals[3] = {SIGTERM, SIGINT, SIGHUP};

// The write end of the live object's pipe, read by the handler (a
// lock-free atomic: async-signal-safe).
std::atomic<int> writeEnd{-1};
std::atomic<CleanupOnSignal::Urgent> urgentWork{nullptr};
std::atomic<const void*> urgentContext{nullptr};

void onSignal(int sig) {
  const int saved = errno;
  const CleanupOnSignal::Urgent urgent = urgentWork.exchange(nullptr);
  if (urgent) urgent(urgentContext.load());
  const int fd = writeEnd.load();
  const unsigned char byte = static_cast<unsigned char>(sig);
  if (fd >= 0 && ::write(fd, &byte, 1) < 0) {
  }
  errno = saved;
}

}  // namespace

CleanupOnSignal::CleanupOnSignal(std::function<void()> cleanup, Urgent urgent, const void* context)
    : cleanup_(std::move(cleanup)) {
  TRIBOS_REQUIRE(::pipe2(pipe_, O_CLOEXEC) == 0, "cannot create a pipe for the signal handler: " << std::strerror(errno));
  int expected = -1;
  if (!writeEnd.compare_exchange_strong(expected, pipe_[1])) {
    ::close(pipe_[0]);
    ::close(pipe_[1]);
    throw Error("CleanupOnSignal: another one is alive in this process");
  }
  urgentContext.store(context);
  urgentWork.store(urgent);
  watcher_ = std::thread([this] { watch(); });
  for (int k = 0; k < 3; ++k) {
    if (::sigaction(kSignals[k], nullptr, &previous_[k]) != 0) continue;
    const bool ignored = !(previous_[k].sa_flags & SA_SIGINFO) && previous_[k].sa_handler == SIG_IGN;
    if (ignored) continue;
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    installed_[k] = ::sigaction(kSignals[k], &action, nullptr) == 0;
  }
}

CleanupOnSignal::~CleanupOnSignal() {
  const unsigned char stop = 0;
  if (::write(pipe_[1], &stop, 1) < 0) {
  }
  watcher_.join();
  restore();
  urgentWork.store(nullptr);
  writeEnd.store(-1);
  ::close(pipe_[0]);
  ::close(pipe_[1]);
}

void CleanupOnSignal::restore() {
  for (int k = 0; k < 3; ++k)
    if (installed_[k]) {
      ::sigaction(kSignals[k], &previous_[k], nullptr);
      installed_[k] = false;
    }
}

void CleanupOnSignal::watch() {
  unsigned char sig = 0;
  for (;;) {
    const ssize_t n = ::read(pipe_[0], &sig, 1);
    if (n == 1) break;
    if (n < 0 && errno == EINTR) continue;
    return;
  }
  if (sig == 0) return;  // the destructor
  received_.store(sig);
  try {
    cleanup_();
  } catch (...) {
    // The process ends by the signal below whatever the cleanup managed.
  }
  restore();
  ::kill(::getpid(), sig);
}

SignalGrace::SignalGrace(double seconds) : grace_(seconds), onSignal_([this] { wait(); }) {}

SignalGrace::~SignalGrace() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    over_ = true;
  }
  ended_.notify_all();
}

// In the watcher thread, after a signal: the process ends by it when this returns.
void SignalGrace::wait() {
  std::unique_lock<std::mutex> lock(mutex_);
  ended_.wait_for(lock, grace_, [this] { return over_; });
}

}  // namespace Tribos
