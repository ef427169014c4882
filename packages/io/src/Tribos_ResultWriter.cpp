#include "Tribos_ResultWriter.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <mpi.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include "Tribos_Error.hpp"
#include "Tribos_QuietHdf5Errors.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_ParameterReader.hpp"
#include "Tribos_Reduce.hpp"

namespace Tribos {
namespace IO {

const char* xdmfAttributeType(FieldShape shape, int components) {
  if (shape == FieldShape::SymmetricTensor) return "Tensor6";
  if (shape == FieldShape::Matrix) return "Matrix";
  return components == 1 ? "Scalar" : components == 3 ? "Vector" : "Matrix";
}

namespace {

// Offset of this rank's block and the global total of per-rank counts.
std::pair<long long, long long> blockOffset(long long mine, MPI_Comm comm) {
  long long offset = 0, total = 0;
  MPI_Exscan(&mine, &offset, 1, MPI_LONG_LONG, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) offset = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return {offset, total};
}

// What HDF5's current error stack tells: the innermost entry (the low-level
// operation that failed) and the MPI error string if MPI-IO reported one.
struct Hdf5Cause {
  std::string innermost, mpi;
};

Hdf5Cause hdf5Cause() {
  Hdf5Cause cause;
  auto visit = [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
    auto& c = *static_cast<Hdf5Cause*>(data);
    std::string desc = e->desc ? e->desc : "";
    // HDF5 appends "MPI error string is '...'" to the failed MPI call.
    const std::string marker = "MPI error string is '";
    const size_t at = desc.find(marker);
    if (at != std::string::npos) {
      if (c.mpi.empty()) c.mpi = desc.substr(at + marker.size(), desc.rfind('\'') - at - marker.size());
      desc = desc.substr(0, at);
      while (!desc.empty() && (desc.back() == ' ' || desc.back() == ':' || desc.back() == ',')) desc.pop_back();
    }
    if (n == 0) c.innermost = desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &cause);
  if (cause.innermost.empty()) cause.innermost = "no error message";
  return cause;
}

// errno after an HDF5 call is only a clue: MPI-IO's cleanup after a failure
// may have changed it (EBADF after a failed open). These values name a
// storage problem whatever call set them.
bool isStorageError(int err) {
  for (int e : {ENOSPC, EFBIG, EDQUOT, EIO, EROFS, EACCES, EPERM, ENOENT, ENOTDIR, EISDIR, ENAMETOOLONG})
    if (err == e) return true;
  return false;
}

// Why `bytes` more bytes cannot go into a file of the directory of path ("" if
// they can, as far as the free space and the file size limit tell).
std::string roomMissing(const std::string& path, hsize_t bytes) {
  struct statvfs fs;
  if (::statvfs(directoryOf(path).c_str(), &fs) == 0) {
    const unsigned long long freeBytes =
        static_cast<unsigned long long>(::geteuid() == 0 ? fs.f_bfree : fs.f_bavail) * fs.f_frsize;
    if (freeBytes < bytes) return systemReason(ENOSPC) + " (" + std::to_string(freeBytes) + " bytes free)";
  }
  struct rlimit limit;
  if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < bytes)
    return systemReason(EFBIG) + " (file size limit " + std::to_string(limit.rlim_cur) + " bytes)";
  return "";
}

// A failure every rank has agreed on: all ranks throw it at the same step,
// so that all of them take the same path to close the file.
struct AgreedFailure {
  std::string message;
};

// One dataset: this rank's rows [offset, offset + count) of a total x cols array.
struct Block {
  std::string name;
  hid_t type;
  long long offset, count, total;
  int cols;
  const void* data;
  hid_t id = -1;
};

template <class T>
Block block(const std::string& name, const std::vector<T>& data, std::pair<long long, long long> offsetTotal,
            long long count, int cols) {
  static_assert(std::is_same<T, double>::value || std::is_same<T, long long>::value, "double or long long data");
  const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
  return Block{name, type, offsetTotal.first, count, offsetTotal.second, cols, data.data()};
}

// Records the first failure of a sequence of HDF5 calls on a file, with
// HDF5's own cause, which must be read at once: the next call clears it.
class FirstFailure {
 public:
  // HDF5 keeps its error stack until the next API call clears it, and errno
  // keeps any old value: both are reset so that a failure reports its own cause.
  explicit FirstFailure(const std::string& path) : path_(path) {
    H5Eclear2(H5E_DEFAULT);
    errno = 0;
  }
  // Returns whether `result` (an hid_t or herr_t) is a failure.
  bool failed(long long result, const char* call, const std::string& object) {
    if (result >= 0) return false;
    if (message.empty()) {
      const int err = errno;  // before the error walk can change it
      const Hdf5Cause cause = hdf5Cause();
      // MPI-IO reports a short write as a success, and HDF5 then only knows
      // that bytes are missing: the likely reasons are a full file system or
      // a file size limit.
      const std::string reason = !cause.mpi.empty()   ? cause.mpi
                                 : isStorageError(err) ? systemReason(err)
                                                       : roomMissing(path_, 1 << 20);
      message = std::string(call) + " of " + object + " failed: " + (reason.empty() ? "" : reason + " ") +
                "(HDF5: " + cause.innermost + ")";
    }
    return true;
  }
  std::string message;

