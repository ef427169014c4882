// The HDF5 file and XDMF index of a small mesh, read back with the HDF5 C
// API: datasets of the right shapes and values in the rank-contiguous
// numbering, point sets that are empty on every rank or on all but rank 0,
// root attributes, an index whose every DataItem names an existing dataset of
// its shape. And the collective failures: wrong arguments, a file that cannot
// be created, an index that cannot be written.
#include <hdf5.h>
#include <sys/stat.h>

#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <map>
#include <regex>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultReader.hpp"
#include "Tribos_ResultSet.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

struct Expected {
  std::vector<int> nodeAt;  // output row -> mesh node
  std::vector<int> cellAt;  // output row -> mesh cell
};

// The output order of nodes (nodeIndex) and cells (ranks' local cells in rank order).
Expected outputOrder(const Mesh::Discretization& disc, int numRanks) {
  Expected e;
  // Every rank's part, cut again from the whole mesh.
  e.nodeAt.resize(disc.numMeshNodes());
  const Mesh::Mesh whole = Mesh::generateBox(disc.spec);
  for (int r = 0; r < numRanks; ++r) {
    const Mesh::Discretization other(whole, disc.spec, {"Structured", {std::max(2, numRanks), 1, 1}, 1}, numRanks, r);
    for (int n = 0; n < other.part.numNodes(); ++n) e.nodeAt[other.nodeIndex()[n]] = other.meshNode(n);
    for (int c = 0; c < other.part.numCells(); ++c) e.cellAt.push_back(other.meshCell(c));
  }
  return e;
}

struct Result {
  std::vector<IO::Field> nodeFields, cellFields;
  std::vector<IO::PointSet> points;
  IO::ResultAttributes attributes;
};

// temperature = 100 + node, cell_id = cell; point sets: "empty" everywhere,
// "root_only" with 4 points on rank 0, "every_rank" with r + 1 points on rank r.
Result makeResult(const Mesh::Discretization& disc, const Comm& comm) {
  Result r;
  IO::Field temperature{"temperature", 1, {}}, cellId{"cell_id", 1, {}};
  for (int n : disc.ownedNodes()) temperature.values.push_back(100 + disc.meshNode(n));
  for (int c = 0; c < disc.part.numCells(); ++c) cellId.values.push_back(disc.meshCell(c));
  r.nodeFields = {temperature};
  r.cellFields = {cellId};
  IO::PointSet empty{"empty", {}, {IO::Field{"normal_force", 1, {}}, IO::Field{"slip", 3, {}}}};
  IO::PointSet rootOnly{"root_only", {}, {IO::Field{"normal_force", 1, {}}, IO::Field{"slip", 3, {}}}};
  if (comm.getRank() == 0)
    for (int k = 0; k < 4; ++k) {
      rootOnly.coords.push_back({double(k), 0.5, 1.0});
      rootOnly.fields[0].values.push_back(10.0 * k);
      for (int d = 1; d <= 3; ++d) rootOnly.fields[1].values.push_back(d * k);
    }
  IO::PointSet everyRank{"every_rank", {}, {IO::Field{"owner", 1, {}}}};
  for (int j = 0; j <= comm.getRank(); ++j) {
    everyRank.coords.push_back({double(comm.getRank()), double(j), 0});
    everyRank.fields[0].values.push_back(comm.getRank());
  }
  r.points = {empty, rootOnly, everyRank};
  r.attributes.text = {{"stop_reason", "converged\twithin tolerance"}, {"problem", "brick"}, {"note", ""}};
  r.attributes.numbers = {{"converged", 1.0}, {"solver_converged", 0.0}};
  return r;
}

// A result of the 6 x 2 x 2 box written and committed to a scratch directory.
struct Written {
  explicit Written(const RCP<const Comm>& comm)
      : scratch(comm, "result_writer"), disc(boxDiscretization(6, 2, 2, *comm)), dir(scratch.path() + "/out", comm) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the checks report what they find
    const Result r = makeResult(disc, *comm);
    IO::ResultSet files(dir, comm);
    const std::string h5 = files.add("solution.h5"), xmf = files.add("solution.xmf");
    IO::ResultWriter(disc, comm).write(h5, "solution.h5", xmf, displacementOf(disc), r.nodeFields, r.cellFields, r.points,
                                       r.attributes);
    files.commit();
  }
  std::string h5Path() const { return dir.path() + "/solution.h5"; }
  ScratchDirectory scratch;
  Mesh::Discretization disc;
  IO::OutputDirectory dir;
};

