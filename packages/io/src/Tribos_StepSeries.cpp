#include "Tribos_StepSeries.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "Tribos_Error.hpp"
#include "Tribos_FileDigest.hpp"
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

std::string StepSeries::dataFileName(const std::string& base, int numSteps, int step) {
  if (numSteps == 1) return base + ".h5";
  // Zero-padded to the width of the last step, at least 4 digits: the files
  // of a run sort in step order.
  const int width = std::max<int>(4, static_cast<int>(std::to_string(numSteps).size()));
  std::string number = std::to_string(step);
  number.insert(0, width > static_cast<int>(number.size()) ? width - number.size() : 0, '0');
  return base + ".step" + number + ".h5";
}

std::string StepSeries::indexFileName() const { return base_ + ".xmf"; }

long long StepSeries::stepOfDataFileName(const std::string& base, const std::string& name) {
  if (name == base + ".h5") return 0;
  const std::string head = base + ".step", tail = ".h5";
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return -1;
  const std::string digits = name.substr(head.size(), name.size() - head.size() - tail.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  // More digits than a step count has: a step beyond every series.
  return digits.size() > 12 ? std::numeric_limits<long long>::max() : std::stoll(digits);
}

bool StepSeries::isDataFileName(const std::string& base, const std::string& name) {
  return stepOfDataFileName(base, name) >= 0;
}

// The refusals this rank found, agreed on by every rank (the lowest failing
// rank speaks) and thrown as one CollectiveError: "<action> the results DIR/BASE: ...".
void StepSeries::refuseIfAny(const std::string& action, const std::string& refusals) const {
  const std::string error = agreeOnError(*comm_, refusals);
  if (!error.empty()) throw CollectiveError(action + " the results " + dir_.path() + "/" + base_ + ": " + error);
}

// Every refusal before anything is written, the same on every rank: the
// arguments are compared with rank 0's first, then checked.
void StepSeries::check(int step, double time, const StepResult& result) const {
  std::ostringstream signature;
  signature << step << ' ' << exactly(time);
  std::ostringstream e;
  auto say = [&](const std::string& what) { e << (e.tellp() > 0 ? "; " : "") << what; };
  if (broadcastFromRoot(*comm_, signature.str()) != signature.str()) {
    say("rank " + std::to_string(comm_->getRank()) + " passes another step or time than rank 0");
  } else {
    const int next = stepsWritten() + 1;
    if (step < next) say("the next step is " + std::to_string(next) + " or a later one, not " + std::to_string(step));
    if (step > numSteps_) say("the series has " + std::to_string(numSteps_) + " steps");
    if (!std::isfinite(time)) say("its time " + exactly(time) + " is not finite");
    else if (written_ > 0 && !(time > lastTime_))
      say("its time " + exactly(time) + " does not follow the time " + exactly(lastTime_) + " of step " +
          std::to_string(written_));
    for (const auto& a : result.attributes.numbers)
      if (a.first == "step" || a.first == "time") say("the attribute " + a.first + " is the series' own");
  }
  refuseIfAny("cannot write step " + std::to_string(step) + " of", e.str());
}

void StepSeries::checkTexts(int step, const std::vector<TextFile>& texts) const {
  std::ostringstream signature;
  for (const TextFile& t : texts) signature << '\n' << t.name << ' ' << t.appended;
  std::ostringstream e;
  auto say = [&](const std::string& what) { e << (e.tellp() > 0 ? "; " : "") << what; };
  if (broadcastFromRoot(*comm_, signature.str()) != signature.str()) {
    say("rank " + std::to_string(comm_->getRank()) + " passes other file names than rank 0");
  } else {
    if (texts.empty() || texts.back().appended)
      say("no text file replaced last (the summary, the marker of a complete set)");
    for (size_t k = 0; k < texts.size(); ++k) {
      const TextFile& t = texts[k];
      if (!isPlainFileName(t.name)) say("the text file name '" + t.name + "' is not a plain file name");
      else if (isDataFileName(t.name) || t.name == indexFileName())
        say("the text file name " + t.name + " is a name of the series' data files or index");
      for (size_t j = 0; j < k; ++j)
        if (texts[j].name == t.name) say("the text file " + t.name + " is given twice");
    }
  }
  refuseIfAny("cannot write step " + std::to_string(step) + " of", e.str());
}

// Rank 0 reads the written file back; every rank gets its digest.
std::string StepSeries::digestOf(const std::string& path) const {
  std::string error, digest;
  if (comm_->getRank() == 0) digest = sha256OfFile(path, error);
  error = rootError(*comm_, error);
  if (!error.empty()) throw RunFailure(error);
  return broadcastFromRoot(*comm_, digest);
}

// The index of a series: whole at this run's first commit (with the steps
// it continues, which have the layout of this one), then step by step over
// its closing tags.
void StepSeries::addIndex(ResultSet& files, int step, const SeriesStep& s) {
  const std::string stepText = xdmfTimeSeriesStep(step, s);
  if (committedThisRun_) {
    files.append(indexFileName(), stepText + xdmfTimeSeriesTail(), indexTail_);
    indexTail_ += static_cast<long long>(stepText.size());
    return;
  }
  std::string text = xdmfTimeSeriesHead();
  for (size_t k = 0; k < continuedTimes_.size(); ++k)
    if (continuedWritten_.empty() || continuedWritten_[k])
      text += xdmfTimeSeriesStep(static_cast<int>(k) + 1, {continuedTimes_[k], dataFileName(static_cast<int>(k) + 1), s.layout});
  text += stepText;
  indexTail_ = static_cast<long long>(text.size());
  writeTextFile(files.add(indexFileName()), text + xdmfTimeSeriesTail(), comm_);
}

void StepSeries::writeStep(int step, double time, const Mesh::Discretization& disc, const StepResult& result,
                           const std::vector<TextFile>& texts) {
  writeStep(step, time, disc, result, [&texts](const StepFile&) { return texts; });
}

void StepSeries::writeStep(int step, double time, const Mesh::Discretization& disc, const StepResult& result,
                           const StepTexts& texts) {
  check(step, time, result);
  ResultSet files(dir_, comm_);
  const std::string dataName = dataFileName(step);
  const std::string h5 = files.add(dataName);
  const ResultWriter writer(disc, comm_);
  const long long indexTail = indexTail_;
  try {
    if (numSteps_ == 1) {
      // A one-step run's files are those it has always written.
      writer.write(h5, dataName, files.add(indexFileName()), result.uOwned, result.nodeFields, result.cellFields,
                   result.pointSets, result.attributes);
    } else {
      // Each step file says which step it holds, so that it reads alone.
      ResultAttributes attributes = result.attributes;
      attributes.numbers.push_back({"step", static_cast<double>(step)});
      attributes.numbers.push_back({"time", time});
      const ResultLayout layout = writer.writeData(h5, dataName, result.uOwned, result.nodeFields, result.cellFields,
                                                   result.pointSets, attributes);
      addIndex(files, step, {time, dataName, layout});
    }
    const std::vector<TextFile> textFiles = texts({step, time, dataName, digestOf(h5)});
    checkTexts(step, textFiles);
    for (const TextFile& t : textFiles)
      if (t.appended && committedThisRun_) files.append(t.name, t.text);
      else writeTextFile(files.add(t.name), t.text, comm_);

    if (written_ == 0) {
      // The directory may hold another run's result of this Base Name: it
      // goes, its summary first, and with it every data file of any series of
      // this name, before a file of this run arrives.
      files.removeAtCommit([this](const std::string& name) { return isDataFileName(name); });
      files.commit();
    } else {
      files.commitExtension();
    }
  } catch (...) {
    indexTail_ = indexTail;  // the step may be written again
    throw;
  }
  written_ = step;
  lastTime_ = time;
  committedThisRun_ = true;
  std::vector<double>().swap(continuedTimes_);
  std::vector<bool>().swap(continuedWritten_);
}

void StepSeries::continueAfter(const std::vector<double>& times, const std::vector<bool>& written) {
  std::ostringstream signature, e;
  for (double t : times) signature << exactly(t) << ' ';
  auto say = [&](const std::string& what) { e << (e.tellp() > 0 ? "; " : "") << what; };
  if (broadcastFromRoot(*comm_, signature.str()) != signature.str())
    say("rank " + std::to_string(comm_->getRank()) + " passes other steps than rank 0");
  else if (written_ > 0)
    say("steps are written already");
  else if (!written.empty() && written.size() != times.size())
    say(std::to_string(written.size()) + " flags of written steps for " + std::to_string(times.size()) + " steps");
  else if (times.empty() || static_cast<int>(times.size()) >= numSteps_)
    say("it continues after " + std::to_string(times.size()) + " of " + std::to_string(numSteps_) +
        " steps; at least one must be done and one left");
  else
    for (size_t k = 0; k < times.size(); ++k)
      if (!std::isfinite(times[k]) || (k > 0 && !(times[k] > times[k - 1])))
        say("the time " + exactly(times[k]) + " of step " + std::to_string(k + 1) + " is not finite or not increasing");
  refuseIfAny("cannot continue", e.str());
  continuedTimes_ = times;
  continuedWritten_ = written;
  written_ = static_cast<int>(times.size());
  lastTime_ = times.back();
}

}  // namespace IO
}  // namespace Tribos
