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
// Every step replaces the index and the text files as one set (ResultSet,
// the summary last). The first commit of a run removes what an earlier run
// of the same Base Name left: its set, summary first, then every
// BASE.h5 and BASE.step<digits>.h5, before any new file arrives. Later steps
// only add their data file and rename the index and texts over the old ones,
// the summary last: the summary in the directory always lists steps whose
// files are all there (the index may list one step more while a step commits).
#pragma once

#include <string>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_OutputDirectory.hpp"
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
};

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
  // last one the summary) and commits them. `step` must be the step after the
  // last committed one (a failed step may be written again), `time` finite
  // and above the previous step's, the same on every rank; the text names
  // plain file names, distinct from the data files and the index. Refusals:
  // Tribos::CollectiveError, nothing written. A write or commit failure:
  // Tribos::RunFailure on every rank, the steps committed before complete
  // in the directory, no temporary left.
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
  // every step. Refusals (steps left to write, times increasing, the same
  // on every rank): Tribos::CollectiveError.
  void continueAfter(const std::vector<double>& times);

  // The file names of the series (plain names in the directory).
  std::string dataFileName(int step) const;  // BASE.h5 (one step) or BASE.stepNNNN.h5
  std::string indexFileName() const;         // BASE.xmf
  // Whether fileName is a data file of a series of this Base Name, of any
  // number of steps (BASE.h5, BASE.step<digits>.h5).
  bool isDataFileName(const std::string& fileName) const;

  int numSteps() const { return numSteps_; }
  // The steps committed so far.
  int stepsWritten() const { return static_cast<int>(written_.size()); }

 private:
  void check(int step, double time, const std::vector<TextFile>& texts, const StepResult& result) const;

  const OutputDirectory& dir_;
  std::string base_;
  int numSteps_;
  RCP<const Comm> comm_;
  std::vector<SeriesStep> written_;  // the committed steps, the same on every rank
  bool layoutsKnown_ = true;         // false after continueAfter until the next step gives the layout
};

}  // namespace IO
}  // namespace Tribos
