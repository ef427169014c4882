#include "Tribos_FCLIB.hpp"

#include <hdf5.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <utility>

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

// HDF5 prints its error stack to stderr by default; the messages thrown here
// say more, so printing is switched off while this library talks to HDF5.
class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// Where we are in which file, for error messages.
struct Location {
  std::string file;
  std::string group;  // path inside the file, without leading '/'

  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("FCLIB file " + file + ": " + why);
  }
  Location child(const std::string& name) const {
    return {file, group.empty() ? name : group + "/" + name};
  }
  std::string groupLabel() const { return group.empty() ? "root group" : "group " + group; }
};

bool hasLink(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

Handle openGroup(hid_t loc, const Location& where, const std::string& name) {
  if (!hasLink(loc, name)) where.fail(where.groupLabel() + " has no group " + name);
  hid_t id = H5Gopen2(loc, name.c_str(), H5P_DEFAULT);
  if (id < 0) where.fail("cannot open group " + where.child(name).group);
  return Handle(id, H5Gclose);
}

Handle openDataset(hid_t loc, const Location& where, const std::string& name) {
  if (!hasLink(loc, name)) where.fail(where.groupLabel() + " has no dataset " + name);
  hid_t id = H5Dopen2(loc, name.c_str(), H5P_DEFAULT);
  if (id < 0) where.fail("cannot open dataset " + where.child(name).group);
  return Handle(id, H5Dclose);
}

Handle openFileForReading(const std::string& path) {
  if (!std::ifstream(path).good())
    throw std::runtime_error("FCLIB file " + path + ": cannot open for reading");
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw std::runtime_error("FCLIB file " + path + ": not a readable HDF5 file");
  return Handle(id, H5Fclose);
}

// ---------------------------------------------------------------- reading

hssize_t elementCount(hid_t dataset, const Location& where, const std::string& name) {
  Handle space(H5Dget_space(dataset), H5Sclose);
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) where.fail("cannot get the size of dataset " + where.child(name).group);
  return count;
}

