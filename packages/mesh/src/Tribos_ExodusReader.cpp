#include "Tribos_ExodusReader.hpp"

#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

// The Exodus II library's last error, for messages.
std::string exodusError() {
  const char *msg = nullptr, *func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  return msg && *msg ? msg : "unknown error";
}

// One open file, closed however the read ends; every call that fails is a
// Tribos::Error naming the file and what was being read.
class ExodusFile {
 public:
  ExodusFile(const std::string& path, const std::string& file) : file_(file) {
    int cpuWordSize = sizeof(double), ioWordSize = 0;
    float version = 0;
    id_ = ex_open(path.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
    TRIBOS_REQUIRE(id_ >= 0, file << " is not an Exodus II file the Exodus library can read (" << exodusError() << ")");
    // Names longer than the default 32 characters are read whole.
    const int64_t used = ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH);
    if (used > 0) ex_set_max_name_length(id_, static_cast<int>(used));
    nameLength_ = std::max<int64_t>(used, MAX_NAME_LENGTH);
  }
  ~ExodusFile() { ex_close(id_); }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;

  int id() const { return id_; }
  void check(int status, const std::string& what) const {
    TRIBOS_REQUIRE(status >= 0, file_ << ": cannot read " << what << " (Exodus II: " << exodusError() << ")");
  }
  // The entity's name, or `prefix` + its id when it has none.
  std::string name(ex_entity_type type, int id, const std::string& prefix) const {
    std::string name(nameLength_ + 1, '\0');
    check(ex_get_name(id_, type, id, &name[0]), "the name of " + prefix + std::to_string(id));
    name.resize(name.find('\0'));
    while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
    return name.empty() ? prefix + std::to_string(id) : name;
  }
  std::vector<int> ids(ex_entity_type type, int64_t count, const std::string& what) const {
    std::vector<int> ids(count);
    if (count > 0) check(ex_get_ids(id_, type, ids.data()), "the ids of its " + what);
    return ids;
  }
  // The entries of a set: the elements of a side set (their side numbers
  // in *sides) or the nodes of a node set (sides null); file numbers.
  std::vector<int> set(ex_entity_type type, int id, const std::string& what, std::vector<int>* sides = nullptr) const {
    int count = 0, factors = 0;
    check(ex_get_set_param(id_, type, id, &count, &factors), what);
    std::vector<int> entries(count);
    if (sides) sides->assign(count, 0);
    if (count > 0) check(ex_get_set(id_, type, id, entries.data(), sides ? sides->data() : nullptr), what);
    return entries;
  }

 private:
  std::string file_;
  int id_ = -1;
  int64_t nameLength_ = MAX_NAME_LENGTH;
};

// Sides of the Exodus II reference cells (1-based local nodes, side 1 first).
const std::vector<std::vector<int>>& exodusSides(CellType type) {
  static const std::vector<std::vector<int>> tet = {{1, 2, 4}, {2, 3, 4}, {1, 4, 3}, {1, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7},
                                                    {1, 5, 8, 4}, {1, 4, 3, 2}, {5, 6, 7, 8}};
  return detail::isTetrahedron(type) ? tet : hex;  // second-order sides: their corners
}

// Exodus II's node of each of Tribos' (Gmsh's) nodes of a cell, 0-based:
// the corners agree; TETRA10 numbers its mid-edge nodes 0-1, 1-2, 2-0, 0-3,
// 1-3, 2-3 (Gmsh: ..., 3-0, 3-2, 3-1), HEX20 the bottom edges 0-1, 1-2, 2-3,
// 3-0, the vertical ones 0-4, 1-5, 2-6, 3-7, the top ones 4-5, 5-6, 6-7, 7-4
// (Gmsh: 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7).
const std::vector<int>& exodusNodeOf(CellType type) {
  static const std::vector<int> tet4 = {0, 1, 2, 3}, hex8 = {0, 1, 2, 3, 4, 5, 6, 7};
  static const std::vector<int> tet10 = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  static const std::vector<int> hex20 = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 9, 13, 10, 14, 15, 16, 19, 17, 18};
  switch (type) {
    case CellType::Tet4: return tet4;
    case CellType::Hex8: return hex8;
    case CellType::Tet10: return tet10;
    case CellType::Hex20: return hex20;
  }
  return hex8;
}

