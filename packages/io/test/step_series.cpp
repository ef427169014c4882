// StepSeries: a time series of results written step by step. Three steps of
// a small mesh give three step files and an index that parses (Teuchos' XML
// parser), lists the three times in order and names existing datasets of the
// shapes it gives, whose values (read back with HDF5) are each step's; after
// every step the directory holds that step's complete set. A later series of
// fewer steps, a one-step run and a series after it leave no data file of the
// earlier ones; other results' files stay. A failure in step 2 (a data file
// that cannot be renamed, a text file that cannot, wrong arguments) leaves
// step 1's set complete and readable, and the step can be written again. A
// one-step series writes what ResultWriter::write writes. Steps may be
// skipped (a run's Output/Step Stride): they have no file and no index entry.
#include <Teuchos_FileInputSource.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_FileDigest.hpp"
#include "Tribos_ResultSet.hpp"
#include "Tribos_StepSeries.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

const std::string kBase = "run";

// The value of every datum depends on the step, so that a file of another
// step (or a stale one) cannot pass for it.
double stepValue(double base, int step) { return base + 1000.0 * step; }

// Step `step` of a result on the box: displacement, a cell field, and a
// contact point set with r + 1 points on rank r (none on some ranks of a
// larger run would do as well: the writer's tests cover that).
IO::StepResult stepResult(const Mesh::Discretization& disc, int step, const Comm& comm) {
  IO::StepResult r;
  for (int n : disc.ownedNodes())  // read back against the geometry beside it
    for (int d = 0; d < 3; ++d) r.uOwned.push_back(stepValue((d + 1) * disc.part.coords[n][d], step));
  IO::Field cellId{"cell_id", 1, {}};
  for (int c = 0; c < disc.part.numCells(); ++c) cellId.values.push_back(stepValue(disc.meshCell(c), step));
  r.cellFields = {cellId};
  IO::PointSet contact{"contact",
                       {},
                       {IO::Field{"normal_force", 1, {}}, IO::Field{"tangential_force", 3, {}}, IO::Field{"slip", 3, {}},
                        IO::Field{"pair", 1, {}}, IO::Field{"status", 1, {}}}};
  const int rank = comm.getRank();
  for (int j = 0; j <= rank; ++j) {
    const double id = 10 * rank + j;  // unique over the ranks
    contact.coords.push_back({double(rank), double(j), 0.5});
    contact.fields[0].values.push_back(stepValue(id, step));
    for (int d = 0; d < 3; ++d) contact.fields[1].values.push_back(stepValue(id + 0.1 * d, step));
    for (int d = 0; d < 3; ++d) contact.fields[2].values.push_back(stepValue(id + 0.01 * d, step));
    contact.fields[3].values.push_back(j % 2);
    contact.fields[4].values.push_back(step % 3);
  }
  r.pointSets = {contact};
  r.attributes.text = {{"problem", "box"}, {"stop_reason", "converged"}};
  r.attributes.numbers = {{"converged", 1.0}};
  return r;
}

std::vector<IO::TextFile> texts(int step) {
  return {{kBase + ".parameters.xml", "<ParameterList/>\n"},
          {kBase + ".history.csv", "step\n" + std::to_string(step) + "\n"},
          {kBase + ".json", "{\"steps\": " + std::to_string(step) + "}\n"}};
}

// What the index says of one step.
struct IndexItem {
  std::string file, dataset;
  std::vector<long long> dims;
};
struct IndexStep {
  double time = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> grids;
  std::vector<IndexItem> items;
};

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

void collectItems(const Teuchos::XMLObject& x, std::vector<IndexItem>& items) {
  if (x.getTag() == "DataItem") {
    std::string text;
    for (int i = 0; i < x.numContentLines(); ++i) text += x.getContentLine(i);
    text = trimmed(text);
    IndexItem item;
    item.file = text.substr(0, text.find(':'));
    item.dataset = text.substr(text.find(':') + 1);
    std::istringstream dims(x.getRequired("Dimensions"));
    for (long long d; dims >> d;) item.dims.push_back(d);
    items.push_back(item);
  }
  for (int i = 0; i < x.numChildren(); ++i) collectItems(x.getChild(i), items);
}