template <typename T>
std::vector<T> readArray(hid_t loc, const Location& where, const std::string& name,
                         hid_t memType) {
  Handle dataset = openDataset(loc, where, name);
  std::vector<T> data(static_cast<std::size_t>(elementCount(dataset.get(), where, name)));
  if (!data.empty() &&
      H5Dread(dataset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    where.fail("cannot read dataset " + where.child(name).group);
  return data;
}

std::vector<double> readDoubles(hid_t loc, const Location& where, const std::string& name) {
  return readArray<double>(loc, where, name, H5T_NATIVE_DOUBLE);
}

std::vector<int> readInts(hid_t loc, const Location& where, const std::string& name) {
  return readArray<int>(loc, where, name, H5T_NATIVE_INT);
}

int readInt(hid_t loc, const Location& where, const std::string& name) {
  std::vector<int> value = readInts(loc, where, name);
  if (value.size() != 1)
    where.fail("dataset " + where.child(name).group + " should hold one integer, has " +
               std::to_string(value.size()) + " values");
  return value[0];
}

std::vector<double> readVector(hid_t loc, const Location& where, const std::string& name,
                               std::size_t expected) {
  std::vector<double> v = readDoubles(loc, where, name);
  if (v.size() != expected)
    where.fail("dataset " + where.child(name).group + " has " + std::to_string(v.size()) +
               " entries, expected " + std::to_string(expected));
  return v;
}

std::string readString(hid_t loc, const Location& where, const std::string& name) {
  Handle dataset = openDataset(loc, where, name);
  Handle fileType(H5Dget_type(dataset.get()), H5Tclose);
  if (H5Tget_class(fileType.get()) != H5T_STRING)
    where.fail("dataset " + where.child(name).group + " is not a string");
  Handle memType(H5Tcopy(H5T_C_S1), H5Tclose);
  if (H5Tis_variable_str(fileType.get()) > 0) {
    H5Tset_size(memType.get(), H5T_VARIABLE);
    char* text = nullptr;
    if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0)
      where.fail("cannot read string " + where.child(name).group);
    std::string result = text ? text : "";
    H5free_memory(text);
    return result;
  }
  const std::size_t size = H5Tget_size(fileType.get());
  H5Tset_size(memType.get(), size + 1);  // room for a terminator if the file has none
  std::vector<char> buffer(size + 1, '\0');
  if (H5Dread(dataset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
    where.fail("cannot read string " + where.child(name).group);
  return std::string(buffer.data());
}

SparseMatrix readMatrix(hid_t parent, const Location& parentWhere, const std::string& name) {
  Handle group = openGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  const int m = readInt(group.get(), where, "m");
  const int n = readInt(group.get(), where, "n");
  const int nz = readInt(group.get(), where, "nz");
  std::vector<int> p = readInts(group.get(), where, "p");
  std::vector<int> i = readInts(group.get(), where, "i");
  std::vector<double> x = readDoubles(group.get(), where, "x");
  const std::string what = "FCLIB file " + where.file + ": matrix " + where.group;
  if (nz == -2) return SparseMatrix::fromCSR(m, n, p, i, x, what);
  if (nz == -1) return SparseMatrix::fromCSC(m, n, p, i, x, what);
  if (nz < 0) where.fail("matrix " + where.group + " has invalid nz = " + std::to_string(nz));
  // Triplets: only the first nz entries are meaningful (arrays may be nzmax long).
  if (p.size() < static_cast<std::size_t>(nz) || i.size() < static_cast<std::size_t>(nz) ||
      x.size() < static_cast<std::size_t>(nz))
    where.fail("matrix " + where.group + " has nz = " + std::to_string(nz) +
               " but shorter i, p or x arrays");
  p.resize(nz);
  i.resize(nz);
  x.resize(nz);
  return SparseMatrix::fromTriplets(m, n, i, p, x, what);
}

std::optional<SparseMatrix> readOptionalMatrix(hid_t parent, const Location& where,
                                               const std::string& name) {
  if (!hasLink(parent, name)) return std::nullopt;
  return readMatrix(parent, where, name);
}

// ---------------------------------------------------------------- writing

Handle createGroup(hid_t loc, const Location& where, const std::string& name) {
  hid_t id = H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) where.fail("cannot create group " + where.child(name).group);
  return Handle(id, H5Gclose);
}

void writeArray(hid_t loc, const Location& where, const std::string& name, hid_t fileType,
                hid_t memType, const void* data, std::size_t count) {
  hsize_t dims[1] = {static_cast<hsize_t>(count)};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle dataset(H5Dcreate2(loc, name.c_str(), fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose);
  if (dataset.get() < 0) where.fail("cannot create dataset " + where.child(name).group);
  if (count > 0 && H5Dwrite(dataset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    where.fail("cannot write dataset " + where.child(name).group);
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
    where.fail("cannot write string " + where.child(name).group);
}

void writeMatrix(hid_t parent, const Location& parentWhere, const std::string& name,
                 const SparseMatrix& A, Storage storage) {
  Handle group = createGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  const hid_t g = group.get();
  writeInt(g, where, "nzmax", A.nnz());
  writeInt(g, where, "m", A.m);
  writeInt(g, where, "n", A.n);
  if (storage == Storage::CompressedRows) {
    writeInt(g, where, "nz", -2);
    writeInts(g, where, "p", A.rowptr);
    writeInts(g, where, "i", A.col);
  } else {
    std::vector<int> row, column;
    A.toTriplets(row, column);
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

// Runs 'body' on a fresh HDF5 file at path + ".tmp" and renames it onto path
// only after the file is closed without error; on failure the temporary file
// is removed and whatever was at path is left untouched.
template <typename Body>
void writeAtomically(const std::string& path, Body body) {
  const std::string tmp = path + ".tmp";
  QuietHdf5Errors quiet;
  try {
    {
      hid_t id = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      if (id < 0) throw std::runtime_error("FCLIB file " + path + ": cannot create " + tmp);
      Handle file(id, H5Fclose);
      body(file.get(), Location{path, ""});
      if (H5Fflush(file.get(), H5F_SCOPE_LOCAL) < 0)
        throw std::runtime_error("FCLIB file " + path + ": cannot flush " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw std::runtime_error("FCLIB file " + path + ": cannot rename " + tmp + " onto it");
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

// ---------------------------------------------------------------- checks

void require(bool condition, const std::string& where, const std::string& message) {
  if (!condition) throw std::runtime_error(where + ": " + message);
}

std::string dims(const SparseMatrix& A) {
  return std::to_string(A.m) + " x " + std::to_string(A.n);
}

std::string sizeMismatch(const std::string& name, std::size_t actual, std::size_t expected) {
  return name + " has " + std::to_string(actual) + " entries, expected " +
         std::to_string(expected);
}

void checkSpacedim(int spacedim, const std::string& where) {
  require(spacedim == 2 || spacedim == 3, where,
          "spacedim is " + std::to_string(spacedim) + ", expected 2 or 3");
}

}  // namespace

// ---------------------------------------------------------------- public

void checkDimensions(const LocalProblem& P, const std::string& where) {
  checkSpacedim(P.spacedim, where);
  const std::size_t nc = P.mu.size();
  const int m = static_cast<int>(nc) * P.spacedim;
  require(P.W.m == m && P.W.n == m, where,
          "W is " + dims(P.W) + ", expected " + std::to_string(m) + " x " + std::to_string(m) +
              " for " + std::to_string(nc) + " contacts (length of mu)");
  require(P.q.size() == static_cast<std::size_t>(m), where, sizeMismatch("q", P.q.size(), m));
  if (P.V || P.R || P.s) {
    require(P.V && P.R && P.s, where, "V, R and s must be given together");
    const int p = P.R->m;
    require(P.V->m == m && P.V->n == p, where, "V is " + dims(*P.V) + ", expected " +
                                                   std::to_string(m) + " x " + std::to_string(p));
    require(P.R->n == p, where, "R is " + dims(*P.R) + ", expected square");
    require(P.s->size() == static_cast<std::size_t>(p), where, sizeMismatch("s", P.s->size(), p));
  }
}

void checkDimensions(const GlobalProblem& P, const std::string& where) {
  checkSpacedim(P.spacedim, where);
  const std::size_t nc = P.mu.size();
  const int m = static_cast<int>(nc) * P.spacedim;
  const int ndof = P.M.m;
  require(P.M.n == ndof, where, "M is " + dims(P.M) + ", expected square");
  require(P.H.m == ndof && P.H.n == m, where,
          "H is " + dims(P.H) + ", expected " + std::to_string(ndof) + " x " +
              std::to_string(m) + " (rows = size of M, columns = spacedim x contacts)");
  require(P.f.size() == static_cast<std::size_t>(ndof), where, sizeMismatch("f", P.f.size(), ndof));
  require(P.w.size() == static_cast<std::size_t>(m), where, sizeMismatch("w", P.w.size(), m));
  if (P.G || P.b) {
    require(P.G && P.b, where, "G and b must be given together");
    require(P.G->m == ndof, where, "G is " + dims(*P.G) + ", expected " + std::to_string(ndof) +
                                       " rows");
    require(P.b->size() == static_cast<std::size_t>(P.G->n), where,
            sizeMismatch("b", P.b->size(), P.G->n));
  }
}

ProblemKind problemKind(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  if (hasLink(file.get(), kLocalGroup)) return ProblemKind::Local;
  if (hasLink(file.get(), kGlobalGroup)) return ProblemKind::Global;
  throw std::runtime_error("FCLIB file " + path + ": has neither group fclib_local nor " +
                           "group fclib_global");
}

LocalProblem readLocal(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  Handle group = openGroup(file.get(), root, kLocalGroup);
  const Location where = root.child(kLocalGroup);
  Handle vectors = openGroup(group.get(), where, "vectors");
  const Location vectorsWhere = where.child("vectors");

  LocalProblem P;
  P.spacedim = readInt(group.get(), where, "spacedim");
  checkSpacedim(P.spacedim, "FCLIB file " + path + ": group " + where.group);
  P.W = readMatrix(group.get(), where, "W");
  P.V = readOptionalMatrix(group.get(), where, "V");
  P.R = readOptionalMatrix(group.get(), where, "R");
  P.mu = readDoubles(vectors.get(), vectorsWhere, "mu");
  const std::size_t m = P.mu.size() * P.spacedim;
  P.q = readVector(vectors.get(), vectorsWhere, "q", m);
  if (hasLink(vectors.get(), "s"))
    P.s = readVector(vectors.get(), vectorsWhere, "s", P.R ? P.R->m : 0);
  checkDimensions(P, "FCLIB file " + path + ": group " + where.group);
  return P;
}

GlobalProblem readGlobal(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  Handle group = openGroup(file.get(), root, kGlobalGroup);
  const Location where = root.child(kGlobalGroup);
  Handle vectors = openGroup(group.get(), where, "vectors");
  const Location vectorsWhere = where.child("vectors");

  GlobalProblem P;
  P.spacedim = readInt(group.get(), where, "spacedim");
  checkSpacedim(P.spacedim, "FCLIB file " + path + ": group " + where.group);
  P.M = readMatrix(group.get(), where, "M");
  P.H = readMatrix(group.get(), where, "H");
  P.G = readOptionalMatrix(group.get(), where, "G");
  P.mu = readDoubles(vectors.get(), vectorsWhere, "mu");
  P.f = readVector(vectors.get(), vectorsWhere, "f", P.M.m);
  P.w = readVector(vectors.get(), vectorsWhere, "w", P.mu.size() * P.spacedim);
  if (hasLink(vectors.get(), "b"))
    P.b = readVector(vectors.get(), vectorsWhere, "b", P.G ? P.G->n : 0);
  checkDimensions(P, "FCLIB file " + path + ": group " + where.group);
  return P;
}

Info readInfo(const std::string& path) {
  QuietHdf5Errors quiet;
  Handle file = openFileForReading(path);
  const Location root{path, ""};
  const char* problemName = hasLink(file.get(), kLocalGroup)    ? kLocalGroup
                            : hasLink(file.get(), kGlobalGroup) ? kGlobalGroup
                                                                : nullptr;
  if (!problemName) root.fail("has neither group fclib_local nor group fclib_global");
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

// Sizes a solution must have for the problem stored in the same file:
// u and r have spacedim x contacts entries, v has the size of M (global only).
struct SolutionSizes {
  std::size_t contact = 0;
  std::optional<std::size_t> velocity;
};

SolutionSizes expectedSolutionSizes(hid_t file, const Location& root) {
  SolutionSizes sizes;
  if (hasLink(file, kLocalGroup)) {
    Handle problem = openGroup(file, root, kLocalGroup);
    const Location where = root.child(kLocalGroup);
    Handle W = openGroup(problem.get(), where, "W");
    sizes.contact = readInt(W.get(), where.child("W"), "m");
  } else if (hasLink(file, kGlobalGroup)) {
    Handle problem = openGroup(file, root, kGlobalGroup);
    const Location where = root.child(kGlobalGroup);
    Handle H = openGroup(problem.get(), where, "H");
    sizes.contact = readInt(H.get(), where.child("H"), "n");
    sizes.velocity = readInt(H.get(), where.child("H"), "m");
  } else {
    root.fail("has neither group fclib_local nor group fclib_global");
  }
  return sizes;
}

Solution readSolutionGroup(hid_t parent, const Location& parentWhere, const std::string& name,
                           const SolutionSizes& sizes) {
  Handle group = openGroup(parent, parentWhere, name);
  const Location where = parentWhere.child(name);
  Solution s;
  if (hasLink(group.get(), "u")) s.u = readVector(group.get(), where, "u", sizes.contact);
  if (hasLink(group.get(), "r")) s.r = readVector(group.get(), where, "r", sizes.contact);
  if (hasLink(group.get(), "v")) {
    s.v = readDoubles(group.get(), where, "v");
    if (sizes.velocity && s.v.size() != *sizes.velocity)
      where.fail("dataset " + where.child("v").group + " has " + std::to_string(s.v.size()) +
                 " entries, expected " + std::to_string(*sizes.velocity));
  }
  // The size of l depends on G, which is absent from every known file: not checked.
  if (hasLink(group.get(), "l")) s.l = readDoubles(group.get(), where, "l");
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
  if (count < 0) where.fail("number_of_guesses is negative");
  for (int k = 1; k <= count; ++k)
    guesses.push_back(readSolutionGroup(group.get(), where, std::to_string(k), sizes));
  return guesses;
}

void writeLocal(const std::string& path, const LocalProblem& P, const Info& info,
                const Solution* solution, const std::vector<Solution>& guesses,
                Storage storage) {
  checkDimensions(P, "FCLIB file " + path + ": local problem to write");
  writeAtomically(path, [&](hid_t file, const Location& root) {
    Handle group = createGroup(file, root, kLocalGroup);
    const Location where = root.child(kLocalGroup);
    writeMatrix(group.get(), where, "W", P.W, storage);
    if (P.V) writeMatrix(group.get(), where, "V", *P.V, storage);
    if (P.R) writeMatrix(group.get(), where, "R", *P.R, storage);
    {
      Handle vectors = createGroup(group.get(), where, "vectors");
      const Location vectorsWhere = where.child("vectors");
      writeDoubles(vectors.get(), vectorsWhere, "q", P.q);
      writeDoubles(vectors.get(), vectorsWhere, "mu", P.mu);
      if (P.s) writeDoubles(vectors.get(), vectorsWhere, "s", *P.s);
    }
    writeInt(group.get(), where, "spacedim", P.spacedim);
    writeInfo(group.get(), where, info);
    writeSolutionAndGuesses(file, root, solution, guesses);
  });
}

void writeGlobal(const std::string& path, const GlobalProblem& P, const Info& info,
                 const Solution* solution, const std::vector<Solution>& guesses,
                 Storage storage) {
  checkDimensions(P, "FCLIB file " + path + ": global problem to write");
  writeAtomically(path, [&](hid_t file, const Location& root) {
    Handle group = createGroup(file, root, kGlobalGroup);
    const Location where = root.child(kGlobalGroup);
    writeMatrix(group.get(), where, "M", P.M, storage);
    writeMatrix(group.get(), where, "H", P.H, storage);
    if (P.G) writeMatrix(group.get(), where, "G", *P.G, storage);
    {
      Handle vectors = createGroup(group.get(), where, "vectors");
      const Location vectorsWhere = where.child("vectors");
      writeDoubles(vectors.get(), vectorsWhere, "f", P.f);
      writeDoubles(vectors.get(), vectorsWhere, "w", P.w);
      writeDoubles(vectors.get(), vectorsWhere, "mu", P.mu);
      if (P.b) writeDoubles(vectors.get(), vectorsWhere, "b", *P.b);
    }
    writeInt(group.get(), where, "spacedim", P.spacedim);
    writeInfo(group.get(), where, info);
    writeSolutionAndGuesses(file, root, solution, guesses);
  });
}

}  // namespace FCLIB
}  // namespace Tribos
