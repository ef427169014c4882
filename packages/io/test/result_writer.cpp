// The HDF5 file and XDMF index of a small mesh, read back with the HDF5 C
// API: datasets of the right shapes and values in the rank-contiguous
// numbering, point sets that are empty on every rank or on all but rank 0,
// root attributes, an index whose every DataItem names an existing dataset of
// its shape. And the collective failures: wrong arguments, a file that cannot
// be created, an index that cannot be written.
#include <hdf5.h>
#include <sys/stat.h>

#include <Tpetra_Core.hpp>

#include <iostream>
#include <map>
#include <regex>

#include "IoTestSupport.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_OutputDirectory.hpp"
#include "Tribos_ResultSet.hpp"

using namespace Tribos;
using namespace Tribos::Test;

namespace {

// Read access to a finished file (serial HDF5, rank 0).
class H5Reader {
 public:
  explicit H5Reader(const std::string& path) : id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5Reader() {
    if (id >= 0) H5Fclose(id);
  }
  bool has(const std::string& dataset) const {
    const hid_t d = H5Dopen2(id, dataset.c_str(), H5P_DEFAULT);
    if (d >= 0) H5Dclose(d);
    return d >= 0;
  }
  std::vector<long long> shape(const std::string& dataset) const {
    const hid_t d = H5Dopen2(id, dataset.c_str(), H5P_DEFAULT);
    if (d < 0) return {};
    const hid_t space = H5Dget_space(d);
    hsize_t dims[8];
    const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
    H5Sclose(space);
    H5Dclose(d);
    return std::vector<long long>(dims, dims + std::max(rank, 0));
  }
  template <class T>
  std::vector<T> read(const std::string& dataset) const {
    long long n = 1;
    for (long long d : shape(dataset)) n *= d;
    std::vector<T> values(static_cast<size_t>(n));
    const hid_t d = H5Dopen2(id, dataset.c_str(), H5P_DEFAULT);
    const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
    if (d >= 0 && n > 0) H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    if (d >= 0) H5Dclose(d);
    return values;
  }
  std::string text(const std::string& attribute) const {
    const hid_t a = H5Aopen(id, attribute.c_str(), H5P_DEFAULT);
    if (a < 0) return "<missing>";
    const hid_t type = H5Aget_type(a);
    std::string value(H5Tget_size(type), '\0');
    H5Aread(a, type, &value[0]);
    H5Tclose(type);
    H5Aclose(a);
    return value.substr(0, value.find('\0'));
  }
  double number(const std::string& attribute) const {
    double v = -12345;
    const hid_t a = H5Aopen(id, attribute.c_str(), H5P_DEFAULT);
    if (a >= 0) H5Aread(a, H5T_NATIVE_DOUBLE, &v), H5Aclose(a);
    return v;
  }
  hid_t id;
};

struct Expected {
  std::vector<int> nodeAt;  // output row -> mesh node
  std::vector<int> cellAt;  // output row -> mesh cell
};

// The output order of nodes (nodeIndex) and cells (ranks' local cells in rank order).
Expected outputOrder(const Mesh::Discretization& disc, int numRanks) {
  Expected e;
  e.nodeAt.resize(disc.mesh.numNodes());
  for (int n = 0; n < disc.mesh.numNodes(); ++n) e.nodeAt[disc.nodeIndex()[n]] = n;
  for (int r = 0; r < numRanks; ++r) {
    const Mesh::Discretization other(disc.mesh, disc.spec, {"Structured", {std::max(2, numRanks), 1, 1}, 1}, numRanks, r);
    for (int c : other.localCells()) e.cellAt.push_back(c);
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
  for (int n : disc.ownedNodes()) temperature.values.push_back(100 + n);
  for (int c : disc.localCells()) cellId.values.push_back(c);
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

void checkMeshData(const H5Reader& h5, const Mesh::Discretization& disc, const Expected& order) {
  const long long N = disc.mesh.numNodes(), C = disc.mesh.numCells(), npc = disc.mesh.nodesPerCell();
  CHECK((h5.shape("/mesh/geometry") == std::vector<long long>{N, 3}), "geometry shape");
  CHECK((h5.shape("/mesh/topology") == std::vector<long long>{C, npc}), "topology shape");
  CHECK((h5.shape("/nodes/displacement") == std::vector<long long>{N, 3}), "displacement shape");
  CHECK((h5.shape("/nodes/temperature") == std::vector<long long>{N, 1}), "temperature shape");
  CHECK((h5.shape("/cells/cell_id") == std::vector<long long>{C, 1}), "cell_id shape");
  const auto xyz = h5.read<double>("/mesh/geometry"), u = h5.read<double>("/nodes/displacement"),
             t = h5.read<double>("/nodes/temperature"), id = h5.read<double>("/cells/cell_id");
  const auto topo = h5.read<long long>("/mesh/topology");
  const auto uExact = displacementOf(disc);
  bool nodesOk = xyz.size() == size_t(3 * N) && u.size() == size_t(3 * N) && t.size() == size_t(N);
  for (long long i = 0; nodesOk && i < N; ++i) {
    const int n = order.nodeAt[i];
    nodesOk = t[i] == 100 + n;
    for (int d = 0; d < 3; ++d) nodesOk = nodesOk && xyz[3 * i + d] == disc.mesh.coords[n][d] && u[3 * i + d] == uExact[3 * n + d];
  }
  CHECK(nodesOk, "geometry, displacement and temperature in the output numbering");
  bool cellsOk = topo.size() == size_t(C * npc) && id.size() == size_t(C) && order.cellAt.size() == size_t(C);
  for (long long i = 0; cellsOk && i < C; ++i) {
    const int c = order.cellAt[i];
    cellsOk = id[i] == c;
    for (int k = 0; k < npc; ++k) cellsOk = cellsOk && order.nodeAt[topo[npc * i + k]] == disc.mesh.cell(c)[k];
  }
  CHECK(cellsOk, "topology and cell_id in the output numbering");
}

void checkPointSets(const H5Reader& h5, int numRanks) {
  for (const char* f : {"/points/empty/geometry", "/points/empty/normal_force", "/points/empty/slip"})
    CHECK(h5.has(f), "empty point set dataset " << f << " exists");
  CHECK((h5.shape("/points/empty/geometry") == std::vector<long long>{0, 3}), "empty geometry is 0 x 3");
  CHECK((h5.shape("/points/empty/normal_force") == std::vector<long long>{0, 1}), "empty normal_force is 0 x 1");
  CHECK((h5.shape("/points/empty/slip") == std::vector<long long>{0, 3}), "empty slip is 0 x 3");

  CHECK((h5.shape("/points/root_only/geometry") == std::vector<long long>{4, 3}), "root_only geometry is 4 x 3");
  const auto g = h5.read<double>("/points/root_only/geometry"), nf = h5.read<double>("/points/root_only/normal_force"),
             slip = h5.read<double>("/points/root_only/slip");
  bool ok = g.size() == 12 && nf.size() == 4 && slip.size() == 12;
  for (int k = 0; ok && k < 4; ++k) {
    ok = g[3 * k] == k && g[3 * k + 1] == 0.5 && g[3 * k + 2] == 1.0 && nf[k] == 10.0 * k;
    for (int d = 1; d <= 3; ++d) ok = ok && slip[3 * k + d - 1] == d * k;
  }
  CHECK(ok, "root_only values");

  const long long total = numRanks * (numRanks + 1) / 2;
  CHECK((h5.shape("/points/every_rank/geometry") == std::vector<long long>{total, 3}), "every_rank geometry shape");
  const auto eg = h5.read<double>("/points/every_rank/geometry"), owner = h5.read<double>("/points/every_rank/owner");
  ok = eg.size() == size_t(3 * total) && owner.size() == size_t(total);
  for (int r = 0, i = 0; ok && r < numRanks; ++r)
    for (int j = 0; ok && j <= r; ++j, ++i) ok = eg[3 * i] == r && eg[3 * i + 1] == j && owner[i] == r;
  CHECK(ok, "every_rank blocks in rank order");
}

void checkAttributes(const H5Reader& h5) {
  CHECK(h5.text("stop_reason") == "converged\twithin tolerance", "stop_reason attribute: " << h5.text("stop_reason"));
  CHECK(h5.text("problem") == "brick", "problem attribute");
  CHECK(h5.text("note") == "", "empty text attribute");
  CHECK(h5.number("converged") == 1.0, "converged attribute");
  CHECK(h5.number("solver_converged") == 0.0, "solver_converged attribute");
}

// Every DataItem of the index names solution.h5 and an existing dataset of
// the shape the index gives; one grid per point set, the empty one with 0 points.
void checkIndex(const std::string& xmf, const H5Reader& h5) {
  const std::regex item("<DataItem Dimensions=\"([0-9]+) ([0-9]+)\"[^>]*>([^:<]+):([^<]+)</DataItem>");
  int items = 0;
  for (std::sregex_iterator m(xmf.begin(), xmf.end(), item), end; m != end; ++m, ++items) {
    const std::string file = (*m)[3], dataset = (*m)[4];
    const std::vector<long long> dims = {std::stoll((*m)[1]), std::stoll((*m)[2])};
    CHECK(file == "solution.h5", "index names " << file);
    CHECK(h5.has(dataset), "index names dataset " << dataset << " which exists");
    CHECK(h5.shape(dataset) == dims, "index gives the shape of " << dataset);
  }
  CHECK(items == 5 + 3 + 3 + 2, "number of DataItems: " << items);
  CHECK(std::count(xmf.begin(), xmf.end(), '\n') > 10 && contains(xmf, "</Xdmf>"), "index complete");
  for (const char* grid : {"body", "empty", "root_only", "every_rank"})
    CHECK(contains(xmf, std::string("<Grid Name=\"") + grid + "\""), "grid " << grid);
  CHECK(contains(xmf, "TopologyType=\"Polyvertex\" NumberOfElements=\"0\""), "empty grid of 0 points");
}

void writeAndReadBack(const std::string& base, const RCP<const Comm>& comm) {
  const auto disc = boxDiscretization(6, 2, 2, *comm);
  const Result r = makeResult(disc, *comm);
  IO::OutputDirectory dir(base + "/out", comm);
  {
    IO::ResultSet files(dir, comm);
    const std::string h5 = files.add("solution.h5"), xmf = files.add("solution.xmf");
    IO::ResultWriter(disc, comm).write(h5, "solution.h5", xmf, displacementOf(disc), r.nodeFields, r.cellFields, r.points,
                                       r.attributes);
    files.commit();
  }
  if (comm->getRank() != 0) return;
  CHECK(temporariesIn(dir.path()).empty(), "no temporaries after commit");
  const std::string h5Path = dir.path() + "/solution.h5";
  H5Reader h5(h5Path);
  CHECK(h5.id >= 0, "the h5 file opens");
  if (h5.id < 0) return;
  checkMeshData(h5, disc, outputOrder(disc, comm->getSize()));
  checkPointSets(h5, comm->getSize());
  checkAttributes(h5);
  checkIndex(readFile(dir.path() + "/solution.xmf"), h5);
  // Space reserved before the data is not left at the end of the file.
  struct stat st;
  const long long data = 8LL * (disc.mesh.numNodes() * 7 + disc.mesh.numCells() * 9 + 4 * 7 + 6 * comm->getSize());
  CHECK(::stat(h5Path.c_str(), &st) == 0 && st.st_size < data + 48 * 1024,
        "file size " << st.st_size << " for " << data << " bytes of data");
}

// Every rank throws exception type E (and the same message); what() of rank 0.
template <class E, class F>
std::string expectCollective(const std::string& label, const Comm& comm, F&& f) {
  std::string message, kind = "nothing";
  try {
    f();
  } catch (const E& e) {
    message = e.what(), kind = "expected";
  } catch (const std::exception& e) {
    message = e.what(), kind = "another exception";
  }
  CHECK(kind == "expected", label << ": got " << kind << " " << message);
  CHECK(message == IO::broadcastFromRoot(comm, message), label << ": the same message on every rank");
  CHECK(message.find('\n') == std::string::npos, label << ": one line");
  if (comm.getRank() == 0) std::cout << "  " << label << ": " << message << std::endl;
  return message;
}

void failures(const std::string& base, const RCP<const Comm>& comm) {
  const auto disc = boxDiscretization(6, 2, 2, *comm);
  IO::OutputDirectory dir(base + "/fail", comm);
  const std::vector<double> u = displacementOf(disc);
  const bool root = comm->getRank() == 0, last = comm->getRank() == comm->getSize() - 1;
  const std::string h5 = dir.temporary("solution.h5"), xmf = dir.temporary("solution.xmf");
  IO::ResultWriter writer(disc, comm);

  // A field of the wrong size on the last rank only: refused before any file exists.
  std::vector<IO::Field> bad = {IO::Field{"temperature", 1, std::vector<double>(disc.ownedNodes().size() + last, 0.0)}};
  std::string m = expectCollective<CollectiveError>("wrong field size", *comm, [&] {
    writer.write(h5, "solution.h5", xmf, u, bad, {});
  });
  CHECK(contains(m, "temperature"), "the message names the field");
  if (root) CHECK(!exists(h5) && !exists(xmf), "nothing written for wrong arguments");

  if (comm->getSize() > 1) {
    std::vector<IO::Field> named = {IO::Field{last ? "heat" : "temperature", 1,
                                              std::vector<double>(disc.ownedNodes().size(), 0.0)}};
    expectCollective<CollectiveError>("names differ between ranks", *comm, [&] {
      writer.write(h5, "solution.h5", xmf, u, named, {});
    });
    if (root) CHECK(!exists(h5), "nothing written for differing names");
  }

  // A file that cannot be created, with and without the reservation before it.
  for (bool reserve : {true, false}) {
    writer.reserveSpace(reserve);
    m = expectCollective<RunFailure>(std::string("missing directory") + (reserve ? "" : ", not reserved"), *comm, [&] {
      writer.write(dir.path() + "/missing/solution.h5", "solution.h5", xmf, u, {}, {});
    });
    CHECK(contains(m, "solution.h5") && contains(m, "uch file or directory"), "message names file and reason: " << m);
    if (!reserve) CHECK(contains(m, "H5Fcreate"), "message names the call: " << m);
  }
  writer.reserveSpace(true);

  // An index that cannot be written: the HDF5 file goes too.
  m = expectCollective<RunFailure>("index not writable", *comm, [&] {
    writer.write(h5, "solution.h5", dir.path() + "/missing/solution.xmf", u, {}, {});
  });
  CHECK(contains(m, "XDMF"), "message says it is the index: " << m);
  if (root) CHECK(!exists(h5), "the HDF5 file of a failed index is removed");
  if (root) CHECK(temporariesIn(dir.path()).empty(), "no temporaries after failures");
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the checks report what they find
  const std::string base = scratchDirectory(*comm, "result_writer");
  writeAndReadBack(base, comm);
  failures(base, comm);
  comm->barrier();
  if (comm->getRank() == 0) removeTree(base);
  return verdict(*comm, "io_test_result_writer");
}