// The steps of a series index, parsed as XML: Xdmf/Domain/Grid (temporal
// collection) / Grid per step with Time and the grids. Throws if it does not parse.
std::vector<IndexStep> readIndex(const std::string& path, Teuchos::FancyOStream& out, bool& success) {
  const Teuchos::XMLObject xdmf = Teuchos::FileInputSource(path).getObject();
  std::vector<IndexStep> steps;
  TEST_EQUALITY(xdmf.getTag(), "Xdmf");
  if (xdmf.numChildren() != 1 || xdmf.getChild(0).getTag() != "Domain") return steps;
  const Teuchos::XMLObject& domain = xdmf.getChild(0);
  TEST_EQUALITY(domain.numChildren(), 1);  // one temporal collection
  if (domain.numChildren() != 1) return steps;
  const Teuchos::XMLObject& series = domain.getChild(0);
  TEST_EQUALITY(series.getRequired("GridType"), "Collection");
  TEST_EQUALITY(series.getRequired("CollectionType"), "Temporal");
  for (int k = 0; k < series.numChildren(); ++k) {
    const Teuchos::XMLObject& step = series.getChild(k);
    IndexStep s;
    for (int i = 0; i < step.numChildren(); ++i) {
      const Teuchos::XMLObject& c = step.getChild(i);
      if (c.getTag() == "Time") s.time = c.getRequiredDouble("Value");
      if (c.getTag() == "Grid") s.grids.push_back(c.getRequired("Name"));
    }
    collectItems(step, s.items);
    steps.push_back(s);
  }
  return steps;
}

// Rank 0: step `step` of the series as written by stepResult, read back
// from its file (the datasets the index named are checked apart).
void checkStepFile(const std::string& path, int step, double time, const Mesh::Discretization& disc, int numRanks,
                   Teuchos::FancyOStream& out, bool& success) {
  out << "step file " << path << "\n";
  const H5Reader h5(path);
  TEST_COMPARE(h5.id, >=, 0);  // the step file opens
  if (h5.id < 0) return;
  const long long N = disc.numMeshNodes(), C = disc.numMeshCells();
  const auto xyz = h5.read<double>("/mesh/geometry"), u = h5.read<double>("/nodes/displacement"),
             cells = h5.read<double>("/cells/cell_id");
  TEST_EQUALITY(u.size(), size_t(3 * N));
  TEST_EQUALITY(xyz.size(), size_t(3 * N));
  bool ok = u.size() == size_t(3 * N) && xyz.size() == u.size();
  for (size_t i = 0; ok && i < u.size(); ++i) ok = u[i] == stepValue((i % 3 + 1) * xyz[i], step);
  TEST_ASSERT(ok);  // the displacement of this step at every node
  std::vector<bool> seen(C, false);
  ok = cells.size() == size_t(C);
  for (double v : cells) {
    const long long c = std::llround(v - stepValue(0, step));
    ok = ok && c >= 0 && c < C && !seen[c] && v == stepValue(double(c), step);
    if (ok) seen[c] = true;
  }
  TEST_ASSERT(ok);  // every cell once, with this step's value

  const std::string g = "/points/contact/";
  const auto pxyz = h5.read<double>(g + "geometry"), normal = h5.read<double>(g + "normal_force"),
             tangential = h5.read<double>(g + "tangential_force"), slip = h5.read<double>(g + "slip"),
             pair = h5.read<double>(g + "pair"), status = h5.read<double>(g + "status");
  const size_t P = numRanks * (numRanks + 1) / 2;
  ok = pxyz.size() == 3 * P && normal.size() == P && tangential.size() == 3 * P && slip.size() == 3 * P &&
       pair.size() == P && status.size() == P;
  TEST_ASSERT(ok);  // contact point set sizes
  for (int r = 0, i = 0; ok && r < numRanks; ++r)
    for (int j = 0; ok && j <= r; ++j, ++i) {
      const double id = 10 * r + j;
      ok = pxyz[3 * i] == r && pxyz[3 * i + 1] == j && pxyz[3 * i + 2] == 0.5 && normal[i] == stepValue(id, step) &&
           pair[i] == j % 2 && status[i] == step % 3;
      for (int d = 0; d < 3; ++d)
        ok = ok && tangential[3 * i + d] == stepValue(id + 0.1 * d, step) && slip[3 * i + d] == stepValue(id + 0.01 * d, step);
    }
  TEST_ASSERT(ok);  // contact fields of this step in rank order
  TEST_EQUALITY(h5.number("step"), double(step));
  TEST_EQUALITY(h5.number("time"), time);
  TEST_EQUALITY(h5.text("problem"), "box");
  TEST_EQUALITY(h5.number("converged"), 1.0);
}

