#include "Tribos_MeshBroadcast.hpp"

#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

void packNamedLists(const std::map<std::string, std::vector<int>>& lists, ByteBuffer& b) {
  b.put(static_cast<long long>(lists.size()));
  for (const auto& [name, nodes] : lists) b.put(name), b.put(nodes);
}

std::map<std::string, std::vector<int>> unpackNamedLists(ByteBuffer& b) {
  std::map<std::string, std::vector<int>> lists;
  const long long n = b.get<long long>();
  for (long long k = 0; k < n; ++k) {
    const std::string name = b.getString();
    lists[name] = b.getVector<int>();
  }
  return lists;
}

}  // namespace

void packMesh(const Mesh& mesh, ByteBuffer& b) {
  b.put(static_cast<int>(mesh.type));
  std::vector<int> types;  // per cell of a mixed mesh
  for (int c = 0; mesh.mixed() && c < mesh.numCells(); ++c) types.push_back(static_cast<int>(mesh.cellType(c)));
  b.put(types);
  b.put(mesh.coords);
  b.put(mesh.connectivity);
  b.put(static_cast<long long>(mesh.faces.size()));
  for (const auto& [name, facets] : mesh.faces) {
    b.put(name);
    std::vector<int> flat;  // per facet: its node count, its nodes, then its cell
    for (const Facet& f : facets) {
      flat.push_back(static_cast<int>(f.nodes.size()));
      flat.insert(flat.end(), f.nodes.begin(), f.nodes.end());
      flat.push_back(f.cell);
    }
    b.put(flat);
  }
  b.put(static_cast<long long>(mesh.bodyNames.size()));
  for (const auto& name : mesh.bodyNames) b.put(name);
  b.put(mesh.cellBody);
  packNamedLists(mesh.nodeSets, b);
  packNamedLists(mesh.partFaceNodes, b);
}

Mesh unpackMesh(ByteBuffer& b) {
  Mesh mesh;
  mesh.type = static_cast<CellType>(b.get<int>());
  const std::vector<int> types = b.getVector<int>();
  mesh.coords = b.getVector<std::array<double, 3>>();
  mesh.connectivity = b.getVector<int>();
  if (!types.empty()) {
    std::vector<CellType> cellTypes;
    for (int t : types) cellTypes.push_back(static_cast<CellType>(t));
    mesh.setCellTypes(cellTypes);
  }
  const long long faces = b.get<long long>();
  for (long long k = 0; k < faces; ++k) {
    auto& face = mesh.faces[b.getString()];
    const std::vector<int> flat = b.getVector<int>();
    for (size_t at = 0; at < flat.size();) {
      const size_t n = static_cast<size_t>(flat[at]);
      TRIBOS_REQUIRE(n >= 3 && n <= 8 && at + n + 2 <= flat.size(), "unpackMesh: the facets are cut short");
      face.push_back({std::vector<int>(flat.begin() + at + 1, flat.begin() + at + 1 + n), flat[at + 1 + n]});
      at += n + 2;
    }
  }
  const long long bodies = b.get<long long>();
  for (long long k = 0; k < bodies; ++k) mesh.bodyNames.push_back(b.getString());
  mesh.cellBody = b.getVector<int>();
  mesh.nodeSets = unpackNamedLists(b);
  mesh.partFaceNodes = unpackNamedLists(b);
  return mesh;
}

void broadcastMesh(Mesh& mesh, const Teuchos::Comm<int>& comm, int root) {
  if (comm.getSize() == 1) return;
  ByteBuffer buffer;
  if (comm.getRank() == root) packMesh(mesh, buffer);
  broadcastBuffer(buffer, root, comm);
  if (comm.getRank() != root) mesh = unpackMesh(buffer);
}

}  // namespace Mesh
}  // namespace Tribos
