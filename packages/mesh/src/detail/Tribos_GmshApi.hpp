// Tribos_GmshApi.hpp: the calls of the Gmsh API the mesh reader makes,
// through Gmsh's C API in a library loaded when a Gmsh mesh is first read.
//
// Why not link libgmsh: it brings about eighty libraries with it
// (OpenCASCADE, FLTK, X11, OpenGL, image codecs), and Debian links them with
// immediate binding, so every Tribos process resolved their symbols at start:
// 0.2 s of a 0.3 s start, paid by every rank of every run, most of which read
// no Gmsh file. Loaded on first use (dlopen, local scope), they cost only the
// runs that read a .msh or .geo mesh. The C API also keeps Gmsh's C++ ABI and
// its exceptions out of Tribos: every call returns an error flag, read here.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace Tribos {
namespace Mesh {
namespace detail {
namespace Gmsh {

// Every function loads the library on first use and throws Tribos::Error
// when it cannot (naming the library and what the loader said); a call that
// Gmsh reports failed throws GmshFailure with Gmsh's last error message.
struct GmshFailure {
  std::string message;
};

// Whether Gmsh is initialized: 1 or 0, or -1 when the library cannot say
// (Gmsh 4.8, Debian 12's, has no gmshIsInitialized).
int isInitialized();
void initialize();  // no argv parsing, no configuration files
void finalize();
void open(const std::string& path);
void setNumberOption(const std::string& name, double value);

using DimTags = std::vector<std::pair<int, int>>;
std::string physicalName(int dim, int tag);
DimTags physicalGroups(int dim);
std::vector<int> entitiesForPhysicalGroup(int dim, int tag);
DimTags entities(int dim);

// Every node of the model: tags and coordinates (3 per node).
void nodes(std::vector<std::size_t>& tags, std::vector<double>& xyz);
std::vector<int> elementTypes(int dim, int tag);
// Elements of one type in entity 'tag': tags and node tags.
void elementsByType(int type, int tag, std::vector<std::size_t>& tags, std::vector<std::size_t>& nodeTags);
// Gmsh's name of an element type; throws GmshFailure for a type it does not know.
std::string elementName(int type);

}  // namespace Gmsh
}  // namespace detail
}  // namespace Mesh
}  // namespace Tribos