bool isDirectory(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// Rank 0: the directory holds the complete set of the first `steps` steps
// of a series at `times`: its files and no other data file of the Base
// Name, an index of those steps in order whose every DataItem names its
// step's file and an existing dataset of its shape, each step's values, the
// texts of the last step, no temporary.
void checkSeries(const std::string& dir, const IO::StepSeries& series, const Mesh::Discretization& disc,
                 const std::vector<double>& times, int steps, const Comm& comm, Teuchos::FancyOStream& out,
                 bool& success) {
  if (comm.getRank() != 0) return;
  out << "series of " << steps << " steps in " << dir << "\n";
  TEST_ASSERT(temporariesIn(dir).empty());
  for (const std::string& name : listDirectory(dir))
    if (series.isDataFileName(name) && !isDirectory(dir + "/" + name)) {  // a directory: a test's obstacle
      const bool written = name.size() == series.dataFileName(1).size() && name <= series.dataFileName(steps);
      out << "data file " << name << "\n";
      TEST_ASSERT(written);  // no data file but the steps written
    }
  for (const IO::TextFile& t : texts(steps)) TEST_EQUALITY(readFile(dir + "/" + t.name), t.text);
  const std::vector<IndexStep> index = readIndex(dir + "/" + series.indexFileName(), out, success);
  TEST_EQUALITY(index.size(), size_t(steps));
  for (size_t k = 0; k < index.size() && k < size_t(steps); ++k) {
    const int step = static_cast<int>(k) + 1;
    const std::string file = series.dataFileName(step);
    TEST_EQUALITY(index[k].time, times[k]);  // the times in order, exactly
    TEST_ASSERT((index[k].grids == std::vector<std::string>{"body", "contact"}));
    TEST_EQUALITY(index[k].items.size(), size_t(2 + 1 + 1 + 1 + 5));  // topology, geometry, fields; contact's
    const H5Reader h5(dir + "/" + file);
    for (const IndexItem& item : index[k].items) {
      out << "step " << step << " " << item.file << ":" << item.dataset << "\n";
      TEST_EQUALITY(item.file, file);
      TEST_ASSERT(h5.has(item.dataset));
      TEST_ASSERT(h5.shape(item.dataset) == item.dims);
    }
    checkStepFile(dir + "/" + file, step, times[k], disc, comm.getSize(), out, success);
  }
}

// Every rank throws exception type E (and the same message); what() of rank 0.
template <class E, class F>
std::string expectCollective(const std::string& label, const Comm& comm, Teuchos::FancyOStream& out, bool& success,
                             F&& f) {
  std::string message, kind = "nothing";
  try {
    f();
  } catch (const E& e) {
    message = e.what(), kind = "expected";
  } catch (const std::exception& e) {
    message = e.what(), kind = std::string("another exception: ") + e.what();
  }
  out << label << ": " << message << "\n";
  TEST_EQUALITY(kind, "expected");
  TEST_EQUALITY(message, broadcastFromRoot(comm, message));  // the same message on every rank
  return message;
}

// A scratch output directory and the box.
struct Setup {
  explicit Setup(const RCP<const Comm>& comm)
      : scratch(comm, "step_series"), disc(boxDiscretization(6, 2, 2, *comm)), dir(scratch.path() + "/out", comm) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the checks report what they find
  }
  ScratchDirectory scratch;
  Mesh::Discretization disc;
  IO::OutputDirectory dir;
};

// Writes steps first..last of a series.
void writeSteps(IO::StepSeries& series, const Mesh::Discretization& disc, const std::vector<double>& times, int first,
                int last, const RCP<const Comm>& comm) {
  for (int k = first; k <= last; ++k) series.writeStep(k, times[k - 1], disc, stepResult(disc, k, *comm), texts(k));
}

// Rank 0: a file put in the way.
void putFile(const RCP<const Comm>& comm, const std::string& path) {
  if (comm->getRank() == 0) writePlainFile(path, "another result");
  comm->barrier();
}

}  // namespace

