// Tribos_ResultReader.hpp: rows of a result file read back, e.g. the
// displacement of the last complete step that a restarted run continues
// from (Tribos_StepSeries.hpp, docs/load_history.md). Each rank reads the
// rows it needs itself; the file is opened read-only, independently of the
// other ranks.
#pragma once

#include <string>
#include <vector>

namespace Tribos {
namespace IO {

// A block of rows of a two-dimensional dataset of doubles.
struct DatasetRows {
  long long rows = 0;           // the dataset's number of rows
  long long columns = 0;        // its number of columns
  std::vector<double> values;   // the rows read, row by row
};

// Rows [first, first + count) of the dataset `dataset` (e.g.
// "/nodes/displacement") of the HDF5 file `path`, with the dataset's shape.
// Not collective. Throws Tribos::Error naming the file and the dataset when
// the file cannot be read, the dataset is missing or not two-dimensional,
// or the rows lie beyond it.
DatasetRows readDatasetRows(const std::string& path, const std::string& dataset, long long first, long long count);

// The number attribute `name` of the file's root group (ResultAttributes::
// numbers, e.g. a Dynamics step's running sums that a restart continues
// from). Not collective. Throws Tribos::Error naming the file and the
// attribute when the file cannot be read or the attribute is missing or not
// one number.
double readRootNumber(const std::string& path, const std::string& name);

}  // namespace IO
}  // namespace Tribos
