#include "Tribos_MeshBroadcast.hpp"

#include <Teuchos_CommHelpers.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Mesh {

namespace {

// The mesh as three flat arrays: integers (counts first, then the cells,
// facets, bodies and node sets), the coordinates, and the names, each
// ended by '\0'.
struct Packed {
  std::vector<int> ints;
  std::vector<double> coords;
  std::string names;
};

Packed pack(const Mesh& mesh) {
  Packed p;
  p.ints = {mesh.type == CellType::Tet4 ? 0 : 1, mesh.numNodes(), static_cast<int>(mesh.connectivity.size()),
            static_cast<int>(mesh.faces.size()), static_cast<int>(mesh.bodyNames.size()),
            static_cast<int>(mesh.cellBody.size()), static_cast<int>(mesh.nodeSets.size())};
  p.ints.insert(p.ints.end(), mesh.connectivity.begin(), mesh.connectivity.end());
  for (const auto& [name, facets] : mesh.faces) {
    p.names += name + '\0';
    p.ints.push_back(static_cast<int>(facets.size()));
    for (const Facet& f : facets) {
      p.ints.insert(p.ints.end(), f.nodes.begin(), f.nodes.end());
      p.ints.push_back(f.cell);
    }
  }
  for (const auto& name : mesh.bodyNames) p.names += name + '\0';
  p.ints.insert(p.ints.end(), mesh.cellBody.begin(), mesh.cellBody.end());
  for (const auto& [name, nodes] : mesh.nodeSets) {
    p.names += name + '\0';
    p.ints.push_back(static_cast<int>(nodes.size()));
    p.ints.insert(p.ints.end(), nodes.begin(), nodes.end());
  }
  for (const auto& x : mesh.coords) p.coords.insert(p.coords.end(), x.begin(), x.end());
  return p;
}

Mesh unpack(const Packed& p) {
  Mesh mesh;
  size_t i = 0, at = 0;
  auto next = [&] { return p.ints.at(i++); };
  auto name = [&] {
    const size_t end = p.names.find('\0', at);
    TRIBOS_REQUIRE(end != std::string::npos, "broadcastMesh: the names are cut short");
    std::string s = p.names.substr(at, end - at);
    at = end + 1;
    return s;
  };
  mesh.type = next() == 0 ? CellType::Tet4 : CellType::Hex8;
  const int numNodes = next(), connectivity = next(), faces = next(), bodies = next(), cellBody = next(), sets = next();
  const int npf = mesh.type == CellType::Tet4 ? 3 : 4;  // nodes per facet
  mesh.connectivity.assign(p.ints.begin() + i, p.ints.begin() + i + connectivity);
  i += connectivity;
  for (int k = 0; k < faces; ++k) {
    auto& face = mesh.faces[name()];
    face.resize(next());
    for (Facet& f : face) {
      f.nodes.assign(p.ints.begin() + i, p.ints.begin() + i + npf);
      i += npf;
      f.cell = next();
    }
  }
  for (int k = 0; k < bodies; ++k) mesh.bodyNames.push_back(name());
  mesh.cellBody.assign(p.ints.begin() + i, p.ints.begin() + i + cellBody);
  i += cellBody;
  for (int k = 0; k < sets; ++k) {
    auto& set = mesh.nodeSets[name()];
    const int n = next();
    set.assign(p.ints.begin() + i, p.ints.begin() + i + n);
    i += n;
  }
  mesh.coords.resize(numNodes);
  for (int n = 0; n < numNodes; ++n) mesh.coords[n] = {p.coords[3 * n], p.coords[3 * n + 1], p.coords[3 * n + 2]};
  return mesh;
}

}  // namespace

void broadcastMesh(Mesh& mesh, const Teuchos::Comm<int>& comm, int root) {
  if (comm.getSize() == 1) return;
  Packed p;
  if (comm.getRank() == root) p = pack(mesh);
  int sizes[3] = {static_cast<int>(p.ints.size()), static_cast<int>(p.coords.size()), static_cast<int>(p.names.size())};
  Teuchos::broadcast(comm, root, 3, sizes);
  p.ints.resize(sizes[0]);
  p.coords.resize(sizes[1]);
  p.names.resize(sizes[2]);
  if (sizes[0] > 0) Teuchos::broadcast(comm, root, sizes[0], p.ints.data());
  if (sizes[1] > 0) Teuchos::broadcast(comm, root, sizes[1], p.coords.data());
  if (sizes[2] > 0) Teuchos::broadcast(comm, root, sizes[2], &p.names[0]);
  if (comm.getRank() != root) mesh = unpack(p);
}

}  // namespace Mesh
}  // namespace Tribos
