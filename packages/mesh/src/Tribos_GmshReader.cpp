#include "Tribos_GmshReader.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <new>
#include <unordered_map>

#include "Tribos_Error.hpp"
#include "Tribos_GeoScript.hpp"
#include "detail/Tribos_GmshApi.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

namespace Gmsh = detail::Gmsh;

// Gmsh element types by the short names Tribos' messages use; others are
// named by Gmsh itself.
std::string elementTypeName(int type) {
  static const std::map<int, std::string> names = {
      {1, "Line2"},   {2, "Tri3"},     {3, "Quad4"},    {4, "Tet4"},      {5, "Hex8"},   {6, "Prism6"},
      {7, "Pyramid5"}, {8, "Line3"},   {9, "Tri6"},     {10, "Quad9"},    {11, "Tet10"}, {12, "Hex27"},
      {13, "Prism18"}, {14, "Pyramid14"}, {15, "Point"}, {16, "Quad8"},   {17, "Hex20"}, {18, "Prism15"},
      {19, "Pyramid13"}, {29, "Tet20"}};
  const auto it = names.find(type);
  if (it != names.end()) return it->second;
  try {
    return Gmsh::elementName(type);
  } catch (const Gmsh::GmshFailure&) {
    return "unknown";
  }
}

// The order of the 3D element types Tribos reads (Tet4, Hex8: 1; Tet10,
// Hex20: 2), 0 for the others.
int cellOrder(int type) {
  switch (type) {
    case 4: case 5: return 1;
    case 11: case 17: return 2;
    default: return 0;
  }
}

CellType cellTypeOfGmsh(int type) {
  switch (type) {
    case 4: return CellType::Tet4;
    case 5: return CellType::Hex8;
    case 11: return CellType::Tet10;
    default: return CellType::Hex20;
  }
}

// The boundary facets of each cell type: Tri3, Quad4, Tri6, Quad8.
int facetTypeOf(CellType type) {
  switch (type) {
    case CellType::Tet4: return 2;
    case CellType::Hex8: return 3;
    case CellType::Tet10: return 9;
    case CellType::Hex20: return 16;
  }
  return 0;
}

// Whether a 2D element type is a face of some cell type, and its corners.
bool isFacetType(int type) { return type == 2 || type == 3 || type == 9 || type == 16; }
int facetCorners(int type) { return type == 2 || type == 9 ? 3 : 4; }

// Why a 3D element type is refused, for the types a user may meet: the
// complete second-order hexahedron and the elements of order 3 or more.
std::string unsupportedReason(int type) {
  switch (type) {
    case 12:
      return " (Hex27 is not supported; mesh with -order 2 and Mesh.SecondOrderIncomplete=1 for Hex20)";
    case 29: case 30: case 31: case 92: case 93:
      return " (elements of order 3 or more are not supported; mesh with -order 1 or -order 2)";
    default:
      return "";
  }
}

// The message of a Gmsh call that failed, empty when it did not.
template <class F>
std::string gmshError(F&& call) {
  try {
    call();
  } catch (const Gmsh::GmshFailure& e) {
    return e.message;
  }
  return "";
}