// Rank 0: no temporaries left after the commit, and the file opens.
bool opens(const Written& w, const H5Reader& h5, Teuchos::FancyOStream& out, bool& success) {
  TEST_ASSERT(temporariesIn(w.dir.path()).empty());  // no temporaries after commit
  TEST_COMPARE(h5.id, >=, 0);                        // the h5 file opens
  return h5.id >= 0;
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
    message = e.what(), kind = "another exception";
  }
  out << label << ": " << message << "\n";
  TEST_EQUALITY(kind, "expected");
  TEST_EQUALITY(message, broadcastFromRoot(comm, message));  // the same message on every rank
  TEST_EQUALITY(message.find('\n'), std::string::npos);          // one line
  return message;
}

// Writing to temporaries of a scratch output directory, nothing committed.
struct Failing {
  explicit Failing(const RCP<const Comm>& comm)
      : scratch(comm, "result_writer"),
        disc(boxDiscretization(6, 2, 2, *comm)),
        dir(scratch.path() + "/fail", comm),
        u(displacementOf(disc)),
        root(comm->getRank() == 0),
        last(comm->getRank() == comm->getSize() - 1),
        h5(dir.temporary("solution.h5")),
        xmf(dir.temporary("solution.xmf")),
        writer(disc, comm) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ScratchDirectory scratch;
  Mesh::Discretization disc;
  IO::OutputDirectory dir;
  std::vector<double> u;
  bool root, last;
  std::string h5, xmf;
  IO::ResultWriter writer;
};

}  // namespace

TEUCHOS_UNIT_TEST(ResultWriter, MeshAndFieldsInOutputNumbering) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  if (comm->getRank() != 0) return;
  const H5Reader h5(w.h5Path());
  if (!opens(w, h5, out, success)) return;
  const auto& disc = w.disc;
  const Expected order = outputOrder(disc, comm->getSize());
  const Mesh::Mesh whole = Mesh::generateBox(disc.spec);
  const long long N = whole.numNodes(), C = whole.numCells(), npc = whole.nodesPerCell();
  TEST_ASSERT((h5.shape("/mesh/geometry") == std::vector<long long>{N, 3}));
  TEST_ASSERT((h5.shape("/mesh/topology") == std::vector<long long>{C, npc}));
  TEST_ASSERT((h5.shape("/nodes/displacement") == std::vector<long long>{N, 3}));
  TEST_ASSERT((h5.shape("/nodes/temperature") == std::vector<long long>{N, 1}));
  TEST_ASSERT((h5.shape("/cells/cell_id") == std::vector<long long>{C, 1}));
  const auto xyz = h5.read<double>("/mesh/geometry"), u = h5.read<double>("/nodes/displacement"),
             t = h5.read<double>("/nodes/temperature"), id = h5.read<double>("/cells/cell_id");
  const auto topo = h5.read<long long>("/mesh/topology");
  TEST_EQUALITY(xyz.size(), size_t(3 * N));
  TEST_EQUALITY(u.size(), size_t(3 * N));
  TEST_EQUALITY(t.size(), size_t(N));
  bool nodesOk = xyz.size() == size_t(3 * N) && u.size() == size_t(3 * N) && t.size() == size_t(N);
  for (long long i = 0; nodesOk && i < N; ++i) {
    const int n = order.nodeAt[i];
    nodesOk = t[i] == 100 + n;
    for (int d = 0; d < 3; ++d) nodesOk = nodesOk && xyz[3 * i + d] == whole.coords[n][d] && u[3 * i + d] == displacementAt(whole.coords[n], n, d);
  }
  TEST_ASSERT(nodesOk);  // geometry, displacement and temperature in the output numbering
  TEST_EQUALITY(topo.size(), size_t(C * npc));
  TEST_EQUALITY(id.size(), size_t(C));
  TEST_EQUALITY(order.cellAt.size(), size_t(C));
  bool cellsOk = topo.size() == size_t(C * npc) && id.size() == size_t(C) && order.cellAt.size() == size_t(C);
  for (long long i = 0; cellsOk && i < C; ++i) {
    const int c = order.cellAt[i];
    cellsOk = id[i] == c;
    for (int k = 0; k < npc; ++k) cellsOk = cellsOk && order.nodeAt[topo[npc * i + k]] == whole.cell(c)[k];
  }
  TEST_ASSERT(cellsOk);  // topology and cell_id in the output numbering
}

