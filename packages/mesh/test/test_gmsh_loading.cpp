// Gmsh is loaded by the first read of a Gmsh mesh, not at the start of a
// process: its libraries (OpenCASCADE, FLTK, X11, OpenGL...) tripled the
// start of every Tribos process, most of which read no Gmsh file
// (src/detail/Tribos_GmshApi.hpp). This executable links tribos_mesh as a
// driver does, and no Gmsh of its own.
#include <Teuchos_UnitTestHarness.hpp>

#include <cstdlib>
#include <fstream>
#include <string>

#include "Tribos_MeshFile.hpp"

namespace {

// Whether a shared object whose file name starts with 'prefix' is mapped
// into this process.
bool mapped(const std::string& prefix) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const auto slash = line.rfind('/');
    if (slash != std::string::npos && line.compare(slash + 1, prefix.size(), prefix) == 0) return true;
  }
  return false;
}

TEUCHOS_UNIT_TEST(GmshLoading, OnFirstReadOfAGmshMesh) {
  TEST_ASSERT(mapped("libtrilinos_teuchoscore"));  // the test of the test: maps are read
  TEST_ASSERT(!mapped("libgmsh"));
  TEST_ASSERT(!mapped("libTKernel"));  // OpenCASCADE, which Gmsh brings
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  const std::string block = std::string(dir ? dir : ".") + "/input/gmsh_block.msh";
  TEST_EQUALITY(Tribos::Mesh::readMeshFile(block).numCells(), 1125);
  TEST_ASSERT(mapped("libgmsh"));
  // A second read uses the library loaded by the first.
  TEST_EQUALITY(Tribos::Mesh::readMeshFile(block).numCells(), 1125);
}

}  // namespace
