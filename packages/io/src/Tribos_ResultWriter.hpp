// Tribos_ResultWriter.hpp: results to one parallel HDF5 file per run with an
// XDMF index that ParaView opens directly. Every rank writes the nodes it owns
// and the cells of its subdomains as contiguous hyperslabs (collective MPI-IO).
// Files are written under a temporary name and renamed when complete, so a
// failed run never leaves a partial file in place of a good one.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

struct Field {
  std::string name;
  int components = 1;
  std::vector<double> values;  // owned nodes (in ownedNodes() order) or local cells, times components
};

// A set of points with their own fields (e.g. contact nodes), written as a
// second XDMF grid of vertices.
struct PointSet {
  std::string name;
  std::vector<std::array<double, 3>> coords;  // this rank's points
  std::vector<Field> fields;                  // per point of this rank
};

class ResultWriter {
 public:
  ResultWriter(const Mesh::Discretization& disc, const RCP<const Comm>& comm);

  // uGlobal: replicated displacement (3 numNodes). nodeFields/cellFields as above.
  void write(const std::string& directory, const std::string& baseName, const std::vector<double>& uGlobal,
             const std::vector<Field>& nodeFields, const std::vector<Field>& cellFields,
             const std::vector<PointSet>& pointSets = {}) const;

 private:
  const Mesh::Discretization& disc_;
  RCP<const Comm> comm_;
};

// Writes text to path atomically (temporary file + rename).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace IO
}  // namespace Tribos
