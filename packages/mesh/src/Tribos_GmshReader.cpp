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
  int cellGmshType = 0;
  std::string firstVolume;
  std::vector<std::size_t> cellTags, cellNodes;  // Gmsh tags
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    const size_t before = cellTags.size();
    for (int entity : bodies[b].entities) {
      const std::string what = physical ? bodies[b].what : "volume " + std::to_string(entity);
      const std::vector<int> types = Gmsh::elementTypes(3, entity);
      for (int type : types) {
        TRIBOS_REQUIRE(type == 4 || type == 5, file << ": element type " << type << " (" << elementTypeName(type) << ") in "
                                                    << what << " is not supported; Tribos reads Tet4 and Hex8");
        TRIBOS_REQUIRE(cellGmshType == 0 || cellGmshType == type,
                       file << " mixes " << elementTypeName(cellGmshType) << " (" << firstVolume << ") and "
                            << elementTypeName(type) << " (" << what << "); a body has one cell type, Tet4 or Hex8");
        if (cellGmshType == 0) cellGmshType = type, firstVolume = what;
        std::vector<std::size_t> tags, nodes;
        Gmsh::elementsByType(type, entity, tags, nodes);
        cellTags.insert(cellTags.end(), tags.begin(), tags.end());
        cellNodes.insert(cellNodes.end(), nodes.begin(), nodes.end());
      }
    }
    mesh.cellBody.insert(mesh.cellBody.end(), cellTags.size() - before, b);
    if (physical) mesh.bodyNames.push_back(bodies[b].name);
  }
  TRIBOS_REQUIRE(!cellTags.empty(), file << " has no 3D elements" << (physical ? " in its physical volumes" : "")
                                          << "; Tribos meshes bodies with Tet4 or Hex8 cells");
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b)
    TRIBOS_REQUIRE(std::count(mesh.cellBody.begin(), mesh.cellBody.end(), b) > 0,
                   file << ": " << bodies[b].what << " has no 3D elements; each physical volume is a body");
  if (!physical) mesh.cellBody.clear();  // one body, as a box mesh
  mesh.type = cellGmshType == 4 ? CellType::Tet4 : CellType::Hex8;

  // Nodes no cell uses (geometry points, nodes of surfaces only) are dropped;
  // the rest keep Gmsh's order. Gmsh's Tet4 and Hex8 node orders are
  // Tribos' (positive volume; Hex8 bottom 0-3 then top 4-7), checked below.
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
  detail::requirePositiveCells(mesh, file, std::vector<long long>(cellTags.begin(), cellTags.end()));

  // Named faces: the physical surfaces, each facet the face of its boundary cell.
  const detail::FaceIndex index(mesh);
  const int facetType = mesh.type == CellType::Tet4 ? 2 : 3;
  const Gmsh::DimTags surfaces = Gmsh::physicalGroups(2);
  for (const auto& g : surfaces) {
    const std::string name = physicalName(2, g.second);
    std::vector<Facet>& face = mesh.faces[name];
    for (int e : Gmsh::entitiesForPhysicalGroup(2, g.second)) {
      for (int type : Gmsh::elementTypes(2, e)) {
        TRIBOS_REQUIRE(type == facetType, file << ": element type " << type << " (" << elementTypeName(type)
                                               << ") in physical surface '" << name << "' is not supported with "
                                               << cellTypeName(mesh.type) << " cells; their faces are "
                                               << elementTypeName(facetType));
        std::vector<std::size_t> tags, nodes;
        Gmsh::elementsByType(type, e, tags, nodes);
        const size_t npf = type == 2 ? 3 : 4;
        for (size_t k = 0; k < tags.size(); ++k) {
          std::vector<int> facetNodes;
          for (size_t a = 0; a < npf; ++a) {
            const auto it = gmshIndex.find(nodes[k * npf + a]);
            facetNodes.push_back(it == gmshIndex.end() ? -1 : newIndex[it->second]);
          }
          const auto* hit = std::count(facetNodes.begin(), facetNodes.end(), -1) ? nullptr : index.boundaryFace(facetNodes);
          TRIBOS_REQUIRE(hit, file << ": surface '" << name << "' is not on the boundary (facet " << tags[k] << ")");
          face.push_back(detail::outwardFacet(mesh, hit->cell, hit->local));
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