 private:
  std::string path_;
};

// A parallel HDF5 file whose every collective call is followed by an
// agreement on its outcome: either all ranks go on, or all ranks throw
// AgreedFailure at the same call and then abandon() the file together.
class ParallelH5File {
 public:
  ParallelH5File(const std::string& path, const RCP<const Comm>& comm) : path_(path), comm_(comm) {
    FirstFailure f(path_);
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (!f.failed(fapl, "H5Pcreate", "a file access list") &&
        !f.failed(H5Pset_fapl_mpio(fapl, rawComm(*comm), MPI_INFO_NULL), "H5Pset_fapl_mpio", "the file"))
      f.failed(id_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "H5Fcreate", "the file");
    if (fapl >= 0) H5Pclose(fapl);
    agree(f.message);
  }
  // Never closes the file: closing is collective, and a destructor may run on
  // one rank only (an exception that is not an AgreedFailure). The owner
  // calls close() or abandon() on every rank.
  ~ParallelH5File() = default;

  void createGroup(const std::string& name) {
    FirstFailure f(path_);
    const hid_t g = H5Gcreate2(id_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (!f.failed(g, "H5Gcreate", "group " + name)) H5Gclose(g);
    agree(f.message);
  }

  void createDataset(Block& b) {
    FirstFailure f(path_);
    const hsize_t dims[2] = {static_cast<hsize_t>(b.total), static_cast<hsize_t>(b.cols)};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    if (!f.failed(space, "H5Screate_simple", "dataset " + b.name)) {
      b.id = H5Dcreate2(id_, b.name.c_str(), b.type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      f.failed(b.id, "H5Dcreate", "dataset " + b.name);
      H5Sclose(space);
    }
    agree(f.message);
  }

  void writeAttribute(const std::string& name, const std::string& text) {
    // A fixed-length string of at least one byte (HDF5 has no empty type),
    // marked UTF-8 and held to it as the summary is (Summary.cpp: inputs are
    // checked, other text has ill-formed sequences replaced).
    const std::string value = validUtf8(text);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, std::max<size_t>(value.size(), 1));
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const std::string padded = value.empty() ? std::string(1, '\0') : value;
    writeScalarAttribute(name, type, padded.data());
    H5Tclose(type);
  }

  void writeAttribute(const std::string& name, double value) { writeScalarAttribute(name, H5T_NATIVE_DOUBLE, &value); }

  // The size of the file as allocated so far: every dataset is allocated at
  // its creation in parallel HDF5, so after the last one this is the final size.
  hsize_t allocatedSize() {
    FirstFailure f(path_);
    hsize_t size = 0;
    f.failed(H5Fget_filesize(id_, &size), "H5Fget_filesize", "the file");
    agree(f.message);
    return size;
  }

  // Writes the metadata: what remains are the data writes.
  void flush() {
    FirstFailure f(path_);
    f.failed(H5Fflush(id_, H5F_SCOPE_GLOBAL), "H5Fflush", "the file");
    agree(f.message);
  }

  void write(const Block& b) {
    if (b.total == 0) return;  // nothing to write, on every rank alike
    FirstFailure f(path_);
    const hid_t fspace = H5Dget_space(b.id);
    const hsize_t start[2] = {static_cast<hsize_t>(b.offset), 0};
    const hsize_t count[2] = {static_cast<hsize_t>(b.count), static_cast<hsize_t>(b.cols)};
    const hid_t mspace = H5Screate_simple(2, count, nullptr);
    // Independent transfers: the rows of a rank are one contiguous extent of
    // the file, so collective buffering gains little, and Open MPI 4.1's
    // collective write (OMPIO) returns success when an aggregator's write
    // fails (seen on a full disk: the data were missing). A rank without rows
    // still calls, with an empty selection (a hyperslab of zero rows is an
    // error in HDF5), so that every rank agrees on the outcome.
    if (b.count > 0) H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
    else H5Sselect_none(fspace), H5Sselect_none(mspace);
    const hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
    H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_INDEPENDENT);
    static const double none = 0;
    f.failed(H5Dwrite(b.id, b.type, mspace, fspace, dxpl, b.count > 0 ? b.data : &none), "H5Dwrite", "dataset " + b.name);
    H5Pclose(dxpl);
    H5Sclose(mspace);
    H5Sclose(fspace);
    agree(f.message);
  }