// Point sets empty on every rank, on all but rank 0, and with r + 1 points on rank r.
TEUCHOS_UNIT_TEST(ResultWriter, PointSets) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  if (comm->getRank() != 0) return;
  const H5Reader h5(w.h5Path());
  if (!opens(w, h5, out, success)) return;
  const int numRanks = comm->getSize();
  for (const char* f : {"/points/empty/geometry", "/points/empty/normal_force", "/points/empty/slip"}) {
    out << "empty point set dataset " << f << "\n";
    TEST_ASSERT(h5.has(f));
  }
  TEST_ASSERT((h5.shape("/points/empty/geometry") == std::vector<long long>{0, 3}));
  TEST_ASSERT((h5.shape("/points/empty/normal_force") == std::vector<long long>{0, 1}));
  TEST_ASSERT((h5.shape("/points/empty/slip") == std::vector<long long>{0, 3}));

  TEST_ASSERT((h5.shape("/points/root_only/geometry") == std::vector<long long>{4, 3}));
  const auto g = h5.read<double>("/points/root_only/geometry"), nf = h5.read<double>("/points/root_only/normal_force"),
             slip = h5.read<double>("/points/root_only/slip");
  TEST_EQUALITY(g.size(), size_t(12));
  TEST_EQUALITY(nf.size(), size_t(4));
  TEST_EQUALITY(slip.size(), size_t(12));
  bool ok = g.size() == 12 && nf.size() == 4 && slip.size() == 12;
  for (int k = 0; ok && k < 4; ++k) {
    ok = g[3 * k] == k && g[3 * k + 1] == 0.5 && g[3 * k + 2] == 1.0 && nf[k] == 10.0 * k;
    for (int d = 1; d <= 3; ++d) ok = ok && slip[3 * k + d - 1] == d * k;
  }
  TEST_ASSERT(ok);  // root_only values

  const long long total = numRanks * (numRanks + 1) / 2;
  TEST_ASSERT((h5.shape("/points/every_rank/geometry") == std::vector<long long>{total, 3}));
  const auto eg = h5.read<double>("/points/every_rank/geometry"), owner = h5.read<double>("/points/every_rank/owner");
  TEST_EQUALITY(eg.size(), size_t(3 * total));
  TEST_EQUALITY(owner.size(), size_t(total));
  ok = eg.size() == size_t(3 * total) && owner.size() == size_t(total);
  for (int r = 0, i = 0; ok && r < numRanks; ++r)
    for (int j = 0; ok && j <= r; ++j, ++i) ok = eg[3 * i] == r && eg[3 * i + 1] == j && owner[i] == r;
  TEST_ASSERT(ok);  // every_rank blocks in rank order
}

TEUCHOS_UNIT_TEST(ResultWriter, RootAttributes) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  if (comm->getRank() != 0) return;
  const H5Reader h5(w.h5Path());
  if (!opens(w, h5, out, success)) return;
  TEST_EQUALITY(h5.text("stop_reason"), "converged\twithin tolerance");
  TEST_EQUALITY(h5.text("problem"), "brick");
  TEST_EQUALITY(h5.text("note"), "");
  TEST_EQUALITY(h5.number("converged"), 1.0);
  TEST_EQUALITY(h5.number("solver_converged"), 0.0);
}

// IO::readRootNumber, as a restart reads a Dynamics step's running sums:
// the number back to the bit, and a missing attribute or a text refused,
// naming the file and the attribute.
TEUCHOS_UNIT_TEST(ResultReader, RootNumber) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  TEST_EQUALITY(IO::readRootNumber(w.h5Path(), "converged"), 1.0);
  const auto refusal = [&](const std::string& name) {
    try {
      IO::readRootNumber(w.h5Path(), name);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no refusal");
  };
  TEST_ASSERT(refusal("external_work").find(w.h5Path() + ", root attribute external_work: no such attribute") !=
              std::string::npos);
  TEST_ASSERT(refusal("problem").find("root attribute problem: not a number") != std::string::npos);
}

// Every DataItem of the index names solution.h5 and an existing dataset of
// the shape the index gives; one grid per point set, the empty one with 0 points.
TEUCHOS_UNIT_TEST(ResultWriter, XdmfIndex) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  if (comm->getRank() != 0) return;
  const H5Reader h5(w.h5Path());
  if (!opens(w, h5, out, success)) return;
  const std::string xmf = readFile(w.dir.path() + "/solution.xmf");
  const std::regex item("<DataItem Dimensions=\"([0-9]+) ([0-9]+)\"[^>]*>([^:<]+):([^<]+)</DataItem>");
  int items = 0;
  for (std::sregex_iterator m(xmf.begin(), xmf.end(), item), end; m != end; ++m, ++items) {
    const std::string file = (*m)[3], dataset = (*m)[4];
    const std::vector<long long> dims = {std::stoll((*m)[1]), std::stoll((*m)[2])};
    out << "DataItem " << file << ":" << dataset << "\n";
    TEST_EQUALITY(file, "solution.h5");
    TEST_ASSERT(h5.has(dataset));
    TEST_ASSERT(h5.shape(dataset) == dims);
  }
  TEST_EQUALITY(items, 5 + 3 + 3 + 2);  // number of DataItems
  TEST_COMPARE(std::count(xmf.begin(), xmf.end(), '\n'), >, 10);  // index complete
  TEST_ASSERT(contains(xmf, "</Xdmf>"));
  for (const char* grid : {"body", "empty", "root_only", "every_rank"}) {
    out << "grid " << grid << "\n";
    TEST_ASSERT(contains(xmf, std::string("<Grid Name=\"") + grid + "\""));
  }
  TEST_ASSERT(contains(xmf, "TopologyType=\"Polyvertex\" NumberOfElements=\"0\""));  // empty grid of 0 points
}

