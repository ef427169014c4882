// in_process.cpp: the bad-input cases (cases.txt) that the driver refuses,
// run in this one process per rank count instead of a process each:
//
//   in_process CASES --source DIR --generated DIR --work DIR [--one-rank NAME ...]
//   in_process CASES --list
//
// Every case not marked `process` runs on every rank by Tribos::runDriver,
// the driver's main, with the arguments run_case.py would give tribos
// (cases.txt's format and its checks: run_case.py's docstring), in a fresh
// directory WORK/NAME_npN that is the working directory of the call. What
// the call writes to its standard output and error (the driver's messages,
// and a library's through the C streams alike) is captured per rank, and the
// case is held to what run_case.py asserts for its exit code (1 or 3):
//   - the exit code on every rank;
//   - rank 0's stderr matches the message (an ECMAScript regex);
//   - no rank printed a crash or a raw library error;
//   - no result file and no temporary in the output directory, and its
//     lock released (what a process's end would do);
//   - no hang: a case still running after kTimeoutSeconds ends the program.
// One line per case (ok, or FAIL with the reason and what was printed); the
// exit code is 1 when any case failed. Inputs gen:NAME come from the
// directory run_case.py --generate writes; each case copies its own.
// --list prints the table as read here (run_case.py --check-table compares
// it with its own reading of every line, the shell-like splitting included).
#include <Tpetra_Core.hpp>

#include <fcntl.h>
#include <mpi.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "driver_call.hpp"
#include "Tribos_ProcessStartup.hpp"

namespace fs = std::filesystem;

namespace {

constexpr int kTimeoutSeconds = 300;

// One line of cases.txt: name | exit [process] | regex | input | arguments | check.
struct Case {
  std::string name;
  int exit = 0;
  bool process = false;  // runs as its own process (run_case.py), not here
  std::string regex, input, args, check;
};

// Python's str.strip() for the ASCII whitespace it knows.
std::string strip(const std::string& s) {
  const char* space = " \t\n\r\v\f\x1c\x1d\x1e\x1f";
  const size_t first = s.find_first_not_of(space);
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(space) - first + 1);
}

// The exit column: "1", or "1 process".
void parseExit(const std::string& field, Case& c) {
  std::istringstream in(field);
  std::string code, marker, extra;
  in >> code >> marker >> extra;
  if (code.empty() || code.find_first_not_of("0123456789") != std::string::npos || !extra.empty() ||
      (!marker.empty() && marker != "process"))
    throw std::runtime_error("case " + c.name + ": the exit column \"" + field + "\" is not CODE or CODE process");
  c.exit = std::stoi(code);
  c.process = marker == "process";
}

// The table as run_case.py's parse_cases reads it: comments and blank lines
// skipped, fields split at '|' and stripped, a later line of a name replacing
// an earlier one.
std::vector<Case> readCases(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<Case> cases;
  std::map<std::string, size_t> index;
  std::string line;
  while (std::getline(in, line)) {
    line = strip(line);
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    size_t start = 0;
    for (size_t bar; (bar = line.find('|', start)) != std::string::npos; start = bar + 1)
      fields.push_back(strip(line.substr(start, bar - start)));
    fields.push_back(strip(line.substr(start)));
    fields.resize(std::max<size_t>(fields.size(), 6));
    Case c;
    c.name = fields[0];
    parseExit(fields[1], c);
    c.regex = fields[2], c.input = fields[3], c.args = fields[4], c.check = fields[5];
    const auto [it, added] = index.emplace(c.name, cases.size());
    if (added) cases.push_back(c);
    else cases[it->second] = c;
  }
  return cases;
}

// Python's shlex.split (POSIX mode, no comments): words split at blanks;
// '...' literal; "..." where a backslash escapes only " and backslash; a
// backslash outside quotes takes the next character as it is; "" is an
// empty word.
std::vector<std::string> shellSplit(const std::string& s) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (blank(c)) {
      if (inWord) words.push_back(word), word.clear(), inWord = false;
      continue;
    }
    inWord = true;
    if (c == '\'') {
      const size_t close = s.find('\'', i + 1);
      if (close == std::string::npos) throw std::runtime_error("no closing quotation in: " + s);
      word += s.substr(i + 1, close - i - 1);
      i = close;
    } else if (c == '"') {
      for (++i;; ++i) {
        if (i >= s.size()) throw std::runtime_error("no closing quotation in: " + s);
        if (s[i] == '"') break;
        if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == '"' || s[i + 1] == '\\')) ++i;
        word += s[i];
      }
    } else if (c == '\\') {
      if (++i >= s.size()) throw std::runtime_error("no escaped character in: " + s);
      word += s[i];
    } else {
      word += c;
    }
  }
  if (inWord) words.push_back(word);
  return words;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
  return s;
}