  void closeDataset(Block& b) {
    FirstFailure f(path_);
    f.failed(H5Dclose(b.id), "H5Dclose", "dataset " + b.name);
    b.id = -1;
    agree(f.message);
  }

  void close() {
    FirstFailure f(path_);
    f.failed(H5Fclose(id_), "H5Fclose", "the file");
    id_ = -1;
    agree(f.message);
  }

  // After an AgreedFailure, on every rank: closes what is open. HDF5 1.10
  // leaves a file whose close failed in its tables, and its shutdown in
  // MPI_Finalize then crashes; the close flushes the metadata, so rank 0
  // first empties the file to give back the space of the data written.
  void abandon(std::vector<Block>& blocks) {
    for (Block& b : blocks)
      if (b.id >= 0) H5Dclose(b.id), b.id = -1;
    if (id_ < 0) return;
    comm_->barrier();  // no rank writes data any more
    if (comm_->getRank() == 0) {
      const int r = ::truncate(path_.c_str(), 0);
      (void)r;
    }
    comm_->barrier();
    H5Fclose(id_);
    id_ = -1;
  }

 private:
  void writeScalarAttribute(const std::string& name, hid_t type, const void* value) {
    FirstFailure f(path_);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(id_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (!f.failed(attr, "H5Acreate", "attribute " + name)) {
      f.failed(H5Awrite(attr, type, value), "H5Awrite", "attribute " + name);
      H5Aclose(attr);
    }
    H5Sclose(space);
    agree(f.message);
  }

  void agree(const std::string& localError) {
    const std::string error = agreeOnError(*comm_, localError);
    if (!error.empty()) throw AgreedFailure{error};
  }

  std::string path_;
  RCP<const Comm> comm_;
  hid_t id_ = -1;
};

// Rank 0 allocates `bytes` at the start of the file at path (fallocate: no
// data written), so that a disk too small, a quota or a file size limit fails
// here, before HDF5 writes anything. HDF5 1.10 cannot survive a failure of
// its metadata writes: rank 0 leaves the flush early while the others wait in
// it, and a file whose close failed crashes MPI_Finalize. A file system
// without fallocate: the free space and the file size limit are checked instead.
std::string reserveOnRoot(const std::string& path, hsize_t bytes, const Comm& comm) {
  std::string error;
  const int fd = comm.getRank() == 0 ? ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644) : -1;
  if (comm.getRank() == 0 && fd < 0) {
    error = "cannot create the file: " + systemReason(errno);
  } else if (comm.getRank() == 0) {
    const int err = ::fallocate(fd, 0, 0, static_cast<off_t>(bytes)) == 0 ? 0 : errno;
    ::close(fd);
    const std::string reason = err == EOPNOTSUPP || err == ENOSYS ? roomMissing(path, bytes)
                               : err != 0                        ? systemReason(err)
                                                                 : "";
    if (!reason.empty()) error = "cannot reserve " + std::to_string(bytes) + " bytes for the file: " + reason;
  }
  return agreeOnError(comm, error);
}

// An upper bound of the file's size: the data plus HDF5's headers, B-trees
// and heaps (below 4 kB per object and attribute, plus the superblock and
// the metadata block of 2 kB that HDF5 allocates at a time).
hsize_t sizeBound(const std::vector<std::string>& groups, const std::vector<Block>& blocks,
                  const ResultAttributes& attributes) {
  hsize_t bytes = 64 * 1024;
  for (const Block& b : blocks) bytes += static_cast<hsize_t>(b.total) * b.cols * 8 + 4096;
  bytes += 4096 * groups.size();
  for (const auto& a : attributes.text) bytes += 4096 + a.first.size() + a.second.size();
  bytes += 4096 * attributes.numbers.size();
  return bytes;
}

// The whole content, in an order that keeps failures cheap: metadata first,
// then the space of the whole file, then the data.
void writeAll(ParallelH5File& file, const std::string& path, const std::vector<std::string>& groups,
              std::vector<Block>& blocks, const ResultAttributes& attributes, bool reserveSpace, const Comm& comm) {
  for (const std::string& g : groups) file.createGroup(g);
  for (Block& b : blocks) file.createDataset(b);
  for (const auto& a : attributes.text) file.writeAttribute(a.first, a.second);
  for (const auto& a : attributes.numbers) file.writeAttribute(a.first, a.second);
  if (reserveSpace) {
    const std::string error = reserveOnRoot(path, file.allocatedSize(), comm);
    if (!error.empty()) throw AgreedFailure{error};
  }
  file.flush();
  for (const Block& b : blocks) file.write(b);
  for (Block& b : blocks) file.closeDataset(b);
}

std::string xmlEscaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// XDMF's number of a cell type in a Mixed topology (Xdmf3's XdmfTopologyType ids).
int xdmfMixedCode(Mesh::CellType type) {
  switch (type) {
    case Mesh::CellType::Tet4: return 6;
    case Mesh::CellType::Hex8: return 9;
    case Mesh::CellType::Tet10: return 38;
    case Mesh::CellType::Hex20: return 48;
  }
  return 9;
}

// XDMF's name of a cell type.
const char* xdmfTopologyType(Mesh::CellType type) {
  switch (type) {
    case Mesh::CellType::Tet4: return "Tetrahedron";
    case Mesh::CellType::Hex8: return "Hexahedron";
    case Mesh::CellType::Tet10: return "Tetrahedron_10";
    case Mesh::CellType::Hex20: return "Hexahedron_20";
  }
  return "Hexahedron";
}

// The lines of an index, indented by `pad` spaces.
void xdmfDataItem(std::ostream& os, int pad, const std::string& h5, const std::string& dataset, long long rows, int cols,
                  const char* numberType) {
  os << std::string(pad, ' ') << "<DataItem Dimensions=\"" << rows << " " << cols << "\" NumberType=\"" << numberType
     << "\" Precision=\"8\" Format=\"HDF\">" << xmlEscaped(h5) << ":" << xmlEscaped(dataset) << "</DataItem>\n";
}

void xdmfAttribute(std::ostream& os, int pad, const std::string& h5, const std::string& group,
                   const ResultLayout::FieldLayout& f, long long n, const char* center) {
  os << std::string(pad, ' ') << "<Attribute Name=\"" << xmlEscaped(f.name) << "\" AttributeType=\""
     << xdmfAttributeType(f.shape, f.components) << "\" Center=\"" << center << "\">\n";
  xdmfDataItem(os, pad + 2, h5, group + "/" + f.name, n, f.components, "Float");
  os << std::string(pad, ' ') << "</Attribute>\n";
}

// The grids of one result file (the body, then one per point set), each
// element at `pad` spaces and its children deeper.
void xdmfGrids(std::ostream& x, int pad, const std::string& h5, const ResultLayout& n) {
  const std::string in(pad, ' ');
  x << in << "<Grid Name=\"body\" GridType=\"Uniform\">\n"
    << in << "  <Topology TopologyType=\"" << (n.mixed ? "Mixed" : xdmfTopologyType(n.cellType))
    << "\" NumberOfElements=\"" << n.cells << "\">\n";
  if (n.mixed)
    xdmfDataItem(x, pad + 4, h5, "/mesh/topology", n.topologyEntries, 1, "Int");
  else
    xdmfDataItem(x, pad + 4, h5, "/mesh/topology", n.cells, n.nodesPerCell, "Int");
  x << in << "  </Topology>\n" << in << "  <Geometry GeometryType=\"XYZ\">\n";
  xdmfDataItem(x, pad + 4, h5, "/mesh/geometry", n.nodes, 3, "Float");
  x << in << "  </Geometry>\n";
  for (const auto& f : n.nodeFields) xdmfAttribute(x, pad + 2, h5, "/nodes", f, n.nodes, "Node");
  for (const auto& f : n.cellFields) xdmfAttribute(x, pad + 2, h5, "/cells", f, n.cells, "Cell");
  x << in << "</Grid>\n";
  for (const auto& ps : n.pointSets) {
    const std::string group = "/points/" + ps.name;
    x << in << "<Grid Name=\"" << xmlEscaped(ps.name) << "\" GridType=\"Uniform\">\n"
      << in << "  <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << ps.points
      << "\" NodesPerElement=\"1\"/>\n" << in << "  <Geometry GeometryType=\"XYZ\">\n";
    xdmfDataItem(x, pad + 4, h5, group + "/geometry", ps.points, 3, "Float");
    x << in << "  </Geometry>\n";
    for (const auto& f : ps.fields) xdmfAttribute(x, pad + 2, h5, group, f, ps.points, "Node");
    x << in << "</Grid>\n";
  }
}

const char* kXdmfHead = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
const char* kXdmfTail = "  </Domain>\n</Xdmf>\n";

std::vector<ResultLayout::FieldLayout> fieldLayouts(const std::vector<Field>& fields) {
  std::vector<ResultLayout::FieldLayout> layouts;
  for (const Field& f : fields) layouts.push_back({f.name, f.components, f.shape});
  return layouts;
}

// What decides the sequence of collective calls (names, components, counts of
// datasets) and the attribute values: it must be the same on every rank, or
// the ranks would call HDF5 differently and hang.
std::string layoutSignature(const std::string& h5Name, const std::vector<Field>& nodeFields,
                            const std::vector<Field>& cellFields, const std::vector<PointSet>& pointSets,
                            const ResultAttributes& attributes) {
  std::ostringstream s;
  s.precision(17);
  s << h5Name << '\n';
  for (const Field& f : nodeFields) s << "node " << f.name << ' ' << f.components << ' ' << int(f.shape) << '\n';
  for (const Field& f : cellFields) s << "cell " << f.name << ' ' << f.components << ' ' << int(f.shape) << '\n';
  for (const PointSet& ps : pointSets) {
    s << "points " << ps.name << '\n';
    for (const Field& f : ps.fields) s << "  " << f.name << ' ' << f.components << ' ' << int(f.shape) << '\n';
  }
  for (const auto& a : attributes.text) s << "text " << a.first << '=' << a.second << '\n';
  for (const auto& a : attributes.numbers) s << "number " << a.first << '=' << a.second << '\n';
  return s.str();
}

// This rank's complaint about its arguments ("" if none).
std::string argumentError(const Mesh::Discretization& disc, const std::vector<double>& uOwned,
                          const std::vector<Field>& nodeFields, const std::vector<Field>& cellFields,
                          const std::vector<PointSet>& pointSets) {
  const long long nOwned = static_cast<long long>(disc.ownedNodes().size());
  const long long nCells = static_cast<long long>(disc.part.numCells());
  std::ostringstream e;
  if (uOwned.size() != 3 * static_cast<size_t>(nOwned))
    e << "the displacement has " << uOwned.size() << " values for " << nOwned << " owned nodes";
  auto check = [&](const Field& f, long long rows, const std::string& what) {
    if (f.components < 1 || f.values.size() != static_cast<size_t>(rows * f.components))
      e << (e.tellp() > 0 ? "; " : "") << what << " field " << f.name << " has " << f.values.size() << " values for "
        << rows << " rows of " << f.components;
  };
  for (const Field& f : nodeFields) check(f, nOwned, "node");
  for (const Field& f : cellFields) check(f, nCells, "cell");
  for (const PointSet& ps : pointSets)
    for (const Field& f : ps.fields) check(f, static_cast<long long>(ps.coords.size()), "point set " + ps.name);
  return e.str();
}

// This rank's rows of every dataset, in the order they are written, with the
// groups that hold them and the global sizes.
struct Content {
  Content(const Mesh::Discretization& disc, const std::vector<double>& uOwned, const std::vector<Field>& nodeFields,
          const std::vector<Field>& cellFields, const std::vector<PointSet>& pointSets, MPI_Comm comm) {
    const Mesh::Mesh& mesh = disc.part;
    for (int n : disc.ownedNodes())
      for (int d = 0; d < 3; ++d) xyz.push_back(mesh.coords[n][d]);
    disp = uOwned;
    // The cell types of every rank's part: one (a table of cells) or several
    // (XDMF's Mixed list: each cell's type number, then its nodes).
    int mine = 0, all = 0;
    for (Mesh::CellType t : mesh.cellTypesPresent()) mine |= 1 << static_cast<int>(t);
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_BOR, comm);
    layout.mixed = (all & (all - 1)) != 0;
    for (int t = 0; !layout.mixed && t < 4; ++t)
      if (all == 1 << t) layout.cellType = static_cast<Mesh::CellType>(t);
    layout.nodesPerCell = layout.mixed ? 1 : Mesh::nodesPerCell(layout.cellType);
    for (int c = 0; c < mesh.numCells(); ++c) {
      const std::vector<int>& order = xdmfNodeOrder(mesh.cellType(c));
      if (layout.mixed) topo.push_back(xdmfMixedCode(mesh.cellType(c)));
      for (int k : order) topo.push_back(disc.nodeIndex()[mesh.cell(c)[k]]);
    }
    pointXyz.resize(pointSets.size());
    for (size_t k = 0; k < pointSets.size(); ++k)
      for (const auto& p : pointSets[k].coords) pointXyz[k].insert(pointXyz[k].end(), p.begin(), p.end());

