#include "Tribos_GmshReader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <new>
#include <sstream>
#include <unordered_map>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Mesh {

namespace {

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
  std::string name;
  int dim = 0, order = 0, numNodes = 0, primary = 0;
  std::vector<double> local;
  try {
    gmsh::model::mesh::getElementProperties(type, name, dim, order, numNodes, local, primary);
  } catch (...) {
    name = "unknown";
  }
  return name;
}

// Gmsh reports errors by throwing: std::string in the 4.8 API, an exception
// object in later ones.
template <class F>
std::string gmshError(F&& call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  } catch (const std::string& e) {
    return e.empty() ? "unknown error" : e;
  } catch (const char* e) {
    return e ? e : "unknown error";
  } catch (...) {
    return "unknown error";
  }
  return "";
}

// Gmsh is a process-wide library state: it is initialized for one read and
// finalized afterwards, unless someone else (the application) initialized it,
// so readers in sequence and an application that uses Gmsh itself both work.
// A Gmsh without gmsh::isInitialized (4.8, Debian 12's) cannot say: then the
// reader assumes it is not (an application that keeps Gmsh open across a
// read must initialize it again afterwards).
class GmshSession {
 public:
  GmshSession() {
#ifdef TRIBOS_GMSH_HAS_IS_INITIALIZED
    owner_ = !gmsh::isInitialized();
#endif
    if (owner_) gmsh::initialize(0, nullptr, false);  // no argv parsing, no config files
    // No output of its own (a run prints on rank 0 only): errors reach the
    // reader as exceptions and are reported with the file name.
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  ~GmshSession() {
    if (owner_) gmsh::finalize();
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  bool owner_ = true;
};

using Point = std::array<double, 3>;

double triple(const Point& o, const Point& a, const Point& b, const Point& c) {
  const double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
  const double v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
  const double w[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Whether a cell has positive volume everywhere: the tetrahedron's volume,
// the hexahedron's Jacobian at each of its corners (the trilinear map is
// one-to-one when all eight are positive), relative to the cell's size so
// that round-off flat cells count as degenerate.
bool positiveCell(const Mesh& mesh, int c) {
  const int* n = mesh.cell(c);
  const auto& x = mesh.coords;
  double h = 0;
  for (int a = 0; a < mesh.nodesPerCell(); ++a)
    for (int d = 0; d < 3; ++d) h = std::max(h, std::abs(x[n[a]][d] - x[n[0]][d]));
  const double floor = 1e-12 * h * h * h;
  if (mesh.type == CellType::Tet4) return triple(x[n[0]], x[n[1]], x[n[2]], x[n[3]]) > floor;
  // Corner k and its three neighbours in right-handed order (Tribos' Hex8
  // order: the bottom quadrilateral 0-3 counter-clockwise seen from above, the top 4-7).
  static const int corner[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                   {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  for (int k = 0; k < 8; ++k)
    if (triple(x[n[k]], x[n[corner[k][0]]], x[n[corner[k][1]]], x[n[corner[k][2]]]) <= floor) return false;
  return true;
}

// Local faces of the reference cells, counter-clockwise seen from outside
// (as generateBox's faces).
const std::vector<std::vector<int>>& cellFaces(CellType type) {
  static const std::vector<std::vector<int>> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}};
  return type == CellType::Tet4 ? tet : hex;
}

// Every cell face, keyed by its sorted node ids, to find the cell of a
// surface facet and whether the face lies on the boundary (one cell).
struct FaceIndex {
  struct Entry {
    std::array<int, 4> key;
    int cell, local;
  };
  std::vector<Entry> entries;

  static std::array<int, 4> keyOf(std::vector<int> nodes) {
    std::sort(nodes.begin(), nodes.end());
    std::array<int, 4> key{-1, -1, -1, -1};
    std::copy(nodes.begin(), nodes.end(), key.begin());
    return key;
  }
  explicit FaceIndex(const Mesh& mesh) {
    const auto& faces = cellFaces(mesh.type);
    entries.reserve(static_cast<size_t>(mesh.numCells()) * faces.size());
    for (int c = 0; c < mesh.numCells(); ++c)
      for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
        std::vector<int> nodes;
        for (int ln : faces[f]) nodes.push_back(mesh.cell(c)[ln]);
        entries.push_back({keyOf(nodes), c, f});
      }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
  }
  // The one cell whose face this is, or -1 (no cell, or an interior face).
  const Entry* boundaryFace(const std::vector<int>& nodes) const {
    const auto key = keyOf(nodes);
    auto lo = std::lower_bound(entries.begin(), entries.end(), key,
                               [](const Entry& e, const std::array<int, 4>& k) { return e.key < k; });
    if (lo == entries.end() || lo->key != key) return nullptr;
    if (lo + 1 != entries.end() && (lo + 1)->key == key) return nullptr;
    return &*lo;
  }
};

std::string physicalName(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? std::to_string(tag) : name;
}

Mesh readGmshFile(const std::string& path, const std::string& file, std::vector<std::string>* warnings) {
  {
    std::error_code ec;
    TRIBOS_REQUIRE(!std::filesystem::is_directory(path, ec), file << " is a directory");
    std::ifstream probe(path, std::ios::binary);
    TRIBOS_REQUIRE(probe.good(), "cannot open " << file << ": " << std::strerror(errno));
  }
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return std::tolower(ch); });

  // A .msh file (ASCII or binary) starts with the line "$MeshFormat". Any
  // other file is refused here rather than handed to Gmsh, which would parse
  // it as a .geo script: its script parser keeps its state after a syntax
  // error, and every later .geo read in the process would fail.
  if (extension != ".geo") {
    std::ifstream in(path, std::ios::binary);
    std::string first;
    std::getline(in, first);
    if (!first.empty() && first.back() == '\r') first.pop_back();
    TRIBOS_REQUIRE(first == "$MeshFormat", file << " is not a Gmsh mesh (a .msh file starts with $MeshFormat; a .geo "
                                                   "script is meshed when its name ends in .geo)");
  }

  GmshSession session;
  std::string error = gmshError([&] { gmsh::open(path); });
  TRIBOS_REQUIRE(error.empty(), file << " is not a mesh Gmsh can read: " << error);
  if (extension == ".geo") {
    error = gmshError([&] { gmsh::model::mesh::generate(3); });
    TRIBOS_REQUIRE(error.empty(), file << ": Gmsh could not mesh the geometry: " << error);
  }

  std::vector<std::size_t> nodeTags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(nodeTags, xyz, parametric, -1, -1, false, false);
  TRIBOS_REQUIRE(!nodeTags.empty(), file << " holds no mesh (no nodes); a .msh file of version 4 or a .geo script is expected");
  std::unordered_map<std::size_t, int> gmshIndex;  // node tag -> position in nodeTags
  gmshIndex.reserve(nodeTags.size());
  for (size_t i = 0; i < nodeTags.size(); ++i) gmshIndex.emplace(nodeTags[i], static_cast<int>(i));

  // The body: the volumes of the physical volumes, or every volume.
  std::vector<std::pair<int, std::string>> volumes;  // entity tag, what to call it in messages
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 3);
  if (!groups.empty()) {
    std::map<int, bool> seen;  // an entity in two physical volumes is read once
    for (const auto& g : groups) {
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(3, g.second, entities);
      for (int e : entities)
        if (!seen[e]) seen[e] = true, volumes.emplace_back(e, "physical volume '" + physicalName(3, g.second) + "'");
    }
  } else {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, 3);
    for (const auto& e : entities) volumes.emplace_back(e.second, "volume " + std::to_string(e.second));
  }

  Mesh mesh;
  int cellGmshType = 0;
  std::string firstVolume;
  std::vector<std::size_t> cellTags, cellNodes;  // Gmsh tags
  for (const auto& [entity, what] : volumes) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, 3, entity);
    for (int type : types) {
      TRIBOS_REQUIRE(type == 4 || type == 5, file << ": element type " << type << " (" << elementTypeName(type) << ") in "
                                                  << what << " is not supported; Tribos reads Tet4 and Hex8");
      TRIBOS_REQUIRE(cellGmshType == 0 || cellGmshType == type,
                     file << " mixes " << elementTypeName(cellGmshType) << " (" << firstVolume << ") and "
                          << elementTypeName(type) << " (" << what << "); a body has one cell type, Tet4 or Hex8");
      if (cellGmshType == 0) cellGmshType = type, firstVolume = what;
      std::vector<std::size_t> tags, nodes;
      gmsh::model::mesh::getElementsByType(type, tags, nodes, entity);
      cellTags.insert(cellTags.end(), tags.begin(), tags.end());
      cellNodes.insert(cellNodes.end(), nodes.begin(), nodes.end());
    }
  }
  TRIBOS_REQUIRE(!cellTags.empty(), file << " has no 3D elements" << (groups.empty() ? "" : " in its physical volumes")
                                          << "; Tribos meshes bodies with Tet4 or Hex8 cells");
  mesh.type = cellGmshType == 4 ? CellType::Tet4 : CellType::Hex8;

  // Nodes no cell uses (geometry points, nodes of surfaces only) are dropped;
  // the rest keep Gmsh's order. Gmsh's Tet4 and Hex8 node orders are
  // Tribos' (positive volume; Hex8 bottom 0-3 then top 4-7), checked below.
  std::vector<int> newIndex(nodeTags.size(), -1);
  for (std::size_t tag : cellNodes) {
    const auto it = gmshIndex.find(tag);
    TRIBOS_REQUIRE(it != gmshIndex.end(), file << ": an element names node " << tag << ", which the file does not define");
    newIndex[it->second] = 0;
  }
  int used = 0;
  std::size_t firstDropped = 0;
  for (size_t i = 0; i < nodeTags.size(); ++i) {
    if (newIndex[i] < 0) {
      if (firstDropped == 0) firstDropped = nodeTags[i];
      continue;
    }
    newIndex[i] = used++;
    mesh.coords.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  }
  if (used < static_cast<int>(nodeTags.size())) {
    std::ostringstream os;
    os << file << ": " << nodeTags.size() - used << " of its " << nodeTags.size()
       << " nodes belong to no 3D element and are dropped (the first: node " << firstDropped << ")";
    if (warnings) warnings->push_back(os.str());
    else std::cerr << "warning: " << os.str() << std::endl;
  }
  mesh.connectivity.reserve(cellNodes.size());
  for (std::size_t tag : cellNodes) mesh.connectivity.push_back(newIndex[gmshIndex.at(tag)]);

  std::vector<std::size_t> bad;
  for (int c = 0; c < mesh.numCells(); ++c)
    if (!positiveCell(mesh, c)) bad.push_back(cellTags[c]);
  if (!bad.empty()) {
    std::ostringstream os;
    for (size_t i = 0; i < std::min<size_t>(bad.size(), 5); ++i) os << (i ? ", " : "") << bad[i];
    throw Error(file + ": " + std::to_string(bad.size()) + " inverted or degenerate element" +
                (bad.size() > 1 ? "s" : "") + " (non-positive volume): element" + (bad.size() > 1 ? "s " : " ") + os.str() +
                (bad.size() > 5 ? ", ..." : ""));
  }

  // Named faces: the physical surfaces, each facet the face of its boundary cell.
  const FaceIndex index(mesh);
  const int facetType = mesh.type == CellType::Tet4 ? 2 : 3;
  gmsh::vectorpair surfaces;
  gmsh::model::getPhysicalGroups(surfaces, 2);
  for (const auto& g : surfaces) {
    const std::string name = physicalName(2, g.second);
    std::vector<Facet>& face = mesh.faces[name];
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(2, g.second, entities);
    for (int e : entities) {
      std::vector<int> types;
      gmsh::model::mesh::getElementTypes(types, 2, e);
      for (int type : types) {
        TRIBOS_REQUIRE(type == facetType, file << ": element type " << type << " (" << elementTypeName(type)
                                               << ") in physical surface '" << name << "' is not supported with "
                                               << cellTypeName(mesh.type) << " cells; their faces are "
                                               << elementTypeName(facetType));
        std::vector<std::size_t> tags, nodes;
        gmsh::model::mesh::getElementsByType(type, tags, nodes, e);
        const size_t npf = type == 2 ? 3 : 4;
        for (size_t k = 0; k < tags.size(); ++k) {
          std::vector<int> facetNodes;
          for (size_t a = 0; a < npf; ++a) {
            const auto it = gmshIndex.find(nodes[k * npf + a]);
            facetNodes.push_back(it == gmshIndex.end() ? -1 : newIndex[it->second]);
          }
          const auto* hit = std::count(facetNodes.begin(), facetNodes.end(), -1) ? nullptr : index.boundaryFace(facetNodes);
          TRIBOS_REQUIRE(hit, file << ": surface '" << name << "' is not on the boundary (facet " << tags[k] << ")");
          Facet f;
          f.cell = hit->cell;
          for (int ln : cellFaces(mesh.type)[hit->local]) f.nodes.push_back(mesh.cell(hit->cell)[ln]);
          face.push_back(std::move(f));
        }
      }
    }
  }
  return mesh;
}

}  // namespace

Mesh readGmsh(const std::string& path, std::vector<std::string>* warnings) {
  const std::string file = "mesh file \"" + path + "\"";
  // A Gmsh call that fails outside gmshError() (on a model Gmsh has read)
  // throws a string (4.8) or an exception: said as a Tribos::Error naming the file.
  try {
    return readGmshFile(path, file, warnings);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(file + ": Gmsh: " + e.what());
  } catch (const std::string& e) {
    throw Error(file + ": Gmsh: " + e);
  } catch (const char* e) {
    throw Error(file + ": Gmsh: " + std::string(e ? e : "unknown error"));
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