std::string hex(const std::string& s) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : s) out += digits[c >> 4], out += digits[c & 15];
  return out;
}

// --list: one line per case, its fields and its argument words in hex
// (tab-separated; words after the fifth field).
void listCases(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    std::cout << hex(c.name) << '\t' << c.exit << '\t' << (c.process ? "process" : "") << '\t' << hex(c.regex) << '\t'
              << hex(c.input) << '\t' << hex(c.check);
    for (const std::string& word : shellSplit(c.args)) std::cout << '\t' << hex(word);
    std::cout << '\n';
  }
}

struct Paths {
  std::string source, generated, work;
};

// Rank 0 makes the case's fresh directory (and copies a generated input into
// it); returns the input argument ("" for none), or throws.
std::string prepare(const Case& c, const Paths& paths, const std::string& work, bool root) {
  if (c.input.rfind("gen:", 0) == 0) {
    const std::string file = work + "/" + c.input.substr(4) + ".xml";
    if (root) fs::copy_file(paths.generated + "/" + c.input.substr(4) + ".xml", file);
    return file;
  }
  if (c.input.rfind("input/", 0) == 0) return paths.source + "/" + c.input;
  if (c.input.rfind("data/", 0) == 0) return paths.source + "/test/" + c.input;
  return "";
}

// The driver's arguments as run_case.py gives them: the input, the case's
// words with {work} and {out} replaced, and --output OUT unless given.
std::vector<std::string> driverArgs(const Case& c, const std::string& input, const std::string& work,
                                    const std::string& out) {
  std::vector<std::string> args;
  if (!input.empty()) args.push_back(input);
  bool output = false;
  for (const std::string& word : shellSplit(c.args)) {
    args.push_back(replaceAll(replaceAll(word, "{work}", work), "{out}", out));
    output = output || args.back() == "--output";
  }
  if (!output) args.insert(args.end(), {"--output", out});
  return args;
}

// Result files (.h5, .xmf, .json, not hidden) and temporaries (.tmp) left
// in the output directory, as run_case.py's result_files finds them.
std::vector<std::string> leftFiles(const std::string& outDir) {
  std::vector<std::string> left;
  std::error_code ec;
  if (!fs::is_directory(outDir, ec)) return left;
  for (const auto& entry : fs::directory_iterator(outDir)) {
    const std::string name = entry.path().filename().string();
    const auto endsWith = [&](const char* tail) {
      const std::string t = tail;
      return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
    };
    if (((endsWith(".h5") || endsWith(".xmf") || endsWith(".json")) && name[0] != '.') || endsWith(".tmp"))
      left.push_back(name);
  }
  return left;
}

