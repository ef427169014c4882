// Tribos_ResultWriter.hpp: results to one parallel HDF5 file per run with an
// XDMF index that ParaView opens directly. Every rank writes the nodes it owns
// and the cells of its subdomains as contiguous hyperslabs (MPI-IO).
// The writer writes to the paths it is given (temporaries of a ResultSet,
// Tribos_ResultSet.hpp, which renames them when the whole set is written) and
// turns every HDF5 or file failure on any rank into the same exception on
// every rank, with the partial files removed.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_Discretization.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace IO {

// What the components of a field are, as the XDMF index names them for
// ParaView: FromComponents (1 Scalar, 3 Vector, other counts Matrix),
// SymmetricTensor (6 components in XDMF's Tensor6 order xx, xy, xz, yy, yz,
// zz; ParaView shows the full tensor) or Matrix (columns of a table, e.g.
// the partners of a contact node, whatever their count).
enum class FieldShape { FromComponents, SymmetricTensor, Matrix };
const char* xdmfAttributeType(FieldShape shape, int components);

struct Field {
  std::string name;
  int components = 1;
  std::vector<double> values;  // owned nodes (in ownedNodes() order) or local cells, times components
  FieldShape shape = FieldShape::FromComponents;
};

// A set of points with their own fields (e.g. contact nodes), written as a
// second XDMF grid of vertices. It may be empty on some or all ranks.
struct PointSet {
  std::string name;
  std::vector<std::array<double, 3>> coords;  // this rank's points
  std::vector<Field> fields;                  // per point of this rank
};

// Attributes of the HDF5 file's root group, identical on every rank.
struct ResultAttributes {
  std::vector<std::pair<std::string, std::string>> text;  // e.g. stop_reason, problem
  std::vector<std::pair<std::string, double>> numbers;    // e.g. converged (1/0), solver_converged
};

// What one write put in its HDF5 file, as an XDMF grid describes it; the
// same on every rank. The datasets are /mesh/geometry (nodes x 3),
// /mesh/topology (cells x nodesPerCell, integers: rows of /mesh/geometry, in
// XDMF's node order, xdmfNodeOrder; for a mesh of several cell types,
// `mixed`, XDMF's Mixed list instead: topologyEntries x 1, each cell's type
// number (Tet4 6, Hex8 9, Tet10 38, Hex20 48) followed by its nodes),
// /nodes/NAME (nodes x components; displacement first), /cells/NAME
// (cells x components), and per point set /points/SET/geometry (points x 3)
// and /points/SET/NAME (points x components).
// The node of Tribos' (Gmsh's) cell at each place of XDMF's: topology row k
// holds cell node xdmfNodeOrder(type)[k]. XDMF's Tetrahedron_10 and
// Hexahedron_20 are VTK's quadratic tetrahedron and hexahedron: the
// tetrahedron's mid-edge nodes on the edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3
// (Gmsh: ..., 3-0, 3-2, 3-1: 8 and 9 swap), the hexahedron's on the bottom
// edges 0-1, 1-2, 2-3, 3-0, the top edges 4-5, 5-6, 6-7, 7-4, then the
// vertical edges 0-4, 1-5, 2-6, 3-7 (Gmsh: 0-1, 0-3, 0-4, 1-2, 1-5, 2-3,
// 2-6, 3-7, 4-5, 4-7, 5-6, 6-7). Tet4 and Hex8 keep their order.
const std::vector<int>& xdmfNodeOrder(Mesh::CellType type);

struct ResultLayout {
  struct FieldLayout {
    std::string name;
    int components = 1;
    FieldShape shape = FieldShape::FromComponents;
  };
  struct PointSetLayout {
    std::string name;
    long long points = 0;
    std::vector<FieldLayout> fields;
  };
  Mesh::CellType cellType = Mesh::CellType::Hex8;  // of every cell, unless mixed
  bool mixed = false;                              // cells of several types
  int nodesPerCell = 8;                            // the topology's columns (1 when mixed)
  long long topologyEntries = 0;                   // the topology's numbers
  long long nodes = 0, cells = 0;
  std::vector<FieldLayout> nodeFields;  // displacement first, then the caller's
  std::vector<FieldLayout> cellFields;
  std::vector<PointSetLayout> pointSets;
};