// The cell type of an Exodus element type ("TETRA", "TET4", "HEX8", ...,
// any case) with this many nodes; false when Tribos has no such cell.
bool cellTypeOf(std::string name, int64_t nodes, CellType& type) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return std::toupper(ch); });
  if (name.rfind("TET", 0) == 0 && nodes == 4) return type = CellType::Tet4, true;
  if (name.rfind("HEX", 0) == 0 && nodes == 8) return type = CellType::Hex8, true;
  if (name.rfind("TET", 0) == 0 && nodes == 10) return type = CellType::Tet10, true;
  if (name.rfind("HEX", 0) == 0 && nodes == 20) return type = CellType::Hex20, true;
  return false;
}

// Why an element type is refused, for those a user may meet.
std::string unsupportedReason(std::string name, int64_t nodes) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return std::toupper(ch); });
  if (name.rfind("HEX", 0) == 0 && nodes == 27) return " (HEX27 is not supported; HEX20 is)";
  if ((name.rfind("TET", 0) == 0 && nodes > 10) || (name.rfind("HEX", 0) == 0 && nodes > 27))
    return " (elements of order 3 or more are not supported)";
  return "";
}

// The names of a kind of entity, refused when two agree (a name is how an
// input file refers to a body, a face or a node set).
std::vector<std::string> uniqueNames(const ExodusFile& exo, ex_entity_type type, const std::vector<int>& ids,
                                     const std::string& prefix, const std::string& what, const std::string& file) {
  std::vector<std::string> names;
  for (size_t k = 0; k < ids.size(); ++k) {
    names.push_back(exo.name(type, ids[k], prefix));
    for (size_t j = 0; j < k; ++j)
      TRIBOS_REQUIRE(names[j] != names[k], file << ": two " << what << "s are named '" << names[k] << "' (ids " << ids[j]
                                               << " and " << ids[k] << "); a name must be unique");
  }
  return names;
}