TEUCHOS_UNIT_TEST(StepSeries, ThreeStepsEachCompleteWhenWritten) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::vector<double> times = {0.25, 0.5, 1.0 / 3.0 + 0.5};
  IO::StepSeries series(s.dir, kBase, 3, comm);
  TEST_EQUALITY(series.dataFileName(2), "run.step0002.h5");
  TEST_EQUALITY(series.indexFileName(), "run.xmf");
  for (int k = 1; k <= 3; ++k) {
    writeSteps(series, s.disc, times, k, k, comm);
    TEST_EQUALITY(series.stepsWritten(), k);
    checkSeries(s.dir.path(), series, s.disc, times, k, *comm, out, success);  // complete after every step
  }
  if (comm->getRank() == 0) {
    for (int k = 1; k <= 3; ++k) TEST_ASSERT(exists(s.dir.path() + "/run.step000" + std::to_string(k) + ".h5"));
    TEST_ASSERT(!exists(s.dir.path() + "/run.h5"));
  }
}

// Every other step written (a run's Output/Step Stride): the steps between
// have no file and no index entry; a series continued after them lists the
// written ones only.
TEUCHOS_UNIT_TEST(StepSeries, SkippedStepsHaveNoFile) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::vector<double> times = {0.5, 1.0, 1.5, 2.0, 2.5};
  {
    IO::StepSeries series(s.dir, kBase, 5, comm);
    writeSteps(series, s.disc, times, 2, 2, comm);
    writeSteps(series, s.disc, times, 4, 4, comm);
    TEST_EQUALITY(series.stepsWritten(), 4);
  }
  IO::StepSeries continued(s.dir, kBase, 5, comm);
  continued.continueAfter({times.begin(), times.begin() + 4}, {false, true, false, true});
  writeSteps(continued, s.disc, times, 5, 5, comm);
  if (comm->getRank() != 0) return;
  const auto files = listDirectory(s.dir.path());
  for (int k = 1; k <= 5; ++k)
    TEST_EQUALITY(std::count(files.begin(), files.end(), continued.dataFileName(k)), k % 2 == 0 || k == 5 ? 1 : 0);
  const auto index = readIndex(s.dir.path() + "/run.xmf", out, success);
  TEST_EQUALITY(index.size(), size_t(3));
  if (index.size() != 3) return;
  TEST_EQUALITY(index[0].time, times[1]);
  TEST_EQUALITY(index[1].time, times[3]);
  TEST_EQUALITY(index[2].time, times[4]);
  for (int k : {2, 4, 5}) checkStepFile(s.dir.path() + "/" + continued.dataFileName(k), k, times[k - 1], s.disc,
                                        comm->getSize(), out, success);
}

// Step numbers as wide as the last step needs.
TEUCHOS_UNIT_TEST(StepSeries, FileNames) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  TEST_EQUALITY(IO::StepSeries(s.dir, "a", 1, comm).dataFileName(1), "a.h5");
  TEST_EQUALITY(IO::StepSeries(s.dir, "a", 9999, comm).dataFileName(12), "a.step0012.h5");
  TEST_EQUALITY(IO::StepSeries(s.dir, "a", 10000, comm).dataFileName(12), "a.step00012.h5");
  const IO::StepSeries series(s.dir, "a", 3, comm);
  for (const char* name : {"a.h5", "a.step1.h5", "a.step00007.h5"}) TEST_ASSERT(series.isDataFileName(name));
  for (const char* name : {"b.h5", "a.step.h5", "a.stepx1.h5", "a.step0001.h5.bak", ".a.step0001.h5.12.tmp",
                           "ab.step0001.h5", "a.xmf"})
    TEST_ASSERT(!series.isDataFileName(name));
}