    const long long nOwned = static_cast<long long>(disc.ownedNodes().size());
    const long long nCells = static_cast<long long>(mesh.numCells());
    const auto nodeBlock = blockOffset(nOwned, comm), cellBlock = blockOffset(nCells, comm);
    const long long topoRows = layout.mixed ? static_cast<long long>(topo.size()) : nCells;
    const auto topoBlock = layout.mixed ? blockOffset(topoRows, comm) : cellBlock;
    layout.topologyEntries = layout.mixed ? topoBlock.second : cellBlock.second * layout.nodesPerCell;
    layout.nodes = nodeBlock.second;
    layout.cells = cellBlock.second;
    layout.nodeFields = fieldLayouts(nodeFields);
    layout.nodeFields.insert(layout.nodeFields.begin(), {"displacement", 3});
    layout.cellFields = fieldLayouts(cellFields);
    groups = {"/mesh", "/nodes", "/cells", "/points"};
    blocks = {block("/mesh/geometry", xyz, nodeBlock, nOwned, 3), block("/mesh/topology", topo, topoBlock, topoRows, layout.nodesPerCell),
              block("/nodes/displacement", disp, nodeBlock, nOwned, 3)};
    for (const Field& f : nodeFields) blocks.push_back(block("/nodes/" + f.name, f.values, nodeBlock, nOwned, f.components));
    for (const Field& f : cellFields) blocks.push_back(block("/cells/" + f.name, f.values, cellBlock, nCells, f.components));
    for (size_t k = 0; k < pointSets.size(); ++k) {
      const long long np = static_cast<long long>(pointSets[k].coords.size());
      const auto pointBlock = blockOffset(np, comm);
      layout.pointSets.push_back({pointSets[k].name, pointBlock.second, fieldLayouts(pointSets[k].fields)});
      groups.push_back("/points/" + pointSets[k].name);
      blocks.push_back(block(groups.back() + "/geometry", pointXyz[k], pointBlock, np, 3));
      for (const Field& f : pointSets[k].fields)
        blocks.push_back(block(groups.back() + "/" + f.name, f.values, pointBlock, np, f.components));
    }
  }
  Content(const Content&) = delete;  // blocks point into the vectors

