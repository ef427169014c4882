#include "Tribos_ResultReader.hpp"

#include <hdf5.h>

#include "Tribos_Error.hpp"
#include "Tribos_QuietHdf5Errors.hpp"

namespace Tribos {
namespace IO {

namespace {

// An HDF5 identifier closed by its closer when the scope ends.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t id() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

}  // namespace

DatasetRows readDatasetRows(const std::string& path, const std::string& dataset, long long first, long long count) {
  QuietHdf5Errors quiet;  // the message below says what failed, once
  const std::string what = "the result file " + path + ", dataset " + dataset;
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  TRIBOS_REQUIRE(file.valid(), "cannot open the result file " << path << " as HDF5");
  // (H5Lexists fails, < 0, when a group on the path is missing.)
  TRIBOS_REQUIRE(H5Lexists(file.id(), dataset.c_str(), H5P_DEFAULT) > 0, what << ": no such dataset");
  const Handle data(H5Dopen2(file.id(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  TRIBOS_REQUIRE(data.valid(), what << ": cannot open the dataset");
  const Handle space(H5Dget_space(data.id()), H5Sclose);
  TRIBOS_REQUIRE(space.valid() && H5Sget_simple_extent_ndims(space.id()) == 2, what << ": not a two-dimensional dataset");
  hsize_t shape[2] = {0, 0};
  H5Sget_simple_extent_dims(space.id(), shape, nullptr);
  DatasetRows out;
  out.rows = static_cast<long long>(shape[0]);
  out.columns = static_cast<long long>(shape[1]);
  TRIBOS_REQUIRE(first >= 0 && count >= 0 && first + count <= out.rows,
                 what << ": rows " << first << " to " << first + count - 1 << " asked of " << out.rows);
  out.values.resize(static_cast<size_t>(count * out.columns));
  if (count == 0 || out.columns == 0) return out;
  const hsize_t start[2] = {static_cast<hsize_t>(first), 0}, block[2] = {static_cast<hsize_t>(count), shape[1]};
  TRIBOS_REQUIRE(H5Sselect_hyperslab(space.id(), H5S_SELECT_SET, start, nullptr, block, nullptr) >= 0,
                 what << ": cannot select rows " << first << " to " << first + count - 1);
  const Handle memory(H5Screate_simple(2, block, nullptr), H5Sclose);
  TRIBOS_REQUIRE(memory.valid() && H5Dread(data.id(), H5T_NATIVE_DOUBLE, memory.id(), space.id(), H5P_DEFAULT,
                                           out.values.data()) >= 0,
                 what << ": cannot read rows " << first << " to " << first + count - 1);
  return out;
}

double readRootNumber(const std::string& path, const std::string& name) {
  QuietHdf5Errors quiet;
  const std::string what = "the result file " + path + ", root attribute " + name;
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  TRIBOS_REQUIRE(file.valid(), "cannot open the result file " << path << " as HDF5");
  TRIBOS_REQUIRE(H5Aexists(file.id(), name.c_str()) > 0, what << ": no such attribute");
  const Handle attribute(H5Aopen(file.id(), name.c_str(), H5P_DEFAULT), H5Aclose);
  TRIBOS_REQUIRE(attribute.valid(), what << ": cannot open the attribute");
  const Handle space(H5Aget_space(attribute.id()), H5Sclose);
  TRIBOS_REQUIRE(space.valid() && H5Sget_simple_extent_npoints(space.id()) == 1, what << ": not one number");
  const Handle type(H5Aget_type(attribute.id()), H5Tclose);
  TRIBOS_REQUIRE(type.valid() && H5Tget_class(type.id()) == H5T_FLOAT, what << ": not a number");
  double value = 0;
  TRIBOS_REQUIRE(H5Aread(attribute.id(), H5T_NATIVE_DOUBLE, &value) >= 0, what << ": cannot read it");
  return value;
}

}  // namespace IO
}  // namespace Tribos
