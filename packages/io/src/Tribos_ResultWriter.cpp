#include "Tribos_ResultWriter.hpp"

#include <hdf5.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace IO {

namespace {

MPI_Comm rawComm(const RCP<const Comm>& comm) {
  return *Teuchos::rcp_dynamic_cast<const Teuchos::MpiComm<int>>(comm, true)->getRawMpiComm();
}

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

class H5File {
 public:
  H5File(const std::string& path, MPI_Comm comm) : path_(path) {
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
    id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    TRIBOS_REQUIRE(id >= 0, "cannot create HDF5 file " << path);
  }
  ~H5File() {
    if (id >= 0) H5Fclose(id);
  }
  void close() {
    TRIBOS_REQUIRE(H5Fclose(id) >= 0, "cannot close HDF5 file " << path_);
    id = -1;
  }
  // Collective write of rows [offset, offset + count) of a total x cols dataset.
  template <class T>
  void writeRows(const std::string& name, const std::vector<T>& data, long long offset, long long count, long long total,
                 int cols) {
    const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
    hsize_t dims[2] = {static_cast<hsize_t>(total), static_cast<hsize_t>(cols)};
    hid_t fspace = H5Screate_simple(2, dims, nullptr);
    hid_t dset = H5Dcreate2(id, name.c_str(), type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    TRIBOS_REQUIRE(dset >= 0, "cannot create dataset " << name << " in " << path_);
    hsize_t start[2] = {static_cast<hsize_t>(offset), 0}, cnt[2] = {static_cast<hsize_t>(count), static_cast<hsize_t>(cols)};
    H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, cnt, nullptr);
    hid_t mspace = H5Screate_simple(2, cnt, nullptr);
    hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
    H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
    const herr_t st = H5Dwrite(dset, type, mspace, fspace, dxpl, data.empty() ? nullptr : data.data());
    H5Pclose(dxpl);
    H5Sclose(mspace);
    H5Sclose(fspace);
    H5Dclose(dset);
    TRIBOS_REQUIRE(st >= 0, "cannot write dataset " << name << " in " << path_);
  }
  hid_t id = -1;

 private:
  std::string path_;
};

std::string baseNameOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == std::string::npos ? path : path.substr(pos + 1);
}

void xdmfAttribute(std::ostream& os, const std::string& h5, const std::string& group, const Field& f, long long n,
                   const char* center) {
  os << "      <Attribute Name=\"" << f.name << "\" AttributeType=\"" << (f.components == 1 ? "Scalar" : "Vector")
     << "\" Center=\"" << center << "\">\n"
     << "        <DataItem Dimensions=\"" << n << " " << f.components
     << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/" << group << "/" << f.name
     << "</DataItem>\n      </Attribute>\n";
}

}  // namespace

ResultWriter::ResultWriter(const Mesh::Discretization& disc, const RCP<const Comm>& comm) : disc_(disc), comm_(comm) {}