// Gmsh is a process-wide library state: it is initialized for one read and
// finalized afterwards, unless someone else (the application) initialized it,
// so readers in sequence and an application that uses Gmsh itself both work.
// A Gmsh without gmshIsInitialized (4.8, Debian 12's) cannot say: then the
// reader assumes it is not (an application that keeps Gmsh open across a
// read must initialize it again afterwards).
class GmshSession {
 public:
  GmshSession() {
    owner_ = Gmsh::isInitialized() != 1;
    if (owner_) Gmsh::initialize();
    // No output of its own (a run prints on rank 0 only): errors reach the
    // reader as failed calls and are reported with the file name.
    Gmsh::setNumberOption("General.Terminal", 0);
    Gmsh::setNumberOption("General.Verbosity", 1);
  }
  ~GmshSession() {
    if (!owner_) return;
    try {
      Gmsh::finalize();
    } catch (const Gmsh::GmshFailure&) {
      // nothing to undo: the read's result (or error) stands
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  bool owner_ = true;
};

std::string physicalName(int dim, int tag) {
  const std::string name = Gmsh::physicalName(dim, tag);
  return name.empty() ? std::to_string(tag) : name;
}

// The bodies: each physical volume (by tag) with its volume entities, or one
// body of every volume when the file has none.
struct Body {
  std::string name, what;  // what: how messages call it
  std::vector<int> entities;
};

// The model's nodes, each tag once. Gmsh keeps a node whose tag the file
// defines twice and resolves the tag to one of them without a word: a tag
// given twice at other coordinates is refused naming both; the same node
// written twice is kept once.
void readNodes(const std::string& file, std::vector<std::size_t>& tags, std::vector<double>& xyz,
               std::unordered_map<std::size_t, int>& index) {
  std::vector<std::size_t> allTags;
  std::vector<double> allXyz;
  Gmsh::nodes(allTags, allXyz);
  index.reserve(allTags.size());
  for (size_t i = 0; i < allTags.size(); ++i) {
    const double* p = &allXyz[3 * i];
    const auto [it, fresh] = index.emplace(allTags[i], static_cast<int>(tags.size()));
    if (fresh) {
      tags.push_back(allTags[i]);
      xyz.insert(xyz.end(), p, p + 3);
      continue;
    }
    const double* q = &xyz[3 * it->second];
    TRIBOS_REQUIRE(p[0] == q[0] && p[1] == q[1] && p[2] == q[2],
                   file << ": node " << allTags[i] << " is defined twice, at (" << q[0] << ", " << q[1] << ", " << q[2]
                        << ") and at (" << p[0] << ", " << p[1] << ", " << p[2] << "); a node tag names one node");
  }
}

std::vector<Body> readBodies(const std::string& file) {
  std::vector<Body> bodies;
  Gmsh::DimTags groups = Gmsh::physicalGroups(3);
  std::sort(groups.begin(), groups.end());
  std::map<int, std::string> owner;  // volume entity -> the physical volume holding it
  for (const auto& g : groups) {
    Body body;
    body.name = physicalName(3, g.second);
    body.what = "physical volume '" + body.name + "'";
    for (const Body& b : bodies)
      TRIBOS_REQUIRE(b.name != body.name, file << ": two physical volumes are named '" << body.name
                                               << "'; each physical volume is a body and needs a name of its own");
    body.entities = Gmsh::entitiesForPhysicalGroup(3, g.second);
    // An element of two physical volumes would be a cell of two bodies.
    for (int e : body.entities) {
      const auto [it, fresh] = owner.emplace(e, body.what);
      TRIBOS_REQUIRE(fresh, file << ": the elements of volume " << e << " are in " << it->second << " and "
                                 << body.what << "; a cell belongs to one body");
    }
    bodies.push_back(std::move(body));
  }
  if (bodies.empty()) {
    const Gmsh::DimTags entities = Gmsh::entities(3);
    Body all;
    all.name = "body";
    for (const auto& e : entities) all.entities.push_back(e.second);
    bodies.push_back(std::move(all));
  }
  return bodies;
}

Mesh readGmshFile(const std::string& path, const std::string& file, std::vector<std::string>* warnings,
                  const MeshFileOptions& options) {
  detail::requireRegularFile(path, file, options.memoryLimit,
                             "the memory the read may use: Gmsh holds the whole file in memory");
  // A .msh file (ASCII or binary) starts with the line "$MeshFormat". Any
  // other file is refused here rather than handed to Gmsh, which would run
  // it as a .geo script (a program: .geo files are meshed in a child
  // process, GeoScriptMesh).
  {
    std::ifstream in(path, std::ios::binary);
    std::string first(12, '\0');
    in.read(&first[0], 12);
    first.resize(in.gcount());
    TRIBOS_REQUIRE(first == "$MeshFormat\n" || first == "$MeshFormat\r",
                   file << " is not a Gmsh mesh (a .msh file starts with $MeshFormat; a .geo script is meshed when "
                           "its name ends in .geo)");
  }

  GmshSession session;
  const std::string error = gmshError([&] { Gmsh::open(path); });
  TRIBOS_REQUIRE(error.empty(), file << " is not a mesh Gmsh can read: " << error);

  std::vector<std::size_t> nodeTags;
  std::vector<double> xyz;
  std::unordered_map<std::size_t, int> gmshIndex;  // node tag -> position in nodeTags
  readNodes(file, nodeTags, xyz, gmshIndex);
  TRIBOS_REQUIRE(!nodeTags.empty(), file << " holds no mesh (no nodes); a .msh file of version 4 or a .geo script is expected");

  const std::vector<Body> bodies = readBodies(file);
  const bool physical = !bodies.front().what.empty();
  Mesh mesh;
  std::vector<std::size_t> cellTags, cellNodes;  // Gmsh tags
  std::vector<CellType> cellTypes;
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    const size_t before = cellTags.size();
    int cellGmshType = 0;  // a body holds cells of one type
    std::string firstVolume;
    for (int entity : bodies[b].entities) {
      const std::string what = physical ? bodies[b].what : "volume " + std::to_string(entity);
      const std::vector<int> types = Gmsh::elementTypes(3, entity);
      for (int type : types) {
        std::vector<std::size_t> tags, nodes;
        Gmsh::elementsByType(type, entity, tags, nodes);
        const std::string element =
            "element " + (tags.empty() ? std::string("?") : std::to_string(tags.front())) + " (" + elementTypeName(type) + ")";
        TRIBOS_REQUIRE(cellOrder(type) != 0, file << ": " << element << " in " << what << " is not supported"
                                                  << unsupportedReason(type)
                                                  << "; Tribos reads Tet4 and Hex8 (first order), Tet10 and Hex20 "
                                                     "(second order)");
        TRIBOS_REQUIRE(cellGmshType == 0 || cellGmshType == type,
                       file << ": " << (physical ? bodies[b].what : std::string("the mesh (one body: it names no "
                                                                                  "physical volumes)"))
                            << " mixes " << elementTypeName(cellGmshType) << " (" << firstVolume << ") and "
                            << elementTypeName(type) << " (volume " << entity << ", " << element << "); "
                            << (cellOrder(cellGmshType) != cellOrder(type)
                                    ? "a body of first- and second-order cells is not supported: its faces would "
                                      "not match; mesh the body with one -order (bodies of different orders meet "
                                      "in contact)"
                                    : "a body holds cells of one type: Tet4, Hex8, Tet10 or Hex20"));
        if (cellGmshType == 0) cellGmshType = type, firstVolume = "volume " + std::to_string(entity);
        cellTags.insert(cellTags.end(), tags.begin(), tags.end());
        cellNodes.insert(cellNodes.end(), nodes.begin(), nodes.end());
        cellTypes.insert(cellTypes.end(), tags.size(), cellTypeOfGmsh(type));
      }
    }
    mesh.cellBody.insert(mesh.cellBody.end(), cellTags.size() - before, b);
    if (physical) mesh.bodyNames.push_back(bodies[b].name);
  }
  TRIBOS_REQUIRE(!cellTags.empty(), file << " has no 3D elements" << (physical ? " in its physical volumes" : "")
                                          << "; Tribos meshes bodies with Tet4, Hex8, Tet10 or Hex20 cells");
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b)
    TRIBOS_REQUIRE(std::count(mesh.cellBody.begin(), mesh.cellBody.end(), b) > 0,
                   file << ": " << bodies[b].what << " has no 3D elements; each physical volume is a body");
  if (!physical) mesh.cellBody.clear();  // one body, as a box mesh

