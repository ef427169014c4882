// IoTestSupport.hpp: what the io tests share: a scratch directory per test
// case, a small distributed mesh with fields, and file helpers.
#pragma once

#include <dirent.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_TestSupport.hpp"
#include "Tribos_FileSystem.hpp"
#include "Tribos_ResultWriter.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace Test {

// A fresh directory under TMPDIR (or /tmp), made by rank 0, known to all.
inline std::string scratchDirectory(const Comm& comm, const std::string& tag) {
  std::string path;
  if (comm.getRank() == 0) {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/tribos_" + tag + "_XXXXXX";
    path = ::mkdtemp(&pattern[0]) ? pattern : "";
  }
  return broadcastFromRoot(comm, path);
}

inline void removeTree(const std::string& path) {
  if (DIR* d = ::opendir(path.c_str())) {
    while (const dirent* e = ::readdir(d)) {
      const std::string name = e->d_name;
      if (name == "." || name == "..") continue;
      const std::string child = path + "/" + name;
      struct stat st;
      if (::lstat(child.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) removeTree(child);
      else ::unlink(child.c_str());
    }
    ::closedir(d);
  }
  ::rmdir(path.c_str());
}

// A scratch directory for one test case, removed by rank 0 once every rank is
// done with it (declare it before the objects that use it).
class ScratchDirectory {
 public:
  ScratchDirectory(const RCP<const Comm>& comm, const std::string& tag)
      : comm_(comm), path_(scratchDirectory(*comm, tag)) {}
  ~ScratchDirectory() {
    comm_->barrier();
    if (comm_->getRank() == 0 && !path_.empty()) removeTree(path_);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::string& path() const { return path_; }

 private:
  RCP<const Comm> comm_;
  std::string path_;
};

inline bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

inline std::vector<std::string> listDirectory(const std::string& path) {
  std::vector<std::string> names;
  if (DIR* d = ::opendir(path.c_str())) {
    while (const dirent* e = ::readdir(d))
      if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
    ::closedir(d);
  }
  return names;
}

// Files of a directory that a run uses as temporaries.
inline std::vector<std::string> temporariesIn(const std::string& path) {
  std::vector<std::string> found;
  for (const std::string& name : listDirectory(path))
    if (isTemporaryName(name) || name.find(".tmp") != std::string::npos) found.push_back(name);
  return found;
}

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void writePlainFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// An nx x ny x nz Hex8 box in nx structured subdomains along x, spread over the ranks.
inline Mesh::Discretization boxDiscretization(int nx, int ny, int nz, const Comm& comm) {
  Mesh::BoxSpec spec;
  spec.type = Mesh::CellType::Hex8;
  spec.cells = {nx, ny, nz};
  Mesh::DecompositionSpec dec;
  dec.partitioner = "Structured";
  dec.grid = {std::max(2, comm.getSize()), 1, 1};
  return Mesh::Discretization(Mesh::generateBox(spec), spec, dec, comm.getSize(), comm.getRank());
}

// u(x) = (x, 2y, 3z) + 10 * mesh node number: every value tells where it belongs.
inline double displacementAt(const std::array<double, 3>& x, int meshNode, int d) {
  return (d + 1) * x[d] + 10.0 * meshNode;
}

// At the owned nodes, as the writer takes it.
inline std::vector<double> displacementOf(const Mesh::Discretization& disc) {
  std::vector<double> u;
  for (int n : disc.ownedNodes())
    for (int d = 0; d < 3; ++d) u.push_back(displacementAt(disc.part.coords[n], disc.meshNode(n), d));
  return u;
}

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

}  // namespace Test
}  // namespace Tribos
