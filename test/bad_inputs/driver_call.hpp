// driver_call.hpp: the tribos driver called as a function (Tribos::runDriver)
// by a test program, on every rank, with what each rank printed captured:
// the file descriptors 1 and 2 point to files of their own during the call,
// so that the C++ streams and a library's C output are caught alike. A call
// still running after the watchdog's limit ends the program (a hang).
#pragma once

#include <Teuchos_Comm.hpp>
#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "Tribos_Driver.hpp"

namespace DriverCall {

// What one rank's call printed on its standard output and error: the file
// descriptors 1 and 2 point to files of their own while the call runs, so
// that the C++ streams (which write through the C ones) and a library's C
// output are caught alike, in the order printed.
class Capture {
 public:
  Capture() : out_(std::tmpfile()), err_(std::tmpfile()), savedOut_(dup(1)), savedErr_(dup(2)) {
    if (!out_ || !err_ || savedOut_ < 0 || savedErr_ < 0) throw std::runtime_error("cannot capture the output");
  }
  void begin() {
    flushAll();
    dup2(fileno(out_), 1);
    dup2(fileno(err_), 2);
  }
  // Ends the capture; returns {stdout, stderr}.
  std::pair<std::string, std::string> end() {
    flushAll();
    dup2(savedOut_, 1);
    dup2(savedErr_, 2);
    return {takeText(fileno(out_)), takeText(fileno(err_))};
  }
  // The process's own standard output, also while a capture runs.
  int realOut() const { return savedOut_; }

 private:
  static void flushAll() {
    std::cout.flush();
    std::cerr.flush();
    std::fflush(stdout);
    std::fflush(stderr);
  }
  static std::string takeText(int fd) {
    std::string text;
    lseek(fd, 0, SEEK_SET);
    char buffer[65536];
    for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<size_t>(n));
    if (ftruncate(fd, 0) != 0) throw std::runtime_error("cannot empty a capture file");
    lseek(fd, 0, SEEK_SET);
    return text;
  }
  FILE* out_;
  FILE* err_;
  int savedOut_, savedErr_;
};

// Ends the program when a call runs longer than its limit (a hang),
// naming the call on the real standard output.
class Watchdog {
 public:
  Watchdog(int realOut, int timeoutSeconds)
      : realOut_(realOut), timeoutSeconds_(timeoutSeconds), thread_([this] { watch(); }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  void start(const std::string& what) {
    std::lock_guard<std::mutex> lock(mutex_);
    what_ = what;
    deadline_ = std::chrono::steady_clock::now() + std::chrono::seconds(timeoutSeconds_);
    running_ = true;
  }
  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    running_ = false;
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      if (running_ && std::chrono::steady_clock::now() > deadline_) {
        const std::string line =
            "FAIL: " + what_ + ": no exit within " + std::to_string(timeoutSeconds_) + " s (hang)\n";
        if (write(realOut_, line.data(), line.size()) < 0) {
        }
        _exit(1);  // mpiexec ends the other ranks
      }
      wake_.wait_for(lock, std::chrono::seconds(1));
    }
  }
  int realOut_;
  int timeoutSeconds_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string what_;
  std::chrono::steady_clock::time_point deadline_;
  bool running_ = false, stop_ = false;
  std::thread thread_;
};

// Every rank's text on rank 0.
inline std::vector<std::string> gatherText(const std::string& mine, int size, int rank) {
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(size), offsets(size, 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
  std::string all(rank == 0 ? static_cast<size_t>(offsets.back() + lengths.back()) : 0, '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, rank == 0 ? &all[0] : nullptr, lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  if (rank == 0)
    for (int r = 0; r < size; ++r) texts.push_back(all.substr(static_cast<size_t>(offsets[r]), lengths[r]));
  return texts;
}

// What one call gave: on rank 0 every rank's exit code, stdout and stderr
// (rank 0 first); empty on the other ranks.
struct Outcome {
  std::vector<int> codes;
  std::vector<std::string> outs, errs;
};

// Runs the driver with `args` on every rank of comm, `work` the working
// directory of the call; `what` names the call if it hangs. Collective.
inline Outcome call(const std::vector<std::string>& args, const std::string& work, const std::string& what,
                    const Teuchos::RCP<const Teuchos::Comm<int>>& comm, Capture& capture, Watchdog& watchdog) {
  const int rank = comm->getRank(), size = comm->getSize();
  const std::filesystem::path home = std::filesystem::current_path();
  std::filesystem::current_path(work);
  watchdog.start(what);
  capture.begin();
  const int code = Tribos::runDriver(args, comm);
  const auto [stdOut, stdErr] = capture.end();
  watchdog.stop();
  std::filesystem::current_path(home);
  Outcome o;
  o.codes.resize(size);
  MPI_Gather(&code, 1, MPI_INT, o.codes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  o.outs = gatherText(stdOut, size, rank);
  o.errs = gatherText(stdErr, size, rank);
  if (rank != 0) o.codes.clear();
  return o;
}

}  // namespace DriverCall