  // Nodes no cell uses (geometry points, nodes of surfaces only) are dropped;
  // the rest keep Gmsh's order. Gmsh's node orders are Tribos' (positive
  // volume; Hex8 bottom 0-3 then top 4-7; Tet10 and Hex20 the corners, then
  // the mid-edge nodes, docs/quadratic_elements.md), checked below.
  // Nodes shared by cells of two bodies stay shared: the bodies are bonded there.
  std::vector<char> usedByCells(nodeTags.size(), 0);
  for (std::size_t tag : cellNodes) {
    const auto it = gmshIndex.find(tag);
    TRIBOS_REQUIRE(it != gmshIndex.end(), file << ": an element names node " << tag << ", which the file does not define");
    usedByCells[it->second] = 1;
  }
  const std::vector<int> newIndex =
      detail::numberUsedNodes(usedByCells, std::vector<long long>(nodeTags.begin(), nodeTags.end()), file, warnings);
  std::vector<long long> usedTags;
  for (size_t i = 0; i < nodeTags.size(); ++i)
    if (newIndex[i] >= 0) {
      mesh.coords.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
      usedTags.push_back(static_cast<long long>(nodeTags[i]));
    }
  detail::requireUsableCoordinates(mesh.coords, usedTags, file);
  mesh.connectivity.reserve(cellNodes.size());
  for (std::size_t tag : cellNodes) mesh.connectivity.push_back(newIndex[gmshIndex.at(tag)]);
  mesh.setCellTypes(cellTypes);
  mesh.checkBodies(file, usedTags);  // bodies of different types share no node
  const std::vector<long long> cellIds(cellTags.begin(), cellTags.end());
  detail::checkMidEdgeNodes(mesh, file, cellIds, warnings);
  detail::requirePositiveCells(mesh, file, cellIds);

