#include "Tribos_FCLIB.hpp"

#include <hdf5.h>
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <utility>

#include "Tribos_FileSystem.hpp"
#include "Tribos_QuietHdf5Errors.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FileKind.hpp"
#include "Tribos_ArrayScan.hpp"

namespace Tribos {
namespace FCLIB {

namespace {

const char* const kLocalGroup = "fclib_local";
const char* const kGlobalGroup = "fclib_global";

// ---------------------------------------------------------------- handles

// Owns one HDF5 identifier and closes it with the matching H5xclose.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept {
    std::swap(id_, other.id_);
    std::swap(closer_, other.closer_);
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0 && closer_) closer_(id_);
  }
  hid_t get() const { return id_; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// Where we are in which file, for error messages. 'group' is the absolute
// HDF5 path of the current group ("" for the root), so that messages name
// datasets the way h5dump and h5py do: /fclib_local/vectors/q.
struct Location {
  std::string file;
  std::string group;

  [[noreturn]] void fail(const std::string& why) const {
    throw Error("FCLIB file " + file + ": " + why);
  }
  Location child(const std::string& name) const { return {file, path(name)}; }
  std::string path(const std::string& name) const { return group + "/" + name; }
  std::string groupLabel() const { return group.empty() ? "root group" : "group " + group; }
};

bool hasLink(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

Handle openGroup(hid_t loc, const Location& where, const std::string& name) {
  if (!hasLink(loc, name)) where.fail(where.groupLabel() + " has no group " + name);
  hid_t id = H5Gopen2(loc, name.c_str(), H5P_DEFAULT);
  if (id < 0) where.fail("cannot open group " + where.path(name));
  return Handle(id, H5Gclose);
}

Handle openDataset(hid_t loc, const Location& where, const std::string& name) {
  if (!hasLink(loc, name)) where.fail(where.groupLabel() + " has no dataset " + name);
  hid_t id = H5Dopen2(loc, name.c_str(), H5P_DEFAULT);
  if (id < 0) where.fail("cannot open dataset " + where.path(name));
  return Handle(id, H5Dclose);
}

// A directory or an empty file is named as such rather than as "not HDF5".
// A FIFO or a device (/dev/zero) would block HDF5's reads or feed them
// without end: only a regular file of at most kMaxFileBytes is opened.
Handle openFileForReading(const std::string& path) {
  auto fail = [&](const std::string& why) { throw Error("FCLIB file " + path + ": " + why); };
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) fail(std::string("cannot open for reading: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail("is a directory, expected an HDF5 file");
  if (!S_ISREG(st.st_mode)) fail("is " + Tribos::fileKind(st.st_mode) + ", expected an HDF5 file (a regular file)");
  if (st.st_size == 0) fail("is empty, expected an HDF5 file");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxFileBytes)
    fail("has " + std::to_string(st.st_size) + " bytes, more than the " + std::to_string(kMaxFileBytes >> 30) +
         " GiB read (the problem is held in memory on one rank)");
  if (!std::ifstream(path).good()) fail("cannot open for reading");
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) fail("not a readable HDF5 file");
  return Handle(id, H5Fclose);
}

// ---------------------------------------------------------------- reading

// Deflate, the compression filter of a standard HDF5 build, never shrinks
// data by more than about 1032:1.
constexpr double kMaxCompressionRatio = 1100.0;
// Unwritten parts of a dataset read as its fill value, and some FCLIB writers
// leave zero vectors unwritten (the /solution/r of the samples); such parts
// are allowed up to this multiple of the file size.
constexpr double kFillAllowance = 16.0;

double fileSize(hid_t object) {
  Handle file(H5Iget_file_id(object), H5Fclose);
  hsize_t size = 0;
  return file.get() >= 0 && H5Fget_filesize(file.get(), &size) >= 0 ? static_cast<double>(size) : 0.0;
}

// A dataset may declare an extent far beyond the bytes the file holds for it,
// so a file of a few kilobytes could make the reader allocate terabytes. The
// declared bytes must be backed by the stored ones (times the compression a
// filter could have achieved), up to a fill-value allowance.
void checkStored(hid_t dataset, hssize_t count, std::size_t typeSize, const Location& where,
                 const std::string& name) {
  const double declared = static_cast<double>(count) * static_cast<double>(typeSize);
  const double stored = static_cast<double>(H5Dget_storage_size(dataset));
  Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  const bool filtered = plist.get() >= 0 && H5Pget_nfilters(plist.get()) > 0;
  const double file = fileSize(dataset);
  if (declared > (filtered ? kMaxCompressionRatio : 1.0) * stored + kFillAllowance * file)
    where.fail(where.path(name) + " declares " + std::to_string(count) + " entries (" +
               std::to_string(static_cast<long long>(declared)) + " bytes) but the file stores " +
               std::to_string(static_cast<long long>(stored)) + " bytes for it (file size " +
               std::to_string(static_cast<long long>(file)) + " bytes)");
}

enum class Numeric { Integer, Real };

// Number of entries of a numeric dataset, once its type fits and its extent is
// backed by stored data. Integers may be read as reals, not the reverse: a
// real-valued size or index would be truncated silently.
std::size_t numericExtent(hid_t dataset, const Location& where, const std::string& name,
                          Numeric kind) {
  Handle type(H5Dget_type(dataset), H5Tclose);
  const H5T_class_t typeClass = H5Tget_class(type.get());
  if (kind == Numeric::Integer && typeClass != H5T_INTEGER)
    where.fail(where.path(name) + " is not an integer dataset");
  if (kind == Numeric::Real && typeClass != H5T_FLOAT && typeClass != H5T_INTEGER)
    where.fail(where.path(name) + " is not a numeric dataset");
  Handle space(H5Dget_space(dataset), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) where.fail("cannot get the size of dataset " + where.path(name));
  checkStored(dataset, count, H5Tget_size(type.get()), where, name);
  return static_cast<std::size_t>(count);
}

// Reads a whole numeric dataset; 'expected', when given, is checked against
// the extent before anything is allocated.
template <typename T>
std::vector<T> readArray(hid_t loc, const Location& where, const std::string& name, Numeric kind,
                         hid_t memType, std::optional<std::size_t> expected = std::nullopt,
                         const std::string& expectedWhy = "") {
  Handle dataset = openDataset(loc, where, name);
  const std::size_t count = numericExtent(dataset.get(), where, name, kind);
  if (expected && count != *expected)
    where.fail(where.path(name) + " has " + std::to_string(count) + " entries, expected " +
               std::to_string(*expected) + expectedWhy);
  std::vector<T> data(count);
  if (count > 0 &&
      H5Dread(dataset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    where.fail("cannot read dataset " + where.path(name));
  return data;
}

std::vector<double> readDoubles(hid_t loc, const Location& where, const std::string& name,
                                std::optional<std::size_t> expected = std::nullopt,
                                const std::string& expectedWhy = "") {
  return readArray<double>(loc, where, name, Numeric::Real, H5T_NATIVE_DOUBLE, expected,
                           expectedWhy);
}

// Integers are read as 64 bits so that a value beyond int32 is reported as
// what it is instead of being clamped by the HDF5 conversion.
std::vector<int> readInts(hid_t loc, const Location& where, const std::string& name,
                          std::optional<std::size_t> expected = std::nullopt,
                          const std::string& expectedWhy = "") {
  const std::vector<long long> wide = readArray<long long>(
      loc, where, name, Numeric::Integer, H5T_NATIVE_LLONG, expected, expectedWhy);
  std::vector<int> values(wide.size());
  for (std::size_t k = 0; k < wide.size(); ++k) {
    if (wide[k] < std::numeric_limits<int>::min() || wide[k] > std::numeric_limits<int>::max())
      where.fail(where.path(name) + "[" + std::to_string(k) + "] = " + std::to_string(wide[k]) +
                 " does not fit in 32 bits");
    values[k] = static_cast<int>(wide[k]);
  }
  return values;
}

int readInt(hid_t loc, const Location& where, const std::string& name) {
  std::vector<int> value = readInts(loc, where, name);
  if (value.size() != 1)
    where.fail(where.path(name) + " should hold one integer, has " +
               std::to_string(value.size()) + " values");
  return value[0];
}

// Extent of a dataset without reading it (sizes of the problem: mu, f).
std::size_t datasetExtent(hid_t loc, const Location& where, const std::string& name) {
  Handle dataset = openDataset(loc, where, name);
  return numericExtent(dataset.get(), where, name, Numeric::Real);
}

std::string readString(hid_t loc, const Location& where, const std::string& name) {
  Handle dataset = openDataset(loc, where, name);
  Handle fileType(H5Dget_type(dataset.get()), H5Tclose);
  if (H5Tget_class(fileType.get()) != H5T_STRING)
    where.fail(where.path(name) + " is not a string");
  // One string only: the buffers below hold one, and H5Dread would write
  // every element of a larger dataspace into them.
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count != 1)
    where.fail(where.path(name) + " should hold one string, has " + std::to_string(count));
  Handle memType(H5Tcopy(H5T_C_S1), H5Tclose);
  if (H5Tis_variable_str(fileType.get()) > 0) {
    H5Tset_size(memType.get(), H5T_VARIABLE);
    char* text = nullptr;
    if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0)
      where.fail("cannot read string " + where.path(name));
    std::string result = text ? text : "";
    H5free_memory(text);
    return result;
  }
  const std::size_t size = H5Tget_size(fileType.get());
  checkStored(dataset.get(), 1, size, where, name);
  H5Tset_size(memType.get(), size + 1);  // room for a terminator if the file has none
  std::vector<char> buffer(size + 1, '\0');
  if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
    where.fail("cannot read string " + where.path(name));
  return std::string(buffer.data());
}

// A dimension a matrix must have, and where that number comes from.
struct Dimension {
  std::size_t value;
  std::string source;  // e.g. " = 3 x 48 contacts (the length of /fclib_local/vectors/mu)"
};

void expectDimension(int declared, const Dimension& expected, const Location& where,
                     const std::string& name) {
  if (declared < 0 || static_cast<std::size_t>(declared) != expected.value)
    where.fail(where.path(name) + " = " + std::to_string(declared) + ", expected " +
               std::to_string(expected.value) + expected.source);
}

// nzmax is the allocated length of the writer (CSparse): never less than the
// entries in use. It sizes nothing here, but a smaller value means the header
// and the arrays disagree.
void checkNzmax(hid_t group, const Location& where, std::size_t used) {
  if (!hasLink(group, "nzmax")) return;
  const int nzmax = readInt(group, where, "nzmax");
  if (nzmax < 0 || static_cast<std::size_t>(nzmax) < used)
    where.fail(where.path("nzmax") + " = " + std::to_string(nzmax) + " is less than the " +
               std::to_string(used) + " entries in use");
}

void checkFiniteValues(const std::vector<double>& x, std::size_t used, const Location& where) {
  for (std::size_t k = 0; k < used; ++k)
    if (!std::isfinite(x[k]))
      where.fail(where.path("x") + "[" + std::to_string(k) + "] is not finite (" +
                 (std::isnan(x[k]) ? "nan" : "inf") + ")");
}

LocalCsr buildMatrix(int m, int n, int nz, std::vector<int> p, std::vector<int> i,
                         std::vector<double> x, const Location& where) {
  const std::string what = "FCLIB file " + where.file + ": " + where.group;
  if (nz == -2) return fromCSR(m, n, p, i, x, what);
  if (nz == -1) return fromCSC(m, n, p, i, x, what);
  // Triplets: only the first nz entries are meaningful (arrays may be nzmax long).
  for (const auto& [name, size] : {std::pair<const char*, std::size_t>{"p", p.size()},
                                   {"i", i.size()}, {"x", x.size()}})
    if (size < static_cast<std::size_t>(nz))
      where.fail(where.path("nz") + " = " + std::to_string(nz) + " but " + where.path(name) +
                 " has only " + std::to_string(size) + " entries");
  p.resize(nz);
  i.resize(nz);
  x.resize(nz);
  return fromTriplets(m, n, i, p, x, what);
}

// Reads a sparse matrix whose dimensions are already known from the stored
// vectors: the declared m and n are checked before any array is read, so a
// wrong header is reported as such and never sizes an allocation.
LocalCsr readMatrix(hid_t parent, const Location& parentWhere, const std::string& name,
                        const Dimension& rows, const Dimension& columns) {
  Handle group = openGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  const hid_t g = group.get();
  const int m = readInt(g, where, "m");
  const int n = readInt(g, where, "n");
  expectDimension(m, rows, where, "m");
  expectDimension(n, columns, where, "n");
  const int nz = readInt(g, where, "nz");
  if (nz < -2)
    where.fail(where.path("nz") + " = " + std::to_string(nz) +
               ", expected -2 (compressed rows), -1 (compressed columns) or >= 0 (triplets)");
  // Compressed storage has one pointer per row (column) plus one; triplets
  // have at least nz column indices, checked with i and x when building.
  std::optional<std::size_t> pointers;
  if (nz < 0) pointers = static_cast<std::size_t>(nz == -2 ? m : n) + 1;
  std::vector<int> p = readInts(g, where, "p", pointers,
                                nz == -2 ? " (m + 1 row pointers)" : " (n + 1 column pointers)");
  std::vector<int> i = readInts(g, where, "i");
  std::vector<double> x = readDoubles(g, where, "x");
  LocalCsr A = buildMatrix(m, n, nz, p, i, x, where);
  const std::size_t used = nz < 0 ? static_cast<std::size_t>(p.back()) : nz;
  checkNzmax(g, where, used);
  checkFiniteValues(x, used, where);
  return A;
}

// ---------------------------------------------------------------- writing

Handle createGroup(hid_t loc, const Location& where, const std::string& name) {
  hid_t id = H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) where.fail("cannot create group " + where.path(name));
  return Handle(id, H5Gclose);
}

void writeArray(hid_t loc, const Location& where, const std::string& name, hid_t fileType,
                hid_t memType, const void* data, std::size_t count) {
  hsize_t dims[1] = {static_cast<hsize_t>(count)};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle dataset(H5Dcreate2(loc, name.c_str(), fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose);
  if (dataset.get() < 0) where.fail("cannot create dataset " + where.path(name));
  if (count > 0 && H5Dwrite(dataset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    where.fail("cannot write dataset " + where.path(name));
}

void writeDoubles(hid_t loc, const Location& where, const std::string& name,
                  const std::vector<double>& v) {
  writeArray(loc, where, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v.data(), v.size());
}

void writeInts(hid_t loc, const Location& where, const std::string& name,
               const std::vector<int>& v) {
  writeArray(loc, where, name, H5T_STD_I32LE, H5T_NATIVE_INT, v.data(), v.size());
}

// FCLIB stores integers as int32 datasets of shape (1,), not as scalars.
void writeInt(hid_t loc, const Location& where, const std::string& name, int value) {
  writeInts(loc, where, name, std::vector<int>{value});
}

// Fixed-length, NUL-terminated ASCII string in a scalar dataset, as FCLIB writes.
void writeString(hid_t loc, const Location& where, const std::string& name,
                 const std::string& text) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle dataset(H5Dcreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  if (dataset.get() < 0 ||
      H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()) < 0)
    where.fail("cannot write string " + where.path(name));
}

void writeMatrix(hid_t parent, const Location& parentWhere, const std::string& name,
                 const LocalCsr& A, Storage storage) {
  Handle group = createGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  const hid_t g = group.get();
  writeInt(g, where, "nzmax", A.nnz());
  writeInt(g, where, "m", A.rows);
  writeInt(g, where, "n", A.cols);
  if (storage == Storage::CompressedRows) {
    writeInt(g, where, "nz", -2);
    // A 0 x n matrix built by hand may have no row pointer; the file needs one.
    writeInts(g, where, "p", A.rowptr.empty() ? std::vector<int>{0} : A.rowptr);
    writeInts(g, where, "i", A.col);
  } else {
    std::vector<int> row, column;
    toTriplets(A, row, column);
    writeInt(g, where, "nz", A.nnz());
    writeInts(g, where, "p", column);
    writeInts(g, where, "i", row);
  }
  writeDoubles(g, where, "x", A.val);
}

void writeInfo(hid_t problemGroup, const Location& where, const Info& info) {
  Handle group = createGroup(problemGroup, where, "info");
  const Location infoWhere = where.child("info");
  writeString(group.get(), infoWhere, "title", info.title);
  writeString(group.get(), infoWhere, "description", info.description);
  writeString(group.get(), infoWhere, "math_info", info.math_info);
}

// Only the vectors a solution actually holds are written.
void writeSolutionGroup(hid_t parent, const Location& where, const std::string& name,
                        const Solution& s) {
  Handle group = createGroup(parent, where, name);
  const Location here = where.child(name);
  if (!s.v.empty()) writeDoubles(group.get(), here, "v", s.v);
  if (!s.u.empty()) writeDoubles(group.get(), here, "u", s.u);
  if (!s.r.empty()) writeDoubles(group.get(), here, "r", s.r);
  if (!s.l.empty()) writeDoubles(group.get(), here, "l", s.l);
}

void writeSolutionAndGuesses(hid_t file, const Location& root, const Solution* solution,
                             const std::vector<Solution>& guesses) {
  if (solution) writeSolutionGroup(file, root, "solution", *solution);
  if (guesses.empty()) return;
  Handle group = createGroup(file, root, "guesses");
  const Location where = root.child("guesses");
  writeInt(group.get(), where, "number_of_guesses", static_cast<int>(guesses.size()));
  for (std::size_t k = 0; k < guesses.size(); ++k)
    writeSolutionGroup(group.get(), where, std::to_string(k + 1), guesses[k]);
}

// Runs 'body' on a fresh HDF5 file at temporaryPathFor(path) and renames it onto
// path only after the file is closed without error; on failure the temporary
// file is removed and whatever was at path is left untouched.
template <typename Body>
void writeAtomically(const std::string& path, Body body) {
  const std::string tmp = temporaryPathFor(path);
  QuietHdf5Errors quiet;
  try {
    {
      hid_t id = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      if (id < 0) throw Error("FCLIB file " + path + ": cannot create " + tmp);
      Handle file(id, H5Fclose);
      body(file.get(), Location{path, ""});
      if (H5Fflush(file.get(), H5F_SCOPE_LOCAL) < 0)
        throw Error("FCLIB file " + path + ": cannot flush " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw Error("FCLIB file " + path + ": cannot rename " + tmp + " onto it");
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

// ---------------------------------------------------------------- checks

// Checks of a problem in memory. Every message names the FCLIB dataset the
// value is (or would be) stored in, after 'context' (e.g. "FCLIB file X").
class Checker {
 public:
  Checker(std::string context, std::string group)
      : context_(std::move(context)), group_(std::move(group)) {}

  [[noreturn]] void fail(const std::string& why) const {
    throw Error(context_ + ": " + why);
  }
  std::string name(const std::string& dataset) const { return group_ + "/" + dataset; }

  void spacedim(int value) const {
    if (value != 2 && value != 3)
      fail(name("spacedim") + " = " + std::to_string(value) + ", expected 2 or 3");
  }

  // The rows of the contact vectors and of W, spacedim x contacts (the
  // length of mu), once spacedim is checked.
  std::size_t contactRows(int spacedim, std::size_t contacts) const {
    this->spacedim(spacedim);
    return contacts * static_cast<std::size_t>(spacedim);
  }

  // 'why' (what an expected size is) is a text or a function that makes it:
  // messages are composed only when a check fails, since a problem is
  // validated at every solve.
  template <class Why>
  void size(const std::vector<double>& v, const std::string& dataset, std::size_t expected,
            const Why& why) const {
    if (v.size() != expected)
      fail(name(dataset) + " has " + std::to_string(v.size()) + " entries, expected " +
           std::to_string(expected) + text(why));
  }

  void finite(const std::vector<double>& v, const std::string& dataset) const {
    if (allFinite(v)) return;
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k]))
        fail(name(dataset) + "[" + std::to_string(k) + "] is not finite (" + kind(v[k]) + ")");
  }

  // Coulomb's cone K_mu = {||r_T|| <= mu r_N} is a cone only for mu >= 0.
  void frictionCoefficients(const std::vector<double>& mu, const std::string& dataset) const {
    finite(mu, dataset);
    for (std::size_t k = 0; k < mu.size(); ++k)
      if (mu[k] < 0.0)
        fail(name(dataset) + "[" + std::to_string(k) + "] = " + number(mu[k]) +
             " is negative (a friction coefficient is >= 0)");
  }

  // Canonical CSR as Tribos_FCLIB_SparseMatrix.hpp documents it, m x n as the problem needs,
  // and finite entries (duplicates summed on reading may overflow).
  template <class Why>
  void matrix(const LocalCsr& A, const std::string& dataset, std::size_t m, std::size_t n,
              const Why& why) const {
    if (A.rows < 0 || A.cols < 0 || static_cast<std::size_t>(A.rows) != m ||
        static_cast<std::size_t>(A.cols) != n)
      fail(name(dataset) + " is " + std::to_string(A.rows) + " x " + std::to_string(A.cols) +
           ", expected " + std::to_string(m) + " x " + std::to_string(n) + text(why));
    structure(A, dataset);
    if (allFinite(A.val)) return;
    for (int r = 0; r < A.rows; ++r)
      for (int k = A.rowptr[r]; k < A.rowptr[r + 1]; ++k)
        if (!std::isfinite(A.val[k]))
          fail(name(dataset) + " has a non-finite entry (" + kind(A.val[k]) + ") at row " +
               std::to_string(r) + ", column " + std::to_string(A.col[k]));
  }

 private:
  static const std::string& text(const std::string& why) { return why; }
  static std::string text(const char* why) { return why; }
  template <class Make>
  static std::string text(const Make& make) { return make(); }
  static const char* kind(double x) { return std::isnan(x) ? "nan" : "inf"; }
  static std::string number(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", x);
    return buffer;
  }

  void structure(const LocalCsr& A, const std::string& dataset) const {
    auto bad = [&](const std::string& why) {
      fail(name(dataset) + " is not a valid compressed-row matrix: " + why);
    };
    if (A.rowptr.empty() && A.rows == 0 && A.col.empty() && A.val.empty()) return;
    if (A.rowptr.size() != static_cast<std::size_t>(A.rows) + 1)
      bad(std::to_string(A.rowptr.size()) + " row pointers for " + std::to_string(A.rows) + " rows");
    if (A.rowptr[0] != 0) bad("the first row pointer is " + std::to_string(A.rowptr[0]));
    // Each test first as one flag over the whole array (a loop without a
    // branch per entry, which vectorizes), then, only when it fails, entry
    // by entry for the message.
    bool decreasing = false;
    for (int r = 0; r < A.rows; ++r) decreasing |= A.rowptr[r + 1] < A.rowptr[r];
    for (int r = 0; decreasing && r < A.rows; ++r)
      if (A.rowptr[r + 1] < A.rowptr[r]) bad("row pointers decrease at row " + std::to_string(r));
    const std::size_t nnz = static_cast<std::size_t>(A.rowptr.back());
    if (A.col.size() != nnz || A.val.size() != nnz)
      bad(std::to_string(A.col.size()) + " column indices and " + std::to_string(A.val.size()) +
          " values for " + std::to_string(nnz) + " entries");
    // One pass over the column indices for two tests:
    // - c in [0, n) iff neither c nor (n - 1) - c, as unsigned 32-bit
    //   numbers, has its top bit set (n - 1 < 2^31);
    // - columns strictly ascending within each row (the solvers search
    //   rows): the steps down over the whole array, less those from one
    //   row's last entry to the next row's first, are the steps down inside
    //   rows.
    std::uint32_t signs = 0;
    const std::uint32_t last = static_cast<std::uint32_t>(A.cols) - 1u;
    int down = 0;
    if (nnz > 0) signs = static_cast<std::uint32_t>(A.col[0]) | (last - static_cast<std::uint32_t>(A.col[0]));
    for (std::size_t k = 1; k < nnz; ++k) {
      const std::uint32_t c = static_cast<std::uint32_t>(A.col[k]);
      signs |= c | (last - c);
      down += A.col[k] <= A.col[k - 1];
    }
    const bool outside = A.cols == 0 ? nnz > 0 : (signs >> 31) != 0;
    for (std::size_t k = 0; outside && k < nnz; ++k)
      if (A.col[k] < 0 || A.col[k] >= A.cols)
        bad("column index " + std::to_string(A.col[k]) + " outside [0, " + std::to_string(A.cols) +
            ")");
    for (int r = 1; r < A.rows; ++r) {  // each boundary once (empty rows repeat it)
      const int k = A.rowptr[r];
      if (k > 0 && static_cast<std::size_t>(k) < nnz && k != A.rowptr[r - 1]) down -= A.col[k] <= A.col[k - 1];
    }
    for (int r = 0; down > 0 && r < A.rows; ++r)
      for (int k = A.rowptr[r] + 1; k < A.rowptr[r + 1]; ++k)
        if (A.col[k] <= A.col[k - 1])
          bad("row " + std::to_string(r) + " has column " + std::to_string(A.col[k]) + " after column " +
              std::to_string(A.col[k - 1]) + " (columns must be strictly ascending within a row: duplicates summed)");
  }

  std::string context_, group_;
};

std::string contactsWhy(std::size_t nc, int spacedim, const std::string& muPath) {
  return " = " + std::to_string(spacedim) + " x " + std::to_string(nc) +
         " contacts (the length of " + muPath + ")";
}

// Solution vectors are data about the problem: sized by it and finite.
void checkSolution(const Solution& s, std::size_t contact, std::optional<std::size_t> velocity,
                   const Checker& c) {
  for (const auto& [vector, dataset] : {std::pair<const std::vector<double>*, const char*>{&s.u, "u"},
                                        {&s.r, "r"}, {&s.v, "v"}, {&s.l, "l"}}) {
    if (vector->empty()) continue;
    const bool contactSized = std::string(dataset) == "u" || std::string(dataset) == "r";
    if (contactSized) c.size(*vector, dataset, contact, " (spacedim x contacts)");
    if (std::string(dataset) == "v" && velocity)
      c.size(*vector, dataset, *velocity, " (the size of M)");
    c.finite(*vector, dataset);
  }
}

void checkSolutions(const Solution* solution, const std::vector<Solution>& guesses,
                    std::size_t contact, std::optional<std::size_t> velocity,
                    const std::string& context) {
  if (solution) checkSolution(*solution, contact, velocity, Checker(context, "/solution"));
  for (std::size_t k = 0; k < guesses.size(); ++k)
    checkSolution(guesses[k], contact, velocity,
                  Checker(context, "/guesses/" + std::to_string(k + 1)));
}

}  // namespace

// ---------------------------------------------------------------- public

void validate(const LocalProblem& P, const std::string& context) {
  const Checker c(context, "/" + std::string(kLocalGroup));
  const std::size_t nc = P.mu.size(), m = c.contactRows(P.spacedim, nc);
  const auto why = [&] { return contactsWhy(nc, P.spacedim, c.name("vectors/mu")); };
  c.matrix(P.W, "W", m, m, why);
  c.size(P.q, "vectors/q", m, why);
  c.frictionCoefficients(P.mu, "vectors/mu");
  c.finite(P.q, "vectors/q");
  if (!P.V && !P.R && !P.s) return;
  if (!(P.V && P.R && P.s)) c.fail(c.name("") + "{V, R, vectors/s}: a mixed problem needs all three");
  const std::size_t p = P.s->size();
  const std::string sWhy = " (the length of " + c.name("vectors/s") + ")";
  c.matrix(*P.R, "R", p, p, sWhy);
  c.matrix(*P.V, "V", m, p, " (spacedim x contacts rows, columns" + sWhy + ")");
  c.finite(*P.s, "vectors/s");
}

void validate(const GlobalProblem& P, const std::string& context) {
  const Checker c(context, "/" + std::string(kGlobalGroup));
  const std::size_t nc = P.mu.size(), m = c.contactRows(P.spacedim, nc);
  const auto why = [&] { return contactsWhy(nc, P.spacedim, c.name("vectors/mu")); };
  const std::size_t ndof = P.f.size();
  const auto fWhy = [&] { return " (the length of " + c.name("vectors/f") + ")"; };
  c.matrix(P.M, "M", ndof, ndof, fWhy);
  c.matrix(P.H, "H", ndof, m, [&] { return " (rows" + fWhy() + ", columns" + why() + ")"; });
  c.size(P.w, "vectors/w", m, why);
  c.frictionCoefficients(P.mu, "vectors/mu");
  c.finite(P.f, "vectors/f");
  c.finite(P.w, "vectors/w");
  if (!P.G && !P.b) return;
  if (!(P.G && P.b)) c.fail(c.name("") + "{G, vectors/b}: G and b come together");
  c.matrix(*P.G, "G", ndof, P.b->size(),
           [&] { return " (rows" + fWhy() + ", columns the length of " + c.name("vectors/b") + ")"; });
  c.finite(*P.b, "vectors/b");
}

ProblemKind problemKind(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  if (hasLink(file.get(), kLocalGroup)) return ProblemKind::Local;
  if (hasLink(file.get(), kGlobalGroup)) return ProblemKind::Global;
  throw Error("FCLIB file " + path + ": has neither group /fclib_local nor " +
                           "group /fclib_global");
}

namespace {

int readSpacedim(hid_t group, const Location& where) {
  const int spacedim = readInt(group, where, "spacedim");
  if (spacedim != 2 && spacedim != 3)
    where.fail(where.path("spacedim") + " = " + std::to_string(spacedim) + ", expected 2 or 3");
  return spacedim;
}

// spacedim x (length of mu): the size of r, u, q, w and of W.
Dimension contactDimension(std::size_t nc, int spacedim, const Location& vectorsWhere) {
  return {nc * static_cast<std::size_t>(spacedim),
          contactsWhy(nc, spacedim, vectorsWhere.path("mu"))};
}

// The optional parts of a mixed problem must come together.
bool readAllOrNone(const std::vector<std::pair<bool, std::string>>& parts, const Location& where) {
  std::string present, missing, all;
  auto add = [](std::string& list, const std::string& name) { list += (list.empty() ? "" : ", ") + name; };
  for (const auto& [has, name] : parts) add(has ? present : missing, name), add(all, name);
  if (present.empty()) return false;
  if (!missing.empty())
    where.fail(where.groupLabel() + " has " + present + " but not " + missing + " (" + all +
               " come together)");
  return true;
}

// The file layer is checked while reading (types, extents, headers, index
// arrays, raw values) so that messages name the dataset and entry in the
// file; validate() then checks the problem as a whole.
void readMixedPart(hid_t group, hid_t vectors, const Location& where,
                   const Location& vectorsWhere, const Dimension& contact, LocalProblem& P) {
  if (!readAllOrNone({{hasLink(group, "V"), "V"}, {hasLink(group, "R"), "R"},
                      {hasLink(vectors, "s"), "vectors/s"}},
                     where))
    return;
  P.s = readDoubles(vectors, vectorsWhere, "s");
  const Dimension multipliers{P.s->size(), " (the length of " + vectorsWhere.path("s") + ")"};
  P.R = readMatrix(group, where, "R", multipliers, multipliers);
  P.V = readMatrix(group, where, "V", contact, multipliers);
}

void readConstraintPart(hid_t group, hid_t vectors, const Location& where,
                        const Location& vectorsWhere, const Dimension& dofs, GlobalProblem& P) {
  if (!readAllOrNone({{hasLink(group, "G"), "G"}, {hasLink(vectors, "b"), "vectors/b"}}, where))
    return;
  P.b = readDoubles(vectors, vectorsWhere, "b");
  P.G = readMatrix(group, where, "G", dofs,
                   {P.b->size(), " (the length of " + vectorsWhere.path("b") + ")"});
}

}  // namespace

// The open problem group of an FCLIB file and its "vectors" subgroup, with
// the friction coefficients and the contact dimension every problem has.
struct ProblemGroup {
  Handle file, group, vectors;
  Location where, vectorsWhere;
  int spacedim = 0;
  std::vector<double> mu;
  Dimension contact;

  ProblemGroup(const std::string& path, const char* groupName)
      : file(openFileForReading(path)),
        group(openGroup(file.get(), Location{path, ""}, groupName)),
        where(Location{path, ""}.child(groupName)),
        vectorsWhere(where.child("vectors")) {
    vectors = openGroup(group.get(), where, "vectors");
    spacedim = readSpacedim(group.get(), where);
    mu = readDoubles(vectors.get(), vectorsWhere, "mu");
    contact = contactDimension(mu.size(), spacedim, vectorsWhere);
  }

  // A problem with the group's spacedim and friction coefficients.
  template <class Problem>
  Problem problem() const {
    Problem P;
    P.spacedim = spacedim;
    P.mu = mu;
    return P;
  }
};

LocalProblem readLocal(const std::string& path) {
  QuietHdf5Errors quiet;
  const ProblemGroup g(path, kLocalGroup);
  LocalProblem P = g.problem<LocalProblem>();
  P.q = readDoubles(g.vectors.get(), g.vectorsWhere, "q", g.contact.value, g.contact.source);
  P.W = readMatrix(g.group.get(), g.where, "W", g.contact, g.contact);
  readMixedPart(g.group.get(), g.vectors.get(), g.where, g.vectorsWhere, g.contact, P);
  validate(P, "FCLIB file " + path);
  return P;
}

GlobalProblem readGlobal(const std::string& path) {
  QuietHdf5Errors quiet;
  const ProblemGroup g(path, kGlobalGroup);
  GlobalProblem P = g.problem<GlobalProblem>();
  P.f = readDoubles(g.vectors.get(), g.vectorsWhere, "f");
  const Dimension dofs{P.f.size(), " (the length of " + g.vectorsWhere.path("f") + ")"};
  P.w = readDoubles(g.vectors.get(), g.vectorsWhere, "w", g.contact.value, g.contact.source);
  P.M = readMatrix(g.group.get(), g.where, "M", dofs, dofs);
  P.H = readMatrix(g.group.get(), g.where, "H", dofs, g.contact);
  readConstraintPart(g.group.get(), g.vectors.get(), g.where, g.vectorsWhere, dofs, P);
  validate(P, "FCLIB file " + path);
  return P;
}

Info readInfo(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  const char* problemName = hasLink(file.get(), kLocalGroup)    ? kLocalGroup
                            : hasLink(file.get(), kGlobalGroup) ? kGlobalGroup
                                                                : nullptr;
  if (!problemName) root.fail("has neither group /fclib_local nor group /fclib_global");
  Handle problem = openGroup(file.get(), root, problemName);
  Info info;
  // The info group and each of its strings are optional in FCLIB.
  if (!hasLink(problem.get(), "info")) return info;
  const Location where = root.child(problemName);
  Handle group = openGroup(problem.get(), where, "info");
  const Location infoWhere = where.child("info");
  auto optionalString = [&](const char* name) {
    return hasLink(group.get(), name) ? readString(group.get(), infoWhere, name) : std::string();
  };
  info.title = optionalString("title");
  info.description = optionalString("description");
  info.math_info = optionalString("math_info");
  return info;
}

namespace {

// Sizes a solution must have for the problem stored in the same file, taken
// from the stored vectors (spacedim x length of mu; length of f), not from
// matrix headers: a broken header is the problem's fault, reported when the
// problem is read, never blamed on the solution.
struct SolutionSizes {
  std::size_t contact = 0;
  std::optional<std::size_t> velocity;
};

SolutionSizes expectedSolutionSizes(hid_t file, const Location& root) {
  const bool local = hasLink(file, kLocalGroup);
  if (!local && !hasLink(file, kGlobalGroup))
    root.fail("has neither group /fclib_local nor group /fclib_global");
  const char* name = local ? kLocalGroup : kGlobalGroup;
  Handle problem = openGroup(file, root, name);
  const Location where = root.child(name);
  Handle vectors = openGroup(problem.get(), where, "vectors");
  const Location vectorsWhere = where.child("vectors");
  SolutionSizes sizes;
  sizes.contact = datasetExtent(vectors.get(), vectorsWhere, "mu") *
                  static_cast<std::size_t>(readSpacedim(problem.get(), where));
  if (!local) sizes.velocity = datasetExtent(vectors.get(), vectorsWhere, "f");
  return sizes;
}

std::vector<double> readSolutionVector(hid_t group, const Location& where, const std::string& name,
                                       const SolutionSizes& sizes) {
  std::optional<std::size_t> expected;
  std::string why;
  if (name == "u" || name == "r") expected = sizes.contact, why = " (spacedim x contacts)";
  if (name == "v") expected = sizes.velocity, why = " (the size of M)";
  // The size of l depends on G, which is absent from every known file: not checked.
  std::vector<double> v = readDoubles(group, where, name, expected, why);
  Checker("FCLIB file " + where.file, where.group).finite(v, name);
  return v;
}

Solution readSolutionGroup(hid_t parent, const Location& parentWhere, const std::string& name,
                           const SolutionSizes& sizes) {
  Handle group = openGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  Solution s;
  for (auto [dataset, vector] : {std::pair<const char*, std::vector<double>*>{"v", &s.v},
                                 {"u", &s.u}, {"r", &s.r}, {"l", &s.l}})
    if (hasLink(group.get(), dataset))
      *vector = readSolutionVector(group.get(), where, dataset, sizes);
  return s;
}

}  // namespace

std::optional<Solution> readSolution(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  if (!hasLink(file.get(), "solution")) return std::nullopt;
  return readSolutionGroup(file.get(), root, "solution", expectedSolutionSizes(file.get(), root));
}

std::optional<Solution> readSolutionLeniently(const std::string& path,
                                              std::vector<std::string>& notes) {
  QuietHdf5Errors quiet;
  try {
    Handle file = openFileForReading(path);
    const Location root{path, ""};
    if (!hasLink(file.get(), "solution")) return std::nullopt;
    const SolutionSizes sizes = expectedSolutionSizes(file.get(), root);
    Handle group = openGroup(file.get(), root, "solution");
    const Location where = root.child("solution");
    Solution s;
    for (auto [dataset, vector] : {std::pair<const char*, std::vector<double>*>{"v", &s.v},
                                   {"u", &s.u}, {"r", &s.r}, {"l", &s.l}}) {
      if (!hasLink(group.get(), dataset)) continue;
      try {
        *vector = readSolutionVector(group.get(), where, dataset, sizes);
      } catch (const std::exception& e) {
        notes.push_back(std::string(e.what()) + "; the stored " + dataset + " is ignored");
      }
    }
    return s;
  } catch (const std::exception& e) {
    notes.push_back(std::string(e.what()) + "; the stored solution is ignored");
    return std::nullopt;
  }
}

std::vector<Solution> readGuesses(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  std::vector<Solution> guesses;
  if (!hasLink(file.get(), "guesses")) return guesses;
  const SolutionSizes sizes = expectedSolutionSizes(file.get(), root);
  Handle group = openGroup(file.get(), root, "guesses");
  const Location where = root.child("guesses");
  const int count = readInt(group.get(), where, "number_of_guesses");
  if (count < 0)
    where.fail(where.path("number_of_guesses") + " = " + std::to_string(count) + " is negative");
  for (int k = 1; k <= count; ++k)
    guesses.push_back(readSolutionGroup(group.get(), where, std::to_string(k), sizes));
  return guesses;
}

namespace {

// The layout both kinds of problem share: the problem group with its
// matrices, its "vectors" subgroup, spacedim and info, then the solution and
// the guesses; written under a temporary and renamed (writeAtomically).
template <class Matrices, class Vectors>
void writeProblem(const std::string& path, const char* groupName, int spacedim, const Info& info,
                  const Solution* solution, const std::vector<Solution>& guesses, Matrices&& matrices,
                  Vectors&& vectors) {
  writeAtomically(path, [&](hid_t file, const Location& root) {
    Handle group = createGroup(file, root, groupName);
    const Location where = root.child(groupName);
    matrices(group.get(), where);
    {
      Handle v = createGroup(group.get(), where, "vectors");
      vectors(v.get(), where.child("vectors"));
    }
    writeInt(group.get(), where, "spacedim", spacedim);
    writeInfo(group.get(), where, info);
    writeSolutionAndGuesses(file, root, solution, guesses);
  });
}

}  // namespace

void writeLocal(const std::string& path, const LocalProblem& P, const Info& info,
                const Solution* solution, const std::vector<Solution>& guesses,
                Storage storage) {
  const std::string context = "FCLIB file " + path + " (writing)";
  validate(P, context);
  checkSolutions(solution, guesses, P.q.size(), std::nullopt, context);
  writeProblem(path, kLocalGroup, P.spacedim, info, solution, guesses,
               [&](hid_t group, const Location& where) {
                 writeMatrix(group, where, "W", P.W, storage);
                 if (P.V) writeMatrix(group, where, "V", *P.V, storage);
                 if (P.R) writeMatrix(group, where, "R", *P.R, storage);
               },
               [&](hid_t vectors, const Location& where) {
                 writeDoubles(vectors, where, "q", P.q);
                 writeDoubles(vectors, where, "mu", P.mu);
                 if (P.s) writeDoubles(vectors, where, "s", *P.s);
               });
}

void writeGlobal(const std::string& path, const GlobalProblem& P, const Info& info,
                 const Solution* solution, const std::vector<Solution>& guesses,
                 Storage storage) {
  const std::string context = "FCLIB file " + path + " (writing)";
  validate(P, context);
  checkSolutions(solution, guesses, P.w.size(), P.f.size(), context);
  writeProblem(path, kGlobalGroup, P.spacedim, info, solution, guesses,
               [&](hid_t group, const Location& where) {
                 writeMatrix(group, where, "M", P.M, storage);
                 writeMatrix(group, where, "H", P.H, storage);
                 if (P.G) writeMatrix(group, where, "G", *P.G, storage);
               },
               [&](hid_t vectors, const Location& where) {
                 writeDoubles(vectors, where, "f", P.f);
                 writeDoubles(vectors, where, "w", P.w);
                 writeDoubles(vectors, where, "mu", P.mu);
                 if (P.b) writeDoubles(vectors, where, "b", *P.b);
               });
}

}  // namespace FCLIB
}  // namespace Tribos