// Space reserved before the data is not left at the end of the file.
TEUCHOS_UNIT_TEST(ResultWriter, NoReservedSpaceLeft) {
  const auto comm = Tpetra::getDefaultComm();
  const Written w(comm);
  if (comm->getRank() != 0) return;
  const H5Reader h5(w.h5Path());
  if (!opens(w, h5, out, success)) return;
  const auto& disc = w.disc;
  struct stat st = {};
  const long long data = 8LL * (disc.numMeshNodes() * 7LL + disc.numMeshCells() * 9LL + 4 * 7 + 6 * comm->getSize());
  TEST_EQUALITY(::stat(w.h5Path().c_str(), &st), 0);
  out << "file size " << st.st_size << " for " << data << " bytes of data\n";
  TEST_COMPARE(st.st_size, <, data + 48 * 1024);
}

// A field of the wrong size on the last rank only: refused before any file exists.
TEUCHOS_UNIT_TEST(ResultWriterFailure, WrongFieldSize) {
  const auto comm = Tpetra::getDefaultComm();
  Failing f(comm);
  std::vector<IO::Field> bad = {IO::Field{"temperature", 1, std::vector<double>(f.disc.ownedNodes().size() + f.last, 0.0)}};
  const std::string m = expectCollective<CollectiveError>("wrong field size", *comm, out, success, [&] {
    f.writer.write(f.h5, "solution.h5", f.xmf, f.u, bad, {});
  });
  TEST_ASSERT(contains(m, "temperature"));  // the message names the field
  if (f.root) {
    TEST_ASSERT(!exists(f.h5));  // nothing written for wrong arguments
    TEST_ASSERT(!exists(f.xmf));
  }
}

TEUCHOS_UNIT_TEST(ResultWriterFailure, NamesDifferBetweenRanks) {
  const auto comm = Tpetra::getDefaultComm();
  if (comm->getSize() == 1) {
    out << "skipped on one rank\n";
    return;
  }
  Failing f(comm);
  std::vector<IO::Field> named = {IO::Field{f.last ? "heat" : "temperature", 1,
                                            std::vector<double>(f.disc.ownedNodes().size(), 0.0)}};
  expectCollective<CollectiveError>("names differ between ranks", *comm, out, success, [&] {
    f.writer.write(f.h5, "solution.h5", f.xmf, f.u, named, {});
  });
  if (f.root) TEST_ASSERT(!exists(f.h5));  // nothing written for differing names
}

// A file that cannot be created, with and without the reservation before it.
TEUCHOS_UNIT_TEST(ResultWriterFailure, FileCannotBeCreated) {
  const auto comm = Tpetra::getDefaultComm();
  Failing f(comm);
  for (bool reserve : {true, false}) {
    f.writer.reserveSpace(reserve);
    const std::string m = expectCollective<RunFailure>(std::string("missing directory") + (reserve ? "" : ", not reserved"),
                                                       *comm, out, success, [&] {
      f.writer.write(f.dir.path() + "/missing/solution.h5", "solution.h5", f.xmf, f.u, {}, {});
    });
    TEST_ASSERT(contains(m, "solution.h5"));  // names the file
    TEST_ASSERT(contains(m, "uch file or directory"));  // and the reason
    if (!reserve) TEST_ASSERT(contains(m, "H5Fcreate"));  // and the call
  }
}

// An index that cannot be written: the HDF5 file goes too.
TEUCHOS_UNIT_TEST(ResultWriterFailure, IndexNotWritable) {
  const auto comm = Tpetra::getDefaultComm();
  Failing f(comm);
  f.writer.reserveSpace(true);
  const std::string m = expectCollective<RunFailure>("index not writable", *comm, out, success, [&] {
    f.writer.write(f.h5, "solution.h5", f.dir.path() + "/missing/solution.xmf", f.u, {}, {});
  });
  TEST_ASSERT(contains(m, "XDMF"));  // the message says it is the index
  if (f.root) {
    TEST_ASSERT(!exists(f.h5));  // the HDF5 file of a failed index is removed
    TEST_ASSERT(temporariesIn(f.dir.path()).empty());
  }
}
