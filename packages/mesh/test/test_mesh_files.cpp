// Mesh files as hostile input. A .geo is a program: refused unless allowed
// (its System commands never run), and when allowed meshed by Gmsh in a
// child process that ends at its time and memory limits, whose errors are
// quoted, whose background commands end with it and whose temporary
// directory is removed. Paths that are not regular files (a FIFO, a device)
// are refused before they are opened; a Gmsh file larger than the memory
// limit before it is read.
#include <Teuchos_UnitTestHarness.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "Tribos_GeoScript.hpp"
#include "Tribos_GmshReader.hpp"
#include "Tribos_MeshFile.hpp"

#include "Tribos_TestSupport.hpp"

namespace {

using namespace Tribos::Mesh;
namespace fs = std::filesystem;

using Tribos::Test::contains;
using Tribos::Test::errorOf;

// A directory of this test's own, removed at the end; TMPDIR points into it
// so that the mesher's temporary directories can be counted.
struct Scratch {
  fs::path dir, tmp;
  Scratch() {
    dir = fs::temp_directory_path() / ("tribos_mesh_files_test_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "tmp");
    tmp = dir / "tmp";
    setenv("TMPDIR", tmp.c_str(), 1);
  }
  ~Scratch() {
    unsetenv("TMPDIR");
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
  int leftovers() const { return static_cast<int>(std::distance(fs::directory_iterator(tmp), fs::directory_iterator())); }
};

// A unit cube of 2 x 2 x 2 hexahedra with a physical volume and surface.
const char* kCube =
    "SetFactory(\"OpenCASCADE\");\n"
    "Box(1) = {0, 0, 0, 1, 1, 1};\n"
    "Transfinite Curve{:} = 3;\nTransfinite Surface{:};\nRecombine Surface{:};\nTransfinite Volume{1};\n"
    "Physical Volume(\"cube\") = {1};\nPhysical Surface(\"bottom\") = {5};\n";

MeshFileOptions allowed(double seconds = 60, double memory = 0) {
  MeshFileOptions options;
  options.runGeoScript = true;
  options.geoTimeLimit = seconds;
  options.memoryLimit = memory;
  return options;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Whether a process runs (a zombie does not: it has ended).
bool running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const size_t close = line.rfind(')');
  return close != std::string::npos && line.size() > close + 2 && line[close + 2] != 'Z';
}

pid_t readPid(const std::string& path) {
  pid_t pid = 0;
  std::ifstream(path) >> pid;
  return pid;
}

TEUCHOS_UNIT_TEST(GeoScript, RefusedUnlessAllowed) {
  const Scratch s;
  const std::string mark = (s.dir / "system_ran").string();
  const std::string script = s.write("system.geo", "System \"touch " + mark + "\";\n" + kCube);
  for (const std::string& path : {script, s.write("include.geo", "Include \"/etc/passwd\";\n" + std::string(kCube))}) {
    const std::string e = errorOf([&] { readMeshFile(path); });
    out << e << "\n";
    TEST_ASSERT(contains(e, "mesh file \"" + path + "\" is a Gmsh script (.geo): a program") &&
                contains(e, "set Mesh/Run Geo Script = true"));
    TEST_ASSERT(!fs::exists(mark));  // the script never ran
  }
  // The check the driver makes before any work says the same.
  TEST_ASSERT(contains(errorOf([&] { requireGeoScriptAllowed(script, MeshFileOptions()); }), "Mesh/Run Geo Script"));
  TEST_EQUALITY(errorOf([&] { requireGeoScriptAllowed(s.dir / "mesh.msh", MeshFileOptions()); }), "");
  // Allowed, it is a program indeed: its command runs and its mesh is read.
  const Mesh m = readMeshFile(script, nullptr, allowed());
  TEST_ASSERT(fs::exists(mark));
  TEST_EQUALITY(m.numCells(), 8);
  TEST_EQUALITY(s.leftovers(), 0);
}

TEUCHOS_UNIT_TEST(GeoScript, TimeLimit) {
  const Scratch s;
  const std::string path = s.write("loop.geo", "x = 0;\nFor i In {1:1e15}\n  x = x + 1;\nEndFor\n");
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = errorOf([&] { readMeshFile(path, nullptr, allowed(1)); });
  const double took = secondsSince(t0);
  out << e << " (" << took << " s)\n";
  TEST_ASSERT(contains(e, "loop.geo") &&
              contains(e, "Gmsh did not finish meshing the script within its time limit of 1 s (Mesh/Geo Time Limit)"));
  TEST_COMPARE(took, >=, 1.0);
  TEST_COMPARE(took, <, 10.0);
  TEST_EQUALITY(s.leftovers(), 0);
}

TEUCHOS_UNIT_TEST(GeoScript, BackgroundCommandsEndWithIt) {
  // A command the script starts in the background ends with Gmsh: at the
  // deadline, and when Gmsh finishes.
  const Scratch s;
  for (const bool loop : {true, false}) {
    const std::string pidFile = (s.dir / (loop ? "loop.pid" : "done.pid")).string();
    const std::string path =
        s.write("background.geo", "System \"sleep 60 > /dev/null 2>&1 & echo $! > " + pidFile + "\";\n" +
                                      (loop ? std::string("x = 0;\nFor i In {1:1e15}\n  x = x + 1;\nEndFor\n") : kCube));
    const std::string e = errorOf([&] { readMeshFile(path, nullptr, allowed(loop ? 1 : 60)); });
    out << e << "\n";
    TEST_EQUALITY(contains(e, "time limit"), loop);
    const pid_t sleeper = readPid(pidFile);
    TEST_COMPARE(sleeper, >, 0);
    // The sleeper's parent, the shell, has ended: it is reaped by init (or a
    // subreaper) soon after the kill.
    for (int k = 0; k < 100 && sleeper > 0 && running(sleeper); ++k) usleep(20000);
    TEST_ASSERT(sleeper > 0 && !running(sleeper));
  }
}

TEUCHOS_UNIT_TEST(GeoScript, MemoryLimit) {
  // 4000^3 hexahedra: their surfaces alone exceed 300 MB, reached in a fraction of a second.
  const Scratch s;
  const std::string path = s.write("fine.geo",
                                   "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                   "Transfinite Curve{:} = 4000;\nTransfinite Surface{:};\nRecombine Surface{:};\n"
                                   "Transfinite Volume{1};\nPhysical Volume(\"body\") = {1};\n");
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = errorOf([&] { readMeshFile(path, nullptr, allowed(60, 300.0 * 1024 * 1024)); });
  out << e << " (" << secondsSince(t0) << " s)\n";
  TEST_ASSERT(contains(e, "fine.geo") && contains(e, "Gmsh ran out of memory meshing the script: it may use 300 MB") &&
              contains(e, "--max-memory"));
  TEST_COMPARE(secondsSince(t0), <, 30.0);
  TEST_EQUALITY(s.leftovers(), 0);
  // The cube fits in it.
  const std::string cube = s.write("cube.geo", kCube);
  TEST_EQUALITY(readMeshFile(cube, nullptr, allowed(60, 300.0 * 1024 * 1024)).numCells(), 8);
}

TEUCHOS_UNIT_TEST(GeoScript, GmshErrorQuoted) {
  const Scratch s;
  const std::string path = s.write("syntax.geo", "Point(1) = {0, 0, 0};\nfoo bar;\n");
  const std::string e = errorOf([&] { readMeshFile(path, nullptr, allowed()); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "syntax.geo") && contains(e, "Gmsh could not mesh the script: ") &&
              contains(e, "line 2: Unknown command 'foo'"));
  TEST_EQUALITY(s.leftovers(), 0);
}

TEUCHOS_UNIT_TEST(GeoScript, PrivateDirectoryRemoved) {
  const Scratch s;
  const std::string path = s.write("cube.geo", kCube);
  std::string dir;
  {
    const GeoScriptMesh meshed(path, "the cube", allowed());
    dir = meshed.directory();
    TEST_ASSERT(fs::path(dir).parent_path() == s.tmp);
    TEST_ASSERT(fs::is_regular_file(meshed.mshPath()));
    struct stat st {};
    TEST_ASSERT(stat(dir.c_str(), &st) == 0 && (st.st_mode & 0777) == 0700);
    std::ifstream msh(meshed.mshPath());
    std::string first, version;
    msh >> first >> version;
    TEST_EQUALITY(first, "$MeshFormat");
    TEST_EQUALITY(version, "4.1");
  }
  TEST_ASSERT(!fs::exists(dir));
  TEST_EQUALITY(s.leftovers(), 0);
}

TEUCHOS_UNIT_TEST(MeshFiles, NotRegularFiles) {
  const Scratch s;
  // A FIFO nobody writes to: opened, it would block the read forever.
  const std::string fifo = (s.dir / "pipe.msh").string();
  const int made = mkfifo(fifo.c_str(), 0600);
  TEST_EQUALITY(made, 0);
  std::string e = errorOf([&] { readMeshFile(fifo); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "mesh file \"" + fifo + "\" is a FIFO (named pipe), not a regular file"));
  // A device, by its own name and behind a mesh file's name: /dev/zero
  // would be read until memory runs out.
  e = errorOf([&] { readMeshFile("/dev/zero"); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "mesh file \"/dev/zero\" is a character device, not a regular file"));
  const std::string link = (s.dir / "zero.exo").string();
  fs::create_symlink("/dev/zero", link);
  e = errorOf([&] { readMeshFile(link); });
  TEST_ASSERT(contains(e, "zero.exo\" is a character device"));
  e = errorOf([&] { readGmsh("/dev/null"); });
  TEST_ASSERT(contains(e, "\"/dev/null\" is a character device"));
  e = errorOf([&] { readMeshFile(s.dir.string()); });
  TEST_ASSERT(contains(e, "is a directory"));
}

TEUCHOS_UNIT_TEST(MeshFiles, GmshFileLargerThanTheMemoryLimit) {
  // Gmsh holds a .msh whole: a file larger than the memory the read may
  // use is refused before Gmsh reads it.
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  const std::string block = std::string(dir ? dir : ".") + "/input/gmsh_block.msh";
  MeshFileOptions options;
  options.memoryLimit = 10000;
  const std::string e = errorOf([&] { readMeshFile(block, nullptr, options); });
  out << e << "\n";
  TEST_ASSERT(contains(e, "gmsh_block.msh\" is ") && contains(e, "kB, more than 10000 bytes (the memory the read may use"));
  options.memoryLimit = 100e6;
  TEST_EQUALITY(readMeshFile(block, nullptr, options).numCells(), 1125);
}

}  // namespace