  std::vector<double> xyz, disp;
  std::vector<long long> topo;
  std::vector<std::vector<double>> pointXyz;
  ResultLayout layout;  // the same on every rank
  std::vector<std::string> groups;
  std::vector<Block> blocks;
};

// The HDF5 file, collectively; "" or the message every rank agreed on, after
// every rank has closed what it opened.
std::string writeHdf5(const std::string& path, const Content& content, const ResultAttributes& attributes,
                      bool reserveSpace, const RCP<const Comm>& comm) {
  QuietHdf5Errors quiet;
  std::vector<Block> blocks = content.blocks;  // they receive the dataset ids
  try {
    // The probe: a disk without room for the file, or a file size limit below
    // it, fails here, before HDF5 has metadata that it could not write.
    // H5Fcreate then truncates the file; writeAll reserves its exact size.
    if (reserveSpace) {
      const std::string error = reserveOnRoot(path, sizeBound(content.groups, blocks, attributes), *comm);
      if (!error.empty()) return error;
    }
    ParallelH5File file(path, comm);
    try {
      writeAll(file, path, content.groups, blocks, attributes, reserveSpace, *comm);
      file.close();
    } catch (const AgreedFailure&) {
      file.abandon(blocks);
      throw;
    }
  } catch (const AgreedFailure& f) {
    return f.message;
  }
  return "";
}

}  // namespace

