// Tribos_StepSeries.hpp: the results of a run in load steps, written step by
// step as a time series that ParaView plays, so that a run stopped at any
// point leaves the steps it completed complete and readable.
//
// Files in the output directory, for Base Name BASE and N steps:
//   N > 1:  BASE.step0001.h5 ... one HDF5 file per completed step (the
//           content of a one-step result: mesh, fields, point sets, root
//           attributes, plus the attributes step and time), each written
//           under a temporary name and renamed when complete;
//           BASE.xmf, an XDMF temporal collection of the completed steps
//           (xdmfTimeSeries, Tribos_ResultWriter.hpp);
//   N = 1:  BASE.h5 and BASE.xmf exactly as ResultWriter::write writes them;
// and the caller's text files (e.g. BASE.parameters.xml, BASE.history.csv),
// the last of them the summary (BASE.json), the marker of a complete set.
// The step number has 4 digits, more when N needs them.
//
// Every step commits the index and the text files as one set (ResultSet,
// the summary last). The first commit of a run removes what an earlier run
// of the same Base Name left: its set, summary first, then every
// BASE.h5 and BASE.step<digits>.h5, before any new file arrives. Later steps
// only add their data file, write their part of the index over its closing
// tags (the tags after it), append to the texts that grow by steps and
// rename the others over the old ones, the summary last: what a step costs
// to write does not grow with the number of steps before it, and the
// summary in the directory always lists steps whose files are all there
// (the index and the appended texts may hold one step more while a step
// commits, or after a kill then).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultSet.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// One step's result, as ResultWriter::write takes it (sizes and rank rules there).
struct StepResult {
  std::vector<double> uOwned;  // 3 per node of disc.ownedNodes(), in its order
  std::vector<Field> nodeFields, cellFields;
  std::vector<PointSet> pointSets;  // e.g. the contact nodes
  ResultAttributes attributes;      // not named step or time: the series sets those
};

// A text file of the result set: a plain file name and its content (rank 0's
// content is written).
struct TextFile {
  std::string name;
  std::string text;
  // false: the file is replaced by text at every commit. true: the file
  // grows by text: at the series' first commit in a run it is replaced (the
  // caller gives its whole content then: a header, the rows of the steps a
  // continued series keeps, and the step's), at later commits text is
  // appended to it.
  bool appended = false;
};

// A step's data file as the series committed it.
struct StepFile {
  int step = 0;
  double time = 0;
  std::string name;    // plain file name in the directory
  std::string sha256;  // the digest of its content (Tribos_FileDigest.hpp)
};

// The text files of a step, given its data file (e.g. a summary that records
// the file's digest). Called on every rank with the same StepFile.
using StepTexts = std::function<std::vector<TextFile>(const StepFile&)>;

class StepSeries {
 public:
  // Collective. dir must outlive the series. baseName: a plain file name
  // (no '/'); numSteps >= 1. Refusals: Tribos::CollectiveError. Nothing is
  // written or removed before the first writeStep.
  StepSeries(const OutputDirectory& dir, const std::string& baseName, int numSteps, const RCP<const Comm>& comm);
  StepSeries(const StepSeries&) = delete;
  StepSeries& operator=(const StepSeries&) = delete;

  // Collective, after step `step` (1-based) is complete at pseudo-time `time`:
  // writes the step's data file, the index of steps 1..step and `texts` (the
  // last one the summary) and commits them. `step` must follow the last
  // committed one (a run that writes every k-th step skips the steps
  // between, which get neither a file nor an index entry; a failed step may
  // be written again), `time` finite
  // and above the previous step's, the same on every rank; the text names
  // plain file names, distinct from the data files and the index. Refusals:
  // Tribos::CollectiveError, nothing written. A write or commit failure:
  // Tribos::RunFailure on every rank, the steps committed before complete
  // in the directory, no temporary left.
  // texts are asked for once the data file is written, with its digest.
  void writeStep(int step, double time, const Mesh::Discretization& disc, const StepResult& result,
                 const StepTexts& texts);
  void writeStep(int step, double time, const Mesh::Discretization& disc, const StepResult& result,
                 const std::vector<TextFile>& texts);

  // Collective, before the first writeStep: the series continues one that
  // an earlier run of the same steps left in the directory, complete up to
  // step times.size() (its summary lists those steps; their data files are
  // there, dataFileName(1), ...), steps at these times. The next writeStep
  // writes the step after them and commits as a later step does: it adds
  // its data file and renames the index and texts over the earlier run's,
  // removing nothing. The index lists the earlier steps with the layout of
  // the step written next: a series has one mesh and the same fields at
  // every step. written: which of the earlier steps have a data file (and
  // so an index entry); empty: all of them. Refusals (steps left to write,
  // times increasing, the same on every rank): Tribos::CollectiveError.
  void continueAfter(const std::vector<double>& times, const std::vector<bool>& written = {});

  // The file names of the series (plain names in the directory).
  std::string dataFileName(int step) const { return dataFileName(base_, numSteps_, step); }
  std::string indexFileName() const;  // BASE.xmf
  // Whether fileName is a data file of a series of this Base Name, of any
  // number of steps (BASE.h5, BASE.step<digits>.h5).
  bool isDataFileName(const std::string& fileName) const { return isDataFileName(base_, fileName); }
  // The same for a series of Base Name `base` and numSteps steps:
  // BASE.h5 (one step) or BASE.stepNNNN.h5.
  static std::string dataFileName(const std::string& base, int numSteps, int step);
  static bool isDataFileName(const std::string& base, const std::string& fileName);
  // The step whose data file fileName is (0 for BASE.h5), -1 for a name that
  // is no data file of Base Name `base`.
  static long long stepOfDataFileName(const std::string& base, const std::string& fileName);

  int numSteps() const { return numSteps_; }
  // The steps committed so far.
  int stepsWritten() const { return written_; }

 private:
  void check(int step, double time, const StepResult& result) const;
  void checkTexts(int step, const std::vector<TextFile>& texts) const;
  void refuseIfAny(const std::string& action, const std::string& refusals) const;
  std::string digestOf(const std::string& path) const;
  void addIndex(ResultSet& files, int step, const SeriesStep& s);

  const OutputDirectory& dir_;
  std::string base_;
  int numSteps_;
  RCP<const Comm> comm_;
  int written_ = 0;                     // steps committed (by this run, or before it: continueAfter)
  double lastTime_ = 0;                 // the time of step written_
  bool committedThisRun_ = false;       // this run committed a step
  std::vector<double> continuedTimes_;  // the steps continueAfter took over, until this run's first commit
  std::vector<bool> continuedWritten_;  // ... which of them have a data file
  long long indexTail_ = 0;             // where the index's closing tags begin
};

}  // namespace IO
}  // namespace Tribos