// Whether the output directory's lock (flock on .tribos.lock) is still held:
// a returned call must have released it, as a process's end does. A lock of
// this process conflicts with one taken through another open file.
bool lockHeld(const std::string& outDir) {
  const int fd = open((outDir + "/.tribos.lock").c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  close(fd);
  return held;
}

// Why the case failed ("" when it passed), from every rank's exit code and
// output (rank 0 first).
std::string judge(const Case& c, const std::vector<int>& codes, const std::vector<std::string>& outs,
                  const std::vector<std::string>& errs, const std::string& outDir) {
  for (size_t r = 0; r < codes.size(); ++r)
    if (codes[r] != c.exit)
      return "exit " + std::to_string(codes[r]) + " on rank " + std::to_string(r) + ", expected " +
             std::to_string(c.exit);
  for (const char* crash : {"Segmentation fault", "core dumped", "Aborted", "MPI_ABORT", "HDF5-DIAG", "terminate called"})
    for (size_t r = 0; r < codes.size(); ++r)
      if (outs[r].find(crash) != std::string::npos || errs[r].find(crash) != std::string::npos)
        return "rank " + std::to_string(r) + " crashed or printed a raw library error (" + crash + ")";
  if (!c.regex.empty() && !std::regex_search(errs[0], std::regex(c.regex, std::regex::ECMAScript)))
    return "stderr does not match /" + c.regex + "/";
  std::string left;
  for (const std::string& name : leftFiles(outDir)) left += (left.empty() ? "" : ", ") + name;
  if (!left.empty()) return "a failed run left files: " + left;
  if (lockHeld(outDir)) return "the output directory's lock is still held after the call returned";
  return "";
}

// Why the case cannot run here ("" when it can).
std::string refusal(const Case& c) {
  if (c.exit != 1 && c.exit != 3)
    return "exit " + std::to_string(c.exit) + ": its result set is checked by run_case.py; mark it `process`";
  if (!c.check.empty()) return "a check expression is evaluated by run_case.py; mark it `process`";
  try {
    std::regex(c.regex, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    return "the message /" + c.regex + "/ is not an ECMAScript regex: " + e.what();
  }
  return "";
}

struct Options {
  std::string cases;
  Paths paths;
  std::vector<std::string> oneRank;
  bool list = false;
};

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return std::string(argv[++i]);
    };
    if (a == "--source") o.paths.source = value();
    else if (a == "--generated") o.paths.generated = value();
    else if (a == "--work") o.paths.work = value();
    else if (a == "--one-rank") o.oneRank.push_back(value());
    else if (a == "--list") o.list = true;
    else if (o.cases.empty() && a[0] != '-') o.cases = a;
    else throw std::runtime_error("unknown argument " + a);
  }
  if (o.cases.empty() || (!o.list && (o.paths.source.empty() || o.paths.generated.empty() || o.paths.work.empty())))
    throw std::runtime_error(
        "usage: in_process CASES --source DIR --generated DIR --work DIR [--one-rank NAME ...] | CASES --list");
  return o;
}

// Runs one case on every rank; on rank 0 returns why it failed ("" if not).
std::string runCase(const Case& c, const Paths& paths, const Teuchos::RCP<const Teuchos::Comm<int>>& comm,
                    DriverCall::Capture& capture, DriverCall::Watchdog& watchdog) {
  const int rank = comm->getRank(), size = comm->getSize();
  const std::string work = paths.work + "/" + c.name + "_np" + std::to_string(size), out = work + "/out";
  std::string input, problem;
  try {
    if (rank == 0) {
      fs::remove_all(work);
      fs::create_directories(work);
    }
    input = prepare(c, paths, work, rank == 0);
  } catch (const std::exception& e) {
    problem = std::string("cannot prepare the case: ") + e.what();
  }
  int prepared = problem.empty() ? 1 : 0;
  MPI_Bcast(&prepared, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!prepared) return problem.empty() ? "cannot prepare the case (rank 0)" : problem;

  const auto [codes, outs, errs] = DriverCall::call(driverArgs(c, input, work, out), work,
                                                   c.name + " (np " + std::to_string(size) + ")", comm, capture, watchdog);
  if (rank != 0) return "";
  const std::string why = judge(c, codes, outs, errs, out);
  if (why.empty()) return "";
  std::string text = why;
  for (int r = 0; r < size; ++r) {
    if (!outs[r].empty()) text += "\n--- stdout of rank " + std::to_string(r) + " ---\n" + outs[r];
    if (!errs[r].empty()) text += "\n--- stderr of rank " + std::to_string(r) + " ---\n" + errs[r];
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  Tpetra::ScopeGuard guard(&argc, &argv);
  const auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank(), size = comm->getSize();
  try {
    const Options options = parseOptions(argc, argv);
    const auto cases = readCases(options.cases);
    if (options.list) {
      if (rank == 0) listCases(cases);
      return 0;
    }
    DriverCall::Capture capture;
    DriverCall::Watchdog watchdog(capture.realOut(), kTimeoutSeconds);
    int run = 0, failed = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const Case& c : cases) {
      if (c.process) continue;
      const bool oneRank = std::find(options.oneRank.begin(), options.oneRank.end(), c.name) != options.oneRank.end();
      if (oneRank && size > 1) continue;
      const std::string label = c.name + " (np " + std::to_string(size) + ")";
      std::string why = refusal(c);
      if (why.empty()) why = runCase(c, options.paths, comm, capture, watchdog);
      ++run;
      if (rank == 0) {
        if (why.empty()) std::cout << "ok: " << label << ": exit " << c.exit << std::endl;
        else std::cout << "FAIL: " << label << ": " << why << std::endl, ++failed;
      }
    }
    if (rank == 0)
      std::cout << run - failed << " of " << run << " cases passed in this process on " << size << " rank(s) in "
                << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s" << std::endl;
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return failed == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "in_process: " << e.what() << std::endl;
    return 1;
  }
}