ResultWriter::ResultWriter(const Mesh::Discretization& disc, const RCP<const Comm>& comm) : disc_(disc), comm_(comm) {}

ResultLayout ResultWriter::writeData(const std::string& h5Path, const std::string& h5Name,
                                     const std::vector<double>& uOwned, const std::vector<Field>& nodeFields,
                                     const std::vector<Field>& cellFields, const std::vector<PointSet>& pointSets,
                                     const ResultAttributes& attributes) const {
  const std::string shownName = directoryOf(h5Path) + "/" + h5Name;
  // Arguments first: a wrong one must stop every rank before the first HDF5 call.
  const std::string signature = layoutSignature(h5Name, nodeFields, cellFields, pointSets, attributes);
  std::string error = broadcastFromRoot(*comm_, signature) == signature
                          ? argumentError(disc_, uOwned, nodeFields, cellFields, pointSets)
                          : "rank " + std::to_string(comm_->getRank()) +
                                " passes other names, components or attributes than rank 0";
  error = agreeOnError(*comm_, error);
  if (!error.empty()) throw CollectiveError("cannot write the result file " + shownName + ": " + error);

  // Everything is packed before the first collective HDF5 call: from there on
  // nothing may throw on one rank only.
  const Content content(disc_, uOwned, nodeFields, cellFields, pointSets, rawComm(*comm_));
  const std::string failure = writeHdf5(h5Path, content, attributes, reserveSpace_, comm_);
  if (!failure.empty()) {
    if (comm_->getRank() == 0) removeIfExists(h5Path);
    throw RunFailure("cannot write the result file " + shownName + ": " + failure);
  }
  return content.layout;
}

