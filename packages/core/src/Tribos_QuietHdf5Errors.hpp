// Tribos_QuietHdf5Errors.hpp: HDF5 prints its whole error stack on stderr by
// default, on every failing rank. Tribos reports one line naming the file
// and dataset instead, so printing is off while an object of this class
// lives; the previous handler is restored, so other users of HDF5 in the
// process keep theirs. (For targets that link HDF5.)
#pragma once

#include <hdf5.h>

namespace Tribos {

class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace Tribos