void ResultWriter::write(const std::string& dir, const std::string& base, const std::vector<double>& uGlobal,
                         const std::vector<Field>& nodeFields, const std::vector<Field>& cellFields,
                         const std::vector<PointSet>& pointSets) const {
  const MPI_Comm comm = rawComm(comm_);
  const Mesh::Mesh& mesh = disc_.mesh;
  const int npc = mesh.nodesPerCell();
  const auto& owned = disc_.ownedNodes();
  const auto cells = disc_.localCells();
  auto outIndex = [&](int n) { return disc_.nodeIndex()[n]; };

  const long long nOwned = static_cast<long long>(owned.size()), nCells = static_cast<long long>(cells.size());
  const auto nodeBlock = blockOffset(nOwned, comm), cellBlock = blockOffset(nCells, comm);
  std::vector<double> xyz, disp;
  for (int n : owned)
    for (int d = 0; d < 3; ++d) xyz.push_back(mesh.coords[n][d]), disp.push_back(uGlobal[3 * n + d]);
  std::vector<long long> topo;
  for (int c : cells)
    for (int k = 0; k < npc; ++k) topo.push_back(outIndex(mesh.cell(c)[k]));

  const std::string h5 = base + ".h5", h5path = dir + "/" + h5, tmp = h5path + ".tmp";
  {
    H5File file(tmp, comm);
    for (const char* g : {"/mesh", "/nodes", "/cells", "/points"}) H5Gclose(H5Gcreate2(file.id, g, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    file.writeRows("/mesh/geometry", xyz, nodeBlock.first, nOwned, nodeBlock.second, 3);
    file.writeRows("/mesh/topology", topo, cellBlock.first, nCells, cellBlock.second, npc);
    file.writeRows("/nodes/displacement", disp, nodeBlock.first, nOwned, nodeBlock.second, 3);
    for (const Field& f : nodeFields) {
      TRIBOS_REQUIRE(f.values.size() == static_cast<size_t>(nOwned * f.components), "node field " << f.name << " has wrong size");
      file.writeRows("/nodes/" + f.name, f.values, nodeBlock.first, nOwned, nodeBlock.second, f.components);
    }
    for (const Field& f : cellFields) {
      TRIBOS_REQUIRE(f.values.size() == static_cast<size_t>(nCells * f.components), "cell field " << f.name << " has wrong size");
      file.writeRows("/cells/" + f.name, f.values, cellBlock.first, nCells, cellBlock.second, f.components);
    }
    for (const PointSet& ps : pointSets) {
      const long long np = static_cast<long long>(ps.coords.size());
      const auto block = blockOffset(np, comm);
      H5Gclose(H5Gcreate2(file.id, ("/points/" + ps.name).c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
      std::vector<double> pxyz;
      for (const auto& p : ps.coords) pxyz.insert(pxyz.end(), p.begin(), p.end());
      file.writeRows("/points/" + ps.name + "/geometry", pxyz, block.first, np, block.second, 3);
      for (const Field& f : ps.fields)
        file.writeRows("/points/" + ps.name + "/" + f.name, f.values, block.first, np, block.second, f.components);
    }
    file.close();
  }
  // Point-set sizes are needed by rank 0 for the index.
  std::vector<long long> pointTotals;
  for (const PointSet& ps : pointSets) pointTotals.push_back(blockOffset(static_cast<long long>(ps.coords.size()), comm).second);
  MPI_Barrier(comm);
  if (comm_->getRank() != 0) return;
  TRIBOS_REQUIRE(std::rename(tmp.c_str(), h5path.c_str()) == 0, "cannot rename " << tmp << " to " << h5path);

  const long long N = nodeBlock.second, C = cellBlock.second;
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n"
    << "    <Grid Name=\"body\" GridType=\"Uniform\">\n"
    << "      <Topology TopologyType=\"" << (mesh.type == Mesh::CellType::Tet4 ? "Tetrahedron" : "Hexahedron")
    << "\" NumberOfElements=\"" << C << "\">\n        <DataItem Dimensions=\"" << C << " " << npc
    << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/mesh/topology</DataItem>\n      </Topology>\n"
    << "      <Geometry GeometryType=\"XYZ\">\n        <DataItem Dimensions=\"" << N
    << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/mesh/geometry</DataItem>\n      </Geometry>\n";
  xdmfAttribute(x, h5, "nodes", Field{"displacement", 3, {}}, N, "Node");
  for (const Field& f : nodeFields) xdmfAttribute(x, h5, "nodes", f, N, "Node");
  for (const Field& f : cellFields) xdmfAttribute(x, h5, "cells", f, C, "Cell");
  x << "    </Grid>\n";
  for (size_t k = 0; k < pointSets.size(); ++k) {
    const PointSet& ps = pointSets[k];
    const long long np = pointTotals[k];
    x << "    <Grid Name=\"" << ps.name << "\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << np << "\" NodesPerElement=\"1\"/>\n"
      << "      <Geometry GeometryType=\"XYZ\">\n        <DataItem Dimensions=\"" << np
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/points/" << ps.name
      << "/geometry</DataItem>\n      </Geometry>\n";
    for (const Field& f : ps.fields) xdmfAttribute(x, h5, "points/" + ps.name, f, np, "Node");
    x << "    </Grid>\n";
  }
  x << "  </Domain>\n</Xdmf>\n";
  writeFileAtomically(dir + "/" + base + ".xmf", x.str());
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream os(tmp);
    TRIBOS_REQUIRE(os.good(), "cannot write file " << tmp);
    os << text;
    os.close();
    TRIBOS_REQUIRE(os.good(), "cannot write file " << tmp);
  }
  TRIBOS_REQUIRE(std::rename(tmp.c_str(), path.c_str()) == 0, "cannot rename " << tmp << " to " << path);
}

}  // namespace IO
}  // namespace Tribos
