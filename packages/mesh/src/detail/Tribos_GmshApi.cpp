#include "detail/Tribos_GmshApi.hpp"

#include <dlfcn.h>
// Declarations only: the functions are looked up in the loaded library, with
// these types (decltype does not refer to the symbols).
#include <gmshc.h>

#include <mutex>

#include "Tribos_Error.hpp"

// The library CMake found (cmake/FindGmsh.cmake): its soname, and its file
// as a second choice.
#ifndef TRIBOS_GMSH_LIBRARY
#define TRIBOS_GMSH_LIBRARY "libgmsh.so"
#endif
#ifndef TRIBOS_GMSH_LIBRARY_PATH
#define TRIBOS_GMSH_LIBRARY_PATH TRIBOS_GMSH_LIBRARY
#endif

namespace Tribos {
namespace Mesh {
namespace detail {
namespace Gmsh {

namespace {

// The C API's functions, typed by their declarations in gmshc.h (every call
// ends with int* ierr).
struct Library {
  void* handle = nullptr;
  decltype(&::gmshFree) free = nullptr;
  decltype(&::gmshLoggerGetLastError) lastError = nullptr;
  int (*isInitialized)(int*) = nullptr;  // gmshIsInitialized: absent before Gmsh 4.9
  decltype(&::gmshInitialize) initialize = nullptr;
  decltype(&::gmshFinalize) finalize = nullptr;
  decltype(&::gmshOpen) open = nullptr;
  decltype(&::gmshOptionSetNumber) setNumber = nullptr;
  decltype(&::gmshModelGetPhysicalName) physicalName = nullptr;
  decltype(&::gmshModelGetPhysicalGroups) physicalGroups = nullptr;
  decltype(&::gmshModelGetEntitiesForPhysicalGroup) entitiesForPhysicalGroup = nullptr;
  decltype(&::gmshModelGetEntities) entities = nullptr;
  decltype(&::gmshModelMeshGetNodes) nodes = nullptr;
  decltype(&::gmshModelMeshGetElementTypes) elementTypes = nullptr;
  decltype(&::gmshModelMeshGetElementsByType) elementsByType = nullptr;
  decltype(&::gmshModelMeshGetElementProperties) elementProperties = nullptr;
};

template <class F>
void bind(void* handle, const char* name, F& f, bool required = true) {
  f = reinterpret_cast<F>(dlsym(handle, name));
  TRIBOS_REQUIRE(f || !required, "Gmsh library " << TRIBOS_GMSH_LIBRARY << " has no function " << name
                                                 << "; Tribos reads meshes with the Gmsh API of version 4.8 or later");
}

Library load() {
  Library g;
  g.handle = dlopen(TRIBOS_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (!g.handle) g.handle = dlopen(TRIBOS_GMSH_LIBRARY_PATH, RTLD_NOW | RTLD_LOCAL);
  if (!g.handle) {
    const char* why = dlerror();
    throw Error(std::string("reading a Gmsh mesh needs the Gmsh library ") + TRIBOS_GMSH_LIBRARY +
                " (Debian: apt-get install libgmsh-dev), which could not be loaded: " + (why ? why : "unknown reason"));
  }
  bind(g.handle, "gmshFree", g.free);
  bind(g.handle, "gmshLoggerGetLastError", g.lastError);
  bind(g.handle, "gmshIsInitialized", g.isInitialized, false);
  bind(g.handle, "gmshInitialize", g.initialize);
  bind(g.handle, "gmshFinalize", g.finalize);
  bind(g.handle, "gmshOpen", g.open);
  bind(g.handle, "gmshOptionSetNumber", g.setNumber);
  bind(g.handle, "gmshModelGetPhysicalName", g.physicalName);
  bind(g.handle, "gmshModelGetPhysicalGroups", g.physicalGroups);
  bind(g.handle, "gmshModelGetEntitiesForPhysicalGroup", g.entitiesForPhysicalGroup);
  bind(g.handle, "gmshModelGetEntities", g.entities);
  bind(g.handle, "gmshModelMeshGetNodes", g.nodes);
  bind(g.handle, "gmshModelMeshGetElementTypes", g.elementTypes);
  bind(g.handle, "gmshModelMeshGetElementsByType", g.elementsByType);
  bind(g.handle, "gmshModelMeshGetElementProperties", g.elementProperties);
  return g;
}

// The library, loaded once per process (kept loaded: Gmsh registers
// handlers at load that its unloading would leave dangling).
const Library& lib() {
  static std::once_flag once;
  static Library g;
  static std::string failure;
  std::call_once(once, [] {
    try {
      g = load();
    } catch (const Error& e) {
      failure = e.what();
    }
  });
  if (!failure.empty()) throw Error(failure);
  return g;
}

// Throws GmshFailure with Gmsh's last error when a call set ierr.
void check(int ierr) {
  if (ierr == 0) return;
  std::string message = "unknown error";
  char* text = nullptr;
  int ignored = 0;
  lib().lastError(&text, &ignored);
  if (text) {
    if (*text) message = text;
    lib().free(text);
  }
  throw GmshFailure{message};
}

// Gmsh's arrays, copied and released.
template <class T>
std::vector<T> take(T* data, size_t n) {
  std::vector<T> v(data, data + n);
  if (data) lib().free(data);
  return v;
}

std::string takeString(char* text) {
  std::string s = text ? text : "";
  if (text) lib().free(text);
  return s;
}

// The int array of a call (data, size, error flag), copied and released.
template <class Call>
std::vector<int> intArray(Call&& call) {
  int* data = nullptr;
  size_t n = 0;
  int ierr = 0;
  call(&data, &n, &ierr);
  auto v = take(data, n);
  check(ierr);
  return v;
}

DimTags pairs(const std::vector<int>& flat) {
  DimTags out;
  for (size_t i = 0; i + 1 < flat.size(); i += 2) out.emplace_back(flat[i], flat[i + 1]);
  return out;
}

}  // namespace

int isInitialized() {
  if (!lib().isInitialized) return -1;
  int ierr = 0;
  const int on = lib().isInitialized(&ierr);
  check(ierr);
  return on != 0;
}

void initialize() {
  int ierr = 0;
  lib().initialize(0, nullptr, 0, &ierr);
  check(ierr);
}

void finalize() {
  int ierr = 0;
  lib().finalize(&ierr);
  check(ierr);
}

void open(const std::string& path) {
  int ierr = 0;
  lib().open(path.c_str(), &ierr);
  check(ierr);
}

void setNumberOption(const std::string& name, double value) {
  int ierr = 0;
  lib().setNumber(name.c_str(), value, &ierr);
  check(ierr);
}

std::string physicalName(int dim, int tag) {
  char* name = nullptr;
  int ierr = 0;
  lib().physicalName(dim, tag, &name, &ierr);
  std::string s = takeString(name);
  check(ierr);
  return s;
}

DimTags physicalGroups(int dim) {
  return pairs(intArray([&](int** data, size_t* n, int* ierr) { lib().physicalGroups(data, n, dim, ierr); }));
}

std::vector<int> entitiesForPhysicalGroup(int dim, int tag) {
  return intArray([&](int** data, size_t* n, int* ierr) { lib().entitiesForPhysicalGroup(dim, tag, data, n, ierr); });
}

DimTags entities(int dim) {
  return pairs(intArray([&](int** data, size_t* n, int* ierr) { lib().entities(data, n, dim, ierr); }));
}

void nodes(std::vector<std::size_t>& tags, std::vector<double>& xyz) {
  size_t *t = nullptr, nt = 0, nx = 0, np = 0;
  double *x = nullptr, *p = nullptr;
  int ierr = 0;
  // Every dimension and entity (-1, -1), no boundary nodes of entities, no
  // parametric coordinates.
  lib().nodes(&t, &nt, &x, &nx, &p, &np, -1, -1, 0, 0, &ierr);
  tags = take(t, nt);
  xyz = take(x, nx);
  take(p, np);
  check(ierr);
}

std::vector<int> elementTypes(int dim, int tag) {
  return intArray([&](int** data, size_t* n, int* ierr) { lib().elementTypes(data, n, dim, tag, ierr); });
}

void elementsByType(int type, int tag, std::vector<std::size_t>& tags, std::vector<std::size_t>& nodeTags) {
  size_t *t = nullptr, nt = 0, *nodes = nullptr, nn = 0;
  int ierr = 0;
  lib().elementsByType(type, &t, &nt, &nodes, &nn, tag, 0, 1, &ierr);
  tags = take(t, nt);
  nodeTags = take(nodes, nn);
  check(ierr);
}

std::string elementName(int type) {
  char* name = nullptr;
  int dim = 0, order = 0, numNodes = 0, primary = 0, ierr = 0;
  double* local = nullptr;
  size_t nLocal = 0;
  lib().elementProperties(type, &name, &dim, &order, &numNodes, &local, &nLocal, &primary, &ierr);
  take(local, nLocal);
  std::string s = takeString(name);
  check(ierr);
  return s;
}

}  // namespace Gmsh
}  // namespace detail
}  // namespace Mesh
}  // namespace Tribos