// A series of 5, then one of 2 in the same directory, then a one-step run,
// then a series of 2 again: each leaves only its own data files, from its
// first commit on; files of other Base Names stay.
TEUCHOS_UNIT_TEST(StepSeries, LaterRunsLeaveNoOldDataFile) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::string dir = s.dir.path();
  const std::vector<double> times = {1, 2, 3, 4, 5};
  putFile(comm, dir + "/other.step0001.h5");
  putFile(comm, dir + "/run.step0001.h5.bak");
  {
    IO::StepSeries five(s.dir, kBase, 5, comm);
    writeSteps(five, s.disc, times, 1, 5, comm);
    checkSeries(dir, five, s.disc, times, 5, *comm, out, success);
  }
  {
    IO::StepSeries two(s.dir, kBase, 2, comm);
    writeSteps(two, s.disc, times, 1, 1, comm);
    checkSeries(dir, two, s.disc, times, 1, *comm, out, success);  // steps 2-5 of the old run gone at the first commit
    writeSteps(two, s.disc, times, 2, 2, comm);
    checkSeries(dir, two, s.disc, times, 2, *comm, out, success);
  }
  {
    IO::StepSeries one(s.dir, kBase, 1, comm);
    writeSteps(one, s.disc, times, 1, 1, comm);
    if (comm->getRank() == 0) {
      TEST_ASSERT(exists(dir + "/run.h5"));
      for (const std::string& name : listDirectory(dir)) {
        out << "after the one-step run: " << name << "\n";
        TEST_ASSERT(!one.isDataFileName(name) || name == "run.h5");  // no step file left
      }
      TEST_ASSERT(contains(readFile(dir + "/run.xmf"), "run.h5:/nodes/displacement"));
      TEST_ASSERT(!contains(readFile(dir + "/run.xmf"), "Temporal"));  // today's index
    }
  }
  {
    IO::StepSeries two(s.dir, kBase, 2, comm);
    writeSteps(two, s.disc, times, 1, 2, comm);
    checkSeries(dir, two, s.disc, times, 2, *comm, out, success);
    if (comm->getRank() == 0) TEST_ASSERT(!exists(dir + "/run.h5"));  // the one-step run's data file gone
  }
  if (comm->getRank() == 0) {
    TEST_EQUALITY(readFile(dir + "/other.step0001.h5"), "another result");  // other names untouched
    TEST_EQUALITY(readFile(dir + "/run.step0001.h5.bak"), "another result");
  }
}

// Step 2's data file cannot take its name (a directory is in the way): the
// failure is the same on every rank, step 1's set stays complete, and once
// the obstacle is gone step 2 is written.
TEUCHOS_UNIT_TEST(StepSeries, FailedDataFileKeepsEarlierSteps) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::string dir = s.dir.path();
  const std::vector<double> times = {0.5, 1.0, 1.5};
  IO::StepSeries series(s.dir, kBase, 3, comm);
  writeSteps(series, s.disc, times, 1, 1, comm);
  if (comm->getRank() == 0) ::mkdir((dir + "/run.step0002.h5").c_str(), 0755), writePlainFile(dir + "/run.step0002.h5/x", "");
  comm->barrier();
  const std::string m = expectCollective<RunFailure>("data file in the way", *comm, out, success, [&] {
    writeSteps(series, s.disc, times, 2, 2, comm);
  });
  TEST_ASSERT(contains(m, "run.step0002.h5"));  // names the file
  TEST_EQUALITY(series.stepsWritten(), 1);
  checkSeries(dir, series, s.disc, times, 1, *comm, out, success);
  if (comm->getRank() == 0) removeTree(dir + "/run.step0002.h5");
  comm->barrier();
  writeSteps(series, s.disc, times, 2, 3, comm);  // the step again, and the next
  checkSeries(dir, series, s.disc, times, 3, *comm, out, success);
}

// A text file of step 2 cannot take its name, after step 2's data file and
// index have theirs: the summary in the directory is still step 1's, and
// every file of step 1 is there and readable (the index lists step 2 too,
// whose file is complete).
TEUCHOS_UNIT_TEST(StepSeries, FailedTextFileKeepsSummaryTrue) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::string dir = s.dir.path();
  const std::vector<double> times = {0.5, 1.0};
  IO::StepSeries series(s.dir, kBase, 2, comm);
  writeSteps(series, s.disc, times, 1, 1, comm);
  if (comm->getRank() == 0) ::mkdir((dir + "/run.extra.txt").c_str(), 0755), writePlainFile(dir + "/run.extra.txt/x", "");
  comm->barrier();
  std::vector<IO::TextFile> withExtra = texts(2);
  withExtra.insert(withExtra.begin(), {"run.extra.txt", "extra"});
  expectCollective<RunFailure>("text file in the way", *comm, out, success, [&] {
    series.writeStep(2, times[1], s.disc, stepResult(s.disc, 2, *comm), withExtra);
  });
  TEST_EQUALITY(series.stepsWritten(), 1);
  if (comm->getRank() == 0) {
    for (const IO::TextFile& t : texts(1)) TEST_EQUALITY(readFile(dir + "/" + t.name), t.text);  // step 1's summary
    TEST_ASSERT(temporariesIn(dir).empty());
    const std::vector<IndexStep> index = readIndex(dir + "/run.xmf", out, success);
    TEST_COMPARE(index.size(), >=, size_t(1));
    for (size_t k = 0; k < index.size(); ++k)
      checkStepFile(dir + "/" + series.dataFileName(k + 1), k + 1, times[k], s.disc, comm->getSize(), out, success);
  }
}