class ResultWriter {
 public:
  ResultWriter(const Mesh::Discretization& disc, const RCP<const Comm>& comm);

  // Writes the HDF5 file to h5Path and the XDMF index to xmfPath (rank 0);
  // the index names the HDF5 file h5Name (its final name, relative: the two
  // files end up in one directory). uOwned: the displacement of the owned
  // nodes (3 per node of disc.ownedNodes(), in its order); nodeFields per owned node, cellFields per local cell,
  // pointSets per point of this rank; every rank passes the same names,
  // components and attributes. Collective. On any HDF5 or file failure on
  // any rank, every rank closes what it opened, rank 0 removes the partial
  // files, and every rank throws Tribos::RunFailure with one message (naming
  // the call, the dataset, the file and the system's reason). Arguments that
  // differ between ranks or fields of the wrong size: Tribos::CollectiveError
  // on every rank, nothing written.
  void write(const std::string& h5Path, const std::string& h5Name, const std::string& xmfPath,
             const std::vector<double>& uOwned, const std::vector<Field>& nodeFields,
             const std::vector<Field>& cellFields, const std::vector<PointSet>& pointSets = {},
             const ResultAttributes& attributes = {}) const;

  // The HDF5 file alone (what write() writes to h5Path, with the same checks
  // and failures; on failure rank 0 removes the partial file), returning
  // what it holds so that the caller can index it, e.g. as one step of a
  // time series (Tribos_StepSeries.hpp). Collective.
  ResultLayout writeData(const std::string& h5Path, const std::string& h5Name, const std::vector<double>& uOwned,
                         const std::vector<Field>& nodeFields, const std::vector<Field>& cellFields,
                         const std::vector<PointSet>& pointSets = {}, const ResultAttributes& attributes = {}) const;

  // Before HDF5 writes anything, rank 0 checks that the file fits (fallocate
  // of a bound of its size, released again), and before the data it reserves
  // the file's blocks: a full disk, a quota or a file size limit then fails
  // there, in one clean step. On by default. Off only to test the failure of
  // the data writes themselves: without it, a disk that cannot take HDF5's
  // metadata makes HDF5 1.10 hang (rank 0 leaves a collective flush early)
  // or crash in MPI_Finalize (a file whose close failed stays registered).
  void reserveSpace(bool on) { reserveSpace_ = on; }

 private:
  const Mesh::Discretization& disc_;
  RCP<const Comm> comm_;
  bool reserveSpace_ = true;
};

// The XDMF index of one result file h5Name (a name relative to the index):
// a grid "body" of the mesh with its node and cell fields, and one grid of
// vertices per point set. What write() writes to xmfPath.
std::string xdmfIndex(const std::string& h5Name, const ResultLayout& layout);

// One step of a time series: its pseudo-time and the result file that holds it.
struct SeriesStep {
  double time = 0;
  std::string h5Name;  // relative to the index
  ResultLayout layout;
};

// The XDMF index of a time series, which ParaView plays: a temporal
// collection (Grid "steps", GridType="Collection" CollectionType="Temporal")
// with, per step in the order given, a spatial collection "step K" holding
// <Time Value="t"/> and the grids xdmfIndex gives that step's file.
std::string xdmfTimeSeries(const std::vector<SeriesStep>& steps);
// Its three parts, xdmfTimeSeries = head + step(1) + ... + step(N) + tail:
// a series adds a step by writing step(K) + tail over the old tail.
std::string xdmfTimeSeriesHead();
std::string xdmfTimeSeriesStep(int step, const SeriesStep& s);
std::string xdmfTimeSeriesTail();

// Writes text to path atomically: to path's directory under a temporary name
// unique to this process (.NAME.<pid>.tmp), flushed to the device, then
// renamed. Not collective. On failure the temporary is removed, the old file
// at path is untouched, and Tribos::RunFailure is thrown on the calling rank.
void writeFileAtomically(const std::string& path, const std::string& text);

// The same, collective: rank 0 writes, every rank throws Tribos::RunFailure
// if it failed.
void writeFileAtomically(const std::string& path, const std::string& text, const RCP<const Comm>& comm);

}  // namespace IO
}  // namespace Tribos