void ResultWriter::write(const std::string& h5Path, const std::string& h5Name, const std::string& xmfPath,
                         const std::vector<double>& uOwned, const std::vector<Field>& nodeFields,
                         const std::vector<Field>& cellFields, const std::vector<PointSet>& pointSets,
                         const ResultAttributes& attributes) const {
  ResultLayout layout;
  try {
    layout = writeData(h5Path, h5Name, uOwned, nodeFields, cellFields, pointSets, attributes);
  } catch (const RunFailure&) {
    // The index goes with its data file, as it always has: no index is left
    // at xmfPath for a data file that failed.
    if (comm_->getRank() == 0) removeIfExists(xmfPath);
    throw;
  }
  const std::string xmfError = comm_->getRank() == 0 ? writeWholeFile(xmfPath, xdmfIndex(h5Name, layout)) : "";
  const std::string failure = rootError(
      *comm_, xmfError.empty() ? "" : "cannot write the XDMF index of " + directoryOf(h5Path) + "/" + h5Name + ": " + xmfError);
  if (!failure.empty()) {
    if (comm_->getRank() == 0) removeIfExists(h5Path), removeIfExists(xmfPath);
    throw RunFailure(failure);
  }
}

std::string xdmfIndex(const std::string& h5Name, const ResultLayout& layout) {
  std::ostringstream x;
  x << kXdmfHead;
  xdmfGrids(x, 4, h5Name, layout);
  x << kXdmfTail;
  return x.str();
}

