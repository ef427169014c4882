// test_signal_grace.cpp: SignalGrace (Tribos_CleanupOnSignal.hpp) in a
// child process each: a stop signal received while it lives ends the process
// by that signal when the object ends, or when the grace runs out, not at
// once; without a signal nothing changes.
#include <Teuchos_UnitTestHarness.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "Tribos_CleanupOnSignal.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Ended {
  int status = 0;
  double seconds = 0;
};

// Runs `body` in a child process; its wait status and how long it ran.
template <class Body>
Ended inChild(Body body) {
  const auto start = Clock::now();
  const pid_t child = fork();
  if (child == 0) {
    body();
    _exit(0);
  }
  Ended e;
  while (waitpid(child, &e.status, 0) < 0) {
  }
  e.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return e;
}

TEUCHOS_UNIT_TEST(SignalGrace, HoldsTheSignalUntilItEnds) {
  int alive[2];
  TEST_ASSERT(pipe(alive) == 0);
  const Ended e = inChild([&] {
    {
      Tribos::SignalGrace grace(30);
      kill(getpid(), SIGTERM);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      const char byte = 1;
      if (write(alive[1], &byte, 1) != 1) _exit(3);  // still running after the signal
    }
    _exit(4);  // not reached: the signal ends the process with the object
  });
  close(alive[1]);
  char byte = 0;
  const ssize_t got = read(alive[0], &byte, 1);
  TEST_EQUALITY(got, 1);
  close(alive[0]);
  TEST_ASSERT(WIFSIGNALED(e.status) && WTERMSIG(e.status) == SIGTERM);
  TEST_ASSERT(e.seconds < 10);  // at the object's end, not after its grace of 30 s
}

TEUCHOS_UNIT_TEST(SignalGrace, EndsTheProcessWhenTheGraceRunsOut) {
  const Ended e = inChild([] {
    Tribos::SignalGrace grace(0.3);
    kill(getpid(), SIGINT);
    std::this_thread::sleep_for(std::chrono::seconds(30));
    _exit(4);
  });
  TEST_ASSERT(WIFSIGNALED(e.status) && WTERMSIG(e.status) == SIGINT);
  TEST_ASSERT(e.seconds >= 0.25 && e.seconds < 10);
}

TEUCHOS_UNIT_TEST(SignalGrace, WithoutASignalNothingChanges) {
  const Ended e = inChild([] {
    { Tribos::SignalGrace grace(5); }
    struct sigaction now {};
    sigaction(SIGTERM, nullptr, &now);
    _exit(now.sa_handler == SIG_DFL ? 7 : 5);  // the default action back
  });
  TEST_ASSERT(WIFEXITED(e.status) && WEXITSTATUS(e.status) == 7);
  TEST_ASSERT(e.seconds < 4);
}

}  // namespace