// Wrong arguments in step 2 (a field of the wrong size on the last rank):
// refused before anything is written, step 1's set untouched.
TEUCHOS_UNIT_TEST(StepSeries, WrongArgumentsKeepEarlierSteps) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::vector<double> times = {0.5, 1.0};
  IO::StepSeries series(s.dir, kBase, 2, comm);
  writeSteps(series, s.disc, times, 1, 1, comm);
  IO::StepResult bad = stepResult(s.disc, 2, *comm);
  if (comm->getRank() == comm->getSize() - 1) bad.cellFields[0].values.push_back(0);
  const std::string m = expectCollective<CollectiveError>("field of the wrong size", *comm, out, success, [&] {
    series.writeStep(2, times[1], s.disc, bad, texts(2));
  });
  TEST_ASSERT(contains(m, "cell_id"));
  checkSeries(s.dir.path(), series, s.disc, times, 1, *comm, out, success);
}

// The series' own refusals, each before anything is written.
TEUCHOS_UNIT_TEST(StepSeries, Refusals) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const auto result = stepResult(s.disc, 1, *comm);
  expectCollective<CollectiveError>("base name with a directory", *comm, out, success,
                                    [&] { IO::StepSeries(s.dir, "sub/run", 2, comm); });
  expectCollective<CollectiveError>("no steps", *comm, out, success, [&] { IO::StepSeries(s.dir, kBase, 0, comm); });
  IO::StepSeries series(s.dir, kBase, 2, comm);
  auto refused = [&](const std::string& label, int step, double time, const IO::StepResult& r,
                     const std::vector<IO::TextFile>& t, const std::string& says) {
    const std::string m = expectCollective<CollectiveError>(label, *comm, out, success,
                                                            [&] { series.writeStep(step, time, s.disc, r, t); });
    TEST_ASSERT(contains(m, says));
  };
  refused("step 0", 0, 1.0, result, texts(1), "the next step is 1 or a later one, not 0");
  refused("time not finite", 1, std::nan(""), result, texts(1), "not finite");
  refused("no summary", 1, 1.0, result, {}, "no text file replaced last");
  refused("text named as a step file", 1, 1.0, result, {{"run.step0002.h5", "x"}}, "run.step0002.h5");
  IO::StepResult timed = result;
  timed.attributes.numbers.push_back({"time", 3.0});
  refused("attribute time", 1, 1.0, timed, texts(1), "attribute time");
  if (comm->getSize() > 1)
    refused("times differ between ranks", 1, 1.0 + comm->getRank(), result, texts(1), "another step or time");
  if (comm->getRank() == 0) TEST_ASSERT(listDirectory(s.dir.path()) == std::vector<std::string>{".tribos.lock"});
  series.writeStep(1, 1.0, s.disc, result, texts(1));
  refused("time going back", 2, 1.0, stepResult(s.disc, 2, *comm), texts(2), "does not follow the time 1 of step 1");
  series.writeStep(2, 2.0, s.disc, stepResult(s.disc, 2, *comm), texts(2));
  refused("beyond the last step", 3, 3.0, result, texts(3), "the series has 2 steps");
}