  // Named faces: the physical surfaces, each facet the face of its boundary cell.
  const detail::FaceIndex index(mesh);
  const Gmsh::DimTags surfaces = Gmsh::physicalGroups(2);
  for (const auto& g : surfaces) {
    const std::string name = physicalName(2, g.second);
    std::vector<Facet>& face = mesh.faces[name];
    for (int e : Gmsh::entitiesForPhysicalGroup(2, g.second)) {
      for (int type : Gmsh::elementTypes(2, e)) {
        TRIBOS_REQUIRE(isFacetType(type), file << ": element type " << type << " (" << elementTypeName(type)
                                               << ") in physical surface '" << name
                                               << "' is not supported; the faces of Tribos' cells are 3- and 6-node "
                                                  "triangles, 4- and 8-node quadrangles");
        std::vector<std::size_t> tags, nodes;
        Gmsh::elementsByType(type, e, tags, nodes);
        const size_t npf = static_cast<size_t>(nodes.size() / std::max<size_t>(tags.size(), 1));
        const size_t corners = static_cast<size_t>(facetCorners(type));
        for (size_t k = 0; k < tags.size(); ++k) {
          std::vector<int> facetNodes;
          for (size_t a = 0; a < npf; ++a) {
            const auto it = gmshIndex.find(nodes[k * npf + a]);
            facetNodes.push_back(it == gmshIndex.end() ? -1 : newIndex[it->second]);
          }
          const std::vector<int> facetCorners(facetNodes.begin(), facetNodes.begin() + corners);
          const auto* hit =
              std::count(facetNodes.begin(), facetNodes.end(), -1) ? nullptr : index.boundaryFace(facetCorners);
          TRIBOS_REQUIRE(hit, file << ": surface '" << name << "' is not on the boundary (facet " << tags[k] << ")");
          const CellType cellType = mesh.cellType(hit->cell);
          TRIBOS_REQUIRE(type == facetTypeOf(cellType),
                         file << ": facet " << tags[k] << " (" << elementTypeName(type) << ") of surface '" << name
                              << "' lies on a " << cellTypeName(cellType) << " cell, whose faces are "
                              << elementTypeName(facetTypeOf(cellType)));
          // A second-order facet's mid-edge nodes are its cell face's.
          const Facet facet = detail::outwardFacet(mesh, hit->cell, hit->local);
          std::vector<int> fileMid(facetNodes.begin() + corners, facetNodes.end());
          std::vector<int> cellMid(facet.nodes.begin() + corners, facet.nodes.end());
          std::sort(fileMid.begin(), fileMid.end());
          std::sort(cellMid.begin(), cellMid.end());
          TRIBOS_REQUIRE(fileMid == cellMid, file << ": facet " << tags[k] << " of surface '" << name
                                                  << "' has mid-edge nodes other than those of the face of its "
                                                     "element (a surface meshed apart from its volume?)");
          face.push_back(facet);
        }
      }
    }
  }
  mesh.checkBodies();
  return mesh;
}

}  // namespace

Mesh readGmsh(const std::string& path, std::vector<std::string>* warnings, const MeshFileOptions& options) {
  const std::string file = "mesh file \"" + path + "\"";
  // A Gmsh call that fails outside gmshError() (on a model Gmsh has read):
  // said as a Tribos::Error naming the file.
  try {
    if (!isGeoScript(path)) return readGmshFile(path, file, warnings, options);
    // A .geo is a program: run only when allowed, in a child process with
    // limits; its mesh is read as any .msh, messages naming the script.
    requireGeoScriptAllowed(path, options);
    detail::requireRegularFile(path, file, options.memoryLimit, "the memory the read may use");
    const GeoScriptMesh meshed(path, file, options);
    return readGmshFile(meshed.mshPath(), file, warnings, options);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const detail::Gmsh::GmshFailure& e) {
    throw Error(file + ": Gmsh: " + e.message);
  } catch (const std::exception& e) {
    throw Error(file + ": " + e.what());
  }
}

BoxSpec boundingBox(const Mesh& mesh) {
  BoxSpec spec;
  spec.type = mesh.type;
  spec.cells = {1, 1, 1};
  if (mesh.coords.empty()) return spec;
  std::array<double, 3> lo = mesh.coords[0], hi = mesh.coords[0];
  for (const auto& p : mesh.coords)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  spec.x = {lo[0], hi[0]};
  spec.y = {lo[1], hi[1]};
  spec.z = {lo[2], hi[2]};
  return spec;
}

}  // namespace Mesh
}  // namespace Tribos
