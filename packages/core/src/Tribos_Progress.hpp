// Tribos_Progress.hpp: what a long run is doing, for the person waiting at
// the terminal. Stages ("assembly", "factorization 3 of 8 subdomains") and
// solver iterations are reported here by the code that does the work; a
// driver decides whether and where they are printed (the tribos driver: rank
// 0's stderr unless --quiet) by holding a Progress::Session.
//
// Short runs stay silent: nothing is printed until the run has lasted
// kDelay seconds. From then on the current stage is printed, every later
// stage as it starts, and iteration lines at most one per kInterval
// seconds; each line is flushed. A line a second is the promise: when the
// work says nothing for kInterval seconds (one long factorization, a loop
// that reports no iterations, a search over many facets), the ticker thread
// prints the stage again with the time spent in it, so that a silent
// terminal always means a stopped run. The current stage is kept even when
// nothing is printed, so that an out-of-memory failure can say where it
// happened.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

namespace Tribos {

class Progress {
 public:
  static constexpr double kDelay = 2.0, kInterval = 1.0;

  // Prints to `out` while alive (one session at a time).
  class Session {
   public:
    explicit Session(std::ostream* out) {
      State& s = state();
      std::lock_guard<std::mutex> lock(s.mutex);
      s.out = out;
      s.start = Clock::now();
      s.stop = false;
      s.stepPrefix.clear();
      s.printedStage = false;
      s.lastIteration = s.lastLine = -1e300;
      s.stageStart = 0;
      if (out) ticker_ = std::thread(tick);
    }
    ~Session() {
      State& s = state();
      {
        std::lock_guard<std::mutex> lock(s.mutex);
        s.stop = true;
        s.out = nullptr;
      }
      s.wake.notify_all();
      if (ticker_.joinable()) ticker_.join();
    }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

   private:
    std::thread ticker_;
  };

  // The load step of the stages that follow ("load step 3 of 20: "); none
  // for a run of one step.
  static void setStep(int step, int steps) {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    s.stepPrefix = steps > 1 ? "load step " + std::to_string(step) + " of " + std::to_string(steps) + ": " : "";
  }

  // A new stage of the run.
  static void stage(const std::string& what) {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    s.stage = s.stepPrefix + what;
    s.stageStart = elapsed(s);
    s.printedStage = false;
    flushStage(s);
  }

  // One iteration of the current stage: text() gives the line, e.g.
  // "outer 3: residual 1.2e-05, n_A 140". It is called only when the line
  // is printed, so solver loops pay no formatting when nothing is shown.
  template <class Text>
  static void iteration(Text&& text) {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.out) return;
    const double t = elapsed(s);
    if (t < kDelay || t - s.lastIteration < kInterval) return;
    flushStage(s);
    s.lastIteration = t;
    print(s, "  " + std::string(text()));
  }

  // 1.234e-05, for progress lines.
  static std::string sci(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", v);
    return buf;
  }

  static std::string currentStage() {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    return s.stage;
  }

 private:
  using Clock = std::chrono::steady_clock;
  struct State {
    std::mutex mutex;
    std::condition_variable wake;
    std::ostream* out = nullptr;
    Clock::time_point start = Clock::now();
    std::string stage = "start-up";
    std::string stepPrefix;
    bool printedStage = false, stop = false;
    double lastIteration = -1e300, lastLine = -1e300, stageStart = 0;
  };
  static State& state() {
    static State s;
    return s;
  }
  static double elapsed(const State& s) { return std::chrono::duration<double>(Clock::now() - s.start).count(); }
  // Callers hold the mutex.
  static void flushStage(State& s) {
    if (!s.out || s.printedStage || elapsed(s) < kDelay) return;
    s.printedStage = true;
    print(s, s.stage);
  }
  static void print(State& s, const std::string& line) {
    char stamp[32];
    s.lastLine = elapsed(s);
    std::snprintf(stamp, sizeof stamp, "[%7.1f s] ", s.lastLine);
    *s.out << stamp << line << std::endl;
  }
  // The stage again when nothing was printed for kInterval seconds.
  static void heartbeat(State& s) {
    if (!s.out || !s.printedStage) return;
    const double t = elapsed(s);
    if (t - s.lastLine < kInterval) return;
    char spent[48];
    std::snprintf(spent, sizeof spent, " (%.0f s in this stage)", t - s.stageStart);
    print(s, "  " + s.stage + spent);
  }
  static void tick() {
    State& s = state();
    std::unique_lock<std::mutex> lock(s.mutex);
    while (!s.stop) {
      flushStage(s);
      heartbeat(s);
      s.wake.wait_for(lock, std::chrono::milliseconds(250));
    }
  }
};

}  // namespace Tribos