// A one-step series writes what ResultWriter::write writes: the same index,
// byte for byte, and the same data in every dataset it names.
TEUCHOS_UNIT_TEST(StepSeries, OneStepIsTheSingleResult) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const IO::OutputDirectory single(s.scratch.path() + "/single", comm);
  const IO::StepResult r = stepResult(s.disc, 1, *comm);
  IO::StepSeries(s.dir, kBase, 1, comm).writeStep(1, 1.0, s.disc, r, texts(1));
  {
    IO::ResultSet files(single, comm);
    const std::string h5 = files.add("run.h5"), xmf = files.add("run.xmf");
    IO::ResultWriter(s.disc, comm).write(h5, "run.h5", xmf, r.uOwned, r.nodeFields, r.cellFields, r.pointSets,
                                         r.attributes);
    files.commit();
  }
  if (comm->getRank() != 0) return;
  const std::string xmf = readFile(s.dir.path() + "/run.xmf");
  TEST_EQUALITY(xmf, readFile(single.path() + "/run.xmf"));
  const H5Reader a(s.dir.path() + "/run.h5"), b(single.path() + "/run.h5");
  for (const char* d : {"/mesh/geometry", "/nodes/displacement", "/cells/cell_id", "/points/contact/geometry",
                        "/points/contact/slip", "/points/contact/status"}) {
    out << "dataset " << d << "\n";
    TEST_ASSERT(contains(xmf, std::string("run.h5:") + d));
    TEST_ASSERT(a.read<double>(d) == b.read<double>(d));
  }
  TEST_ASSERT(a.read<long long>("/mesh/topology") == b.read<long long>("/mesh/topology"));
  TEST_EQUALITY(a.number("step"), -12345.0);  // no attributes of a series
}

// Texts that grow by steps: at the first commit the file is what the step
// gives (its header and rows), at each later one the step's rows are
// appended; the others are replaced. Each step's texts are made knowing its
// data file, whose digest is that of the committed file. The index, written
// step by step over its closing tags, is at every step the index of all the
// steps written (checkSeries parses it and reads every dataset it names).
TEUCHOS_UNIT_TEST(StepSeries, AppendedTextsGrowByStep) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  const std::string dir = s.dir.path();
  const std::vector<double> times = {0.5, 1.0, 1.5, 2.0};
  IO::StepSeries series(s.dir, kBase, 4, comm);
  std::string expected = "header\n";
  for (int k = 1; k <= 4; ++k) {
    IO::StepFile seen;
    series.writeStep(k, times[k - 1], s.disc, stepResult(s.disc, k, *comm), [&](const IO::StepFile& f) {
      seen = f;
      const std::string row = "row " + std::to_string(k) + " " + f.name + "\n";
      std::vector<IO::TextFile> t = texts(k);
      t.insert(t.end() - 1, IO::TextFile{kBase + ".rows.txt", (k == 1 ? "header\n" : "") + row, true});
      return t;
    });
    expected += "row " + std::to_string(k) + " " + series.dataFileName(k) + "\n";
    TEST_EQUALITY(seen.step, k);
    TEST_EQUALITY(seen.time, times[k - 1]);
    TEST_EQUALITY(seen.name, series.dataFileName(k));
    checkSeries(dir, series, s.disc, times, k, *comm, out, success);
    if (comm->getRank() == 0) {
      TEST_EQUALITY(readFile(dir + "/run.rows.txt"), expected);
      std::string error;
      TEST_EQUALITY(IO::sha256OfFile(dir + "/" + seen.name, error), seen.sha256);
      TEST_EQUALITY(error, "");
      TEST_EQUALITY(seen.sha256.size(), 64u);
    }
  }
  // A new run of the directory starts the grown file again.
  IO::StepSeries again(s.dir, kBase, 2, comm);
  again.writeStep(1, 1.0, s.disc, stepResult(s.disc, 1, *comm),
                  std::vector<IO::TextFile>{{kBase + ".rows.txt", "header\nrow 1\n", true}, {kBase + ".json", "{}\n"}});
  if (comm->getRank() == 0) TEST_EQUALITY(readFile(dir + "/run.rows.txt"), "header\nrow 1\n");
}

// The SHA-256 of a file is the standard one (FIPS 180-4's example "abc"),
// and a file that cannot be read is named.
TEUCHOS_UNIT_TEST(StepSeries, FileDigest) {
  const auto comm = Tpetra::getDefaultComm();
  Setup s(comm);
  if (comm->getRank() != 0) return;
  const std::string path = s.dir.path() + "/abc.txt";
  writePlainFile(path, "abc");
  std::string error;
  TEST_EQUALITY(IO::sha256OfFile(path, error), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  TEST_EQUALITY(error, "");
  TEST_EQUALITY(IO::sha256OfFile(path + ".missing", error), "");
  TEST_ASSERT(contains(error, "abc.txt.missing"));
}
