#include "Tribos_StepSeries.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_ResultSet.hpp"

namespace Tribos {
namespace IO {

namespace {

std::string exactly(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

bool isPlainFileName(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name != "." && name != "..";
}

}  // namespace

StepSeries::StepSeries(const OutputDirectory& dir, const std::string& baseName, int numSteps,
                       const RCP<const Comm>& comm)
    : dir_(dir), base_(baseName), numSteps_(numSteps), comm_(comm) {
  if (!isPlainFileName(baseName))
    throw CollectiveError("the Base Name '" + baseName + "' of a result is not a plain file name");
  if (numSteps < 1) throw CollectiveError("a time series of results needs at least one step, not " + std::to_string(numSteps));
}

std::string StepSeries::dataFileName(int step) const {
  if (numSteps_ == 1) return base_ + ".h5";
  // Zero-padded to the width of the last step, at least 4 digits: the files
  // of a run sort in step order.
  const int width = std::max<int>(4, static_cast<int>(std::to_string(numSteps_).size()));
  std::string number = std::to_string(step);
  number.insert(0, width > static_cast<int>(number.size()) ? width - number.size() : 0, '0');
  return base_ + ".step" + number + ".h5";
}

std::string StepSeries::indexFileName() const { return base_ + ".xmf"; }

bool StepSeries::isDataFileName(const std::string& name) const {
  if (name == base_ + ".h5") return true;
  const std::string head = base_ + ".step", tail = ".h5";
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return false;
  for (size_t i = head.size(); i < name.size() - tail.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

// Every refusal before anything is written, the same on every rank: the
// arguments are compared with rank 0's first, then checked.
void StepSeries::check(int step, double time, const std::vector<TextFile>& texts, const StepResult& result) const {
  std::ostringstream signature;
  signature << step << ' ' << exactly(time);
  for (const TextFile& t : texts) signature << '\n' << t.name;
  std::ostringstream e;
  auto say = [&](const std::string& what) { e << (e.tellp() > 0 ? "; " : "") << what; };
  if (broadcastFromRoot(*comm_, signature.str()) != signature.str()) {
    say("rank " + std::to_string(comm_->getRank()) + " passes another step, time or file names than rank 0");
  } else {
    const int next = stepsWritten() + 1;
    if (step != next) say("the next step is " + std::to_string(next) + ", not " + std::to_string(step));
    if (step > numSteps_) say("the series has " + std::to_string(numSteps_) + " steps");
    if (!std::isfinite(time)) say("its time " + exactly(time) + " is not finite");
    else if (!written_.empty() && !(time > written_.back().time))
      say("its time " + exactly(time) + " does not follow the time " + exactly(written_.back().time) + " of step " +
          std::to_string(stepsWritten()));
    if (texts.empty()) say("no text files given (the last one is the summary, the marker of a complete set)");
    for (const TextFile& t : texts)
      if (!isPlainFileName(t.name)) say("the text file name '" + t.name + "' is not a plain file name");
      else if (isDataFileName(t.name) || t.name == indexFileName())
        say("the text file name " + t.name + " is a name of the series' data files or index");
    for (const auto& a : result.attributes.numbers)
      if (a.first == "step" || a.first == "time") say("the attribute " + a.first + " is the series' own");
  }
  const std::string error = agreeOnError(*comm_, e.str());
  if (!error.empty())
    throw CollectiveError("cannot write step " + std::to_string(step) + " of the results " + dir_.path() + "/" + base_ +
                          ": " + error);
}

void StepSeries::writeStep(int step, double time, const Mesh::Discretization& disc, const StepResult& result,
                           const std::vector<TextFile>& texts) {
  check(step, time, texts, result);
  ResultSet files(dir_, comm_);
  const std::string dataName = dataFileName(step);
  const std::string h5 = files.add(dataName), xmf = files.add(indexFileName());
  std::vector<std::string> textPaths;
  for (const TextFile& t : texts) textPaths.push_back(files.add(t.name));

  const ResultWriter writer(disc, comm_);
  std::vector<SeriesStep> steps = written_;
  if (numSteps_ == 1) {
    // A one-step run's files are those it has always written.
    writer.write(h5, dataName, xmf, result.uOwned, result.nodeFields, result.cellFields, result.pointSets,
                 result.attributes);
    steps.push_back({time, dataName, {}});
  } else {
    // Each step file says which step it holds, so that it reads alone.
    ResultAttributes attributes = result.attributes;
    attributes.numbers.push_back({"step", static_cast<double>(step)});
    attributes.numbers.push_back({"time", time});
    steps.push_back({time, dataName,
                     writer.writeData(h5, dataName, result.uOwned, result.nodeFields, result.cellFields,
                                      result.pointSets, attributes)});
    // Steps of the run this one continues: the files of one mesh and fields.
    if (!layoutsKnown_)
      for (auto& earlier : steps) earlier.layout = steps.back().layout;
    writeTextFile(xmf, xdmfTimeSeries(steps), comm_);
  }
  for (size_t k = 0; k < texts.size(); ++k) writeTextFile(textPaths[k], texts[k].text, comm_);

  if (written_.empty()) {
    // The directory may hold another run's result of this Base Name: it
    // goes, its summary first, and with it every data file of any series of
    // this name, before a file of this run arrives.
    files.removeAtCommit([this](const std::string& name) { return isDataFileName(name); });
    files.commit();
  } else {
    files.commitExtension();
  }
  written_ = std::move(steps);
  layoutsKnown_ = true;
}

void StepSeries::continueAfter(const std::vector<double>& times) {
  std::ostringstream signature, e;
  for (double t : times) signature << exactly(t) << ' ';
  auto say = [&](const std::string& what) { e << (e.tellp() > 0 ? "; " : "") << what; };
  if (broadcastFromRoot(*comm_, signature.str()) != signature.str())
    say("rank " + std::to_string(comm_->getRank()) + " passes other steps than rank 0");
  else if (!written_.empty())
    say("steps are written already");
  else if (times.empty() || static_cast<int>(times.size()) >= numSteps_)
    say("it continues after " + std::to_string(times.size()) + " of " + std::to_string(numSteps_) +
        " steps; at least one must be done and one left");
  else
    for (size_t k = 0; k < times.size(); ++k)
      if (!std::isfinite(times[k]) || (k > 0 && !(times[k] > times[k - 1])))
        say("the time " + exactly(times[k]) + " of step " + std::to_string(k + 1) + " is not finite or not increasing");
  const std::string error = agreeOnError(*comm_, e.str());
  if (!error.empty())
    throw CollectiveError("cannot continue the results " + dir_.path() + "/" + base_ + ": " + error);
  for (size_t k = 0; k < times.size(); ++k)
    written_.push_back({times[k], dataFileName(static_cast<int>(k) + 1), {}});
  layoutsKnown_ = false;
}

}  // namespace IO
}  // namespace Tribos