std::string xdmfTimeSeriesHead() {
  return std::string(kXdmfHead) + "    <Grid Name=\"steps\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
}

std::string xdmfTimeSeriesStep(int step, const SeriesStep& s) {
  std::ostringstream x;
  char time[32];
  std::snprintf(time, sizeof time, "%.17g", s.time);  // read back to the same double
  x << "      <Grid Name=\"step " << step << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
    << "        <Time Value=\"" << time << "\"/>\n";
  xdmfGrids(x, 8, s.h5Name, s.layout);
  x << "      </Grid>\n";
  return x.str();
}

std::string xdmfTimeSeriesTail() { return std::string("    </Grid>\n") + kXdmfTail; }

std::string xdmfTimeSeries(const std::vector<SeriesStep>& steps) {
  std::string x = xdmfTimeSeriesHead();
  for (size_t k = 0; k < steps.size(); ++k) x += xdmfTimeSeriesStep(static_cast<int>(k) + 1, steps[k]);
  return x + xdmfTimeSeriesTail();
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = temporaryPathFor(path);
  std::string error = writeWholeFile(tmp, text);
  if (error.empty()) error = renameFile(tmp, path);
  if (!error.empty()) {
    removeIfExists(tmp);
    throw RunFailure("cannot write " + path + ": " + error);
  }
}

void writeFileAtomically(const std::string& path, const std::string& text, const RCP<const Comm>& comm) {
  std::string error;
  if (comm->getRank() == 0) {
    try {
      writeFileAtomically(path, text);
    } catch (const RunFailure& e) {
      error = e.what();
    }
  }
  error = rootError(*comm, error);
  if (!error.empty()) throw RunFailure(error);
}

const std::vector<int>& xdmfNodeOrder(Mesh::CellType type) {
  static const std::vector<int> tet4 = {0, 1, 2, 3}, hex8 = {0, 1, 2, 3, 4, 5, 6, 7};
  static const std::vector<int> tet10 = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  static const std::vector<int> hex20 = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
  switch (type) {
    case Mesh::CellType::Tet4: return tet4;
    case Mesh::CellType::Hex8: return hex8;
    case Mesh::CellType::Tet10: return tet10;
    case Mesh::CellType::Hex20: return hex20;
  }
  return hex8;
}

}  // namespace IO
}  // namespace Tribos