Mesh readExodusFile(const std::string& path, const std::string& file, std::vector<std::string>* warnings,
                    const MeshFileOptions& options) {
  detail::requireRegularFile(path, file);
  const ExodusFile exo(path, file);
  ex_init_params init{};
  exo.check(ex_get_init_ext(exo.id(), &init), "its header");
  TRIBOS_REQUIRE(init.num_dim == 3, file << " is a " << init.num_dim << "D mesh; Tribos reads 3D meshes");
  TRIBOS_REQUIRE(init.num_elem > 0 && init.num_nodes > 0, file << " has no elements; Tribos meshes bodies with Tet4, Hex8, Tet10 or Hex20 cells");
  // The header's counts before the arrays they size are allocated: a
  // netCDF-4 file may declare arrays it does not store (read as fill
  // values). Node and element numbers are ints; the reader holds about 64
  // bytes per node and 128 per element (Hex8) at once.
  TRIBOS_REQUIRE(init.num_nodes < 2147483647 && init.num_elem < 2147483647,
                 file << " declares " << init.num_nodes << " nodes and " << init.num_elem
                      << " elements; a mesh has at most 2^31 - 1 of each");
  const double arrays = 64.0 * double(init.num_nodes) + 128.0 * double(init.num_elem);
  TRIBOS_REQUIRE(options.memoryLimit <= 0 || arrays <= options.memoryLimit,
                 file << " declares " << init.num_nodes << " nodes and " << init.num_elem << " elements, whose arrays "
                      << "need about " << detail::describeBytes(arrays) << ", more than the "
                      << detail::describeBytes(options.memoryLimit) << " the read may use (--max-memory, or the "
                      << "memory available on the machine)");

  std::vector<double> x(init.num_nodes), y(init.num_nodes), z(init.num_nodes);
  exo.check(ex_get_coord(exo.id(), x.data(), y.data(), z.data()), "the node coordinates");
  std::vector<int> nodeMap(init.num_nodes), elemMap(init.num_elem);  // the file's ids
  exo.check(ex_get_id_map(exo.id(), EX_NODE_MAP, nodeMap.data()), "the node number map");
  exo.check(ex_get_id_map(exo.id(), EX_ELEM_MAP, elemMap.data()), "the element number map");

  // Element blocks: the bodies, in file order (the order of the elements'
  // internal numbers, which side sets use).
  Mesh mesh;
  const std::vector<int> blockIds = exo.ids(EX_ELEM_BLOCK, init.num_elem_blk, "element blocks");
  const std::vector<std::string> blockNames = uniqueNames(exo, EX_ELEM_BLOCK, blockIds, "block_", "element block", file);
  std::vector<int> fileNodes;                     // 1-based file node of each cell corner
  std::vector<int> elementOf;                     // cell -> 0-based internal element number
  std::vector<int> cellOf(init.num_elem, -1);     // internal element -> cell
  std::vector<CellType> cellTypes;                // per cell: each block is a body of one type
  int element = 0;
  for (size_t k = 0; k < blockIds.size(); ++k) {
    char typeName[MAX_STR_LENGTH + 1] = "";
    int count = 0, nodes = 0, edges = 0, faces = 0, attributes = 0;
    exo.check(ex_get_block(exo.id(), EX_ELEM_BLOCK, blockIds[k], typeName, &count, &nodes, &edges, &faces, &attributes),
              "element block " + std::to_string(blockIds[k]));
    const std::string what = "block '" + blockNames[k] + "'";
    if (count == 0) {
      detail::warn(warnings, file + ": " + what + " has no elements and is ignored");
      continue;
    }
    CellType type;
    TRIBOS_REQUIRE(cellTypeOf(typeName, nodes, type),
                   file << ": element type " << typeName << " of " << nodes << " nodes in " << what << " is not supported"
                        << unsupportedReason(typeName, nodes)
                        << "; Tribos reads Tet4 and Hex8 (first order), Tet10 and Hex20 (second order)");
    std::vector<int> connectivity(static_cast<size_t>(count) * nodes);
    exo.check(ex_get_conn(exo.id(), EX_ELEM_BLOCK, blockIds[k], connectivity.data(), nullptr, nullptr),
              "the connectivity of " + what);
    for (int n : connectivity)
      TRIBOS_REQUIRE(n >= 1 && n <= init.num_nodes, file << ": an element of " << what << " names node " << n
                                                          << "; the file's nodes are 1 to " << init.num_nodes);
    const std::vector<int>& exodusNode = exodusNodeOf(type);
    for (int e = 0; e < count; ++e)
      for (int a = 0; a < nodes; ++a) fileNodes.push_back(connectivity[static_cast<size_t>(e) * nodes + exodusNode[a]]);
    for (int e = 0; e < count; ++e, ++element) {
      cellOf[element] = static_cast<int>(elementOf.size());
      elementOf.push_back(element);
      cellTypes.push_back(type);
      mesh.cellBody.push_back(static_cast<int>(mesh.bodyNames.size()));
    }
    mesh.bodyNames.push_back(blockNames[k]);
  }
  TRIBOS_REQUIRE(!elementOf.empty(), file << " has no elements in its element blocks; Tribos meshes bodies with Tet4, Hex8, Tet10 or Hex20 cells");

  // Nodes no cell uses are dropped; the others keep the file's order.
  std::vector<char> usedByCells(init.num_nodes, 0);
  for (int n : fileNodes) usedByCells[n - 1] = 1;
  const std::vector<int> newIndex =
      detail::numberUsedNodes(usedByCells, std::vector<long long>(nodeMap.begin(), nodeMap.end()), file, warnings);
  std::vector<long long> usedIds;
  for (int64_t i = 0; i < init.num_nodes; ++i)
    if (newIndex[i] >= 0) {
      mesh.coords.push_back({x[i], y[i], z[i]});
      usedIds.push_back(nodeMap[i]);
    }
  detail::requireUsableCoordinates(mesh.coords, usedIds, file);
  mesh.connectivity.reserve(fileNodes.size());
  for (int n : fileNodes) mesh.connectivity.push_back(newIndex[n - 1]);
  mesh.setCellTypes(cellTypes);
  mesh.checkBodies(file, usedIds);  // blocks of different types share no node
  std::vector<long long> cellIds;
  for (int e : elementOf) cellIds.push_back(elemMap[e]);
  detail::checkMidEdgeNodes(mesh, file, cellIds, warnings, "block");
  detail::requirePositiveCells(mesh, file, cellIds, "block");

  // Side sets: faces, each side the outward face of its cell.
  const detail::FaceIndex index(mesh);
  const std::vector<int> sideSetIds = exo.ids(EX_SIDE_SET, init.num_side_sets, "side sets");
  const std::vector<std::string> sideSetNames = uniqueNames(exo, EX_SIDE_SET, sideSetIds, "sideset_", "side set", file);
  for (size_t k = 0; k < sideSetIds.size(); ++k) {
    const std::string what = "side set '" + sideSetNames[k] + "'";
    std::vector<int> sideNumbers;
    const std::vector<int> elements = exo.set(EX_SIDE_SET, sideSetIds[k], what, &sideNumbers);
    std::vector<Facet>& face = mesh.faces[sideSetNames[k]];
    for (size_t s = 0; s < elements.size(); ++s) {
      const int e = elements[s] - 1, side = sideNumbers[s];
      TRIBOS_REQUIRE(e >= 0 && e < init.num_elem && cellOf[e] >= 0,
                     file << ": " << what << " names element " << elements[s] << ", which is in no element block");
      const int c = cellOf[e];
      const auto& sides = exodusSides(mesh.cellType(c));
      TRIBOS_REQUIRE(side >= 1 && side <= static_cast<int>(sides.size()),
                     file << ": " << what << " names side " << side << " of element " << elemMap[e] << "; a "
                          << cellTypeName(mesh.cellType(c)) << " has sides 1 to " << sides.size());
      std::vector<int> nodes;
      for (int ln : sides[side - 1]) nodes.push_back(mesh.cell(c)[ln - 1]);
      const auto* hit = index.boundaryFace(nodes);
      TRIBOS_REQUIRE(hit && hit->cell == c, file << ": " << what << " is not on the boundary (element " << elemMap[e]
                                                 << " side " << side << ")");
      face.push_back(detail::outwardFacet(mesh, c, hit->local));
    }
  }

  // Node sets.
  const std::vector<int> nodeSetIds = exo.ids(EX_NODE_SET, init.num_node_sets, "node sets");
  const std::vector<std::string> nodeSetNames = uniqueNames(exo, EX_NODE_SET, nodeSetIds, "nodeset_", "node set", file);
  for (size_t k = 0; k < nodeSetIds.size(); ++k) {
    const std::string what = "node set '" + nodeSetNames[k] + "'";
    const std::vector<int> nodes = exo.set(EX_NODE_SET, nodeSetIds[k], what);
    std::vector<int>& set = mesh.nodeSets[nodeSetNames[k]];
    for (int n : nodes) {
      TRIBOS_REQUIRE(n >= 1 && n <= init.num_nodes, file << ": " << what << " names node " << n
                                                          << "; the file's nodes are 1 to " << init.num_nodes);
      TRIBOS_REQUIRE(newIndex[n - 1] >= 0, file << ": " << what << " holds node " << nodeMap[n - 1]
                                                << ", which belongs to no element");
      set.push_back(newIndex[n - 1]);
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return mesh;
}

}  // namespace

Mesh readExodus(const std::string& path, std::vector<std::string>* warnings, const MeshFileOptions& options) {
  return readExodusFile(path, "mesh file \"" + path + "\"", warnings, options);
}

}  // namespace Mesh
}  // namespace Tribos
