// Tribos_GeoScript.hpp: a Gmsh .geo script meshed by the gmsh executable in
// a child process of bounded time and memory. A .geo is a program: Gmsh
// runs its System commands in a shell, reads the files it Includes, and
// runs its loops and meshes without bound. In a child of its own process
// group with resource limits, a runaway script ends with a message naming
// the limit it reached instead of hanging or exhausting the run's machine.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <memory>
#include <string>

#include "Tribos_MeshFile.hpp"

namespace Tribos {
class CleanupOnSignal;
namespace Mesh {

// How long the ranks that do not mesh wait, after a stop signal, for the
// one that meshes to end Gmsh and remove its directory (SignalGrace,
// Tribos_CleanupOnSignal.hpp): far more than that takes, and a run told to
// end still ends within seconds.
constexpr double kGeoSignalGraceSeconds = 5;

// The gmsh executable that meshes .geo scripts: the one found when Tribos
// was configured, else the first `gmsh` on PATH; "" when there is none.
std::string gmshExecutable();

// Meshes `script` in 3D into a .msh file (format 4.1) in a fresh private
// temporary directory, which the destructor removes with everything in it.
// The child runs `gmsh SCRIPT -3 -format msh41 -o DIR/mesh.msh` in a process
// group of its own (the commands a System starts end with it), with stdin
// from /dev/null, its output kept in DIR/gmsh.log, HOME set to DIR (no
// option or session files of the user's), and limits: the address space
// (options.memoryLimit, when > 0), the CPU time and the wall clock
// (options.geoTimeLimit; at the deadline the whole process group is killed),
// the size of any file it writes (the memory limit, or 64 GB), no core file.
// The caller has checked options.runGeoScript (requireGeoScriptAllowed).
//
// SIGTERM, SIGINT or SIGHUP of the run, while the object lives, kill the
// child's process group and remove the directory before the signal ends
// the run (CleanupOnSignal): neither outlives a run stopped by mpirun or
// Ctrl-C. The directory, TMPDIR/tribos-geo-HOST-PID-XXXXXX, is locked
// (flock) while the object lives; one that a run killed by SIGKILL left
// (its PID gone, its lock free) is removed by the next object made on
// that host. The child dies with the run (PR_SET_PDEATHSIG).
//
// Throws Tribos::Error naming `file` (how messages call the script) and the
// way it ended: the time limit (Mesh/Geo Time Limit), the memory limit
// (--max-memory), a file larger than its bound, Gmsh's own error (its last
// error lines quoted), a signal, no gmsh executable.
class GeoScriptMesh {
 public:
  GeoScriptMesh(const std::string& script, const std::string& file, const MeshFileOptions& options);
  ~GeoScriptMesh();
  GeoScriptMesh(const GeoScriptMesh&) = delete;
  GeoScriptMesh& operator=(const GeoScriptMesh&) = delete;

  // The .msh file Gmsh wrote.
  const std::string& mshPath() const { return msh_; }
  // The temporary directory (removed by the destructor).
  const std::string& directory() const { return dir_; }

 private:
  void makeDirectory(const std::string& file);
  void removeDirectory();
  // In the signal handler: the child's group killed, the directory removed.
  static void stopAtOnce(const void* self);
  std::string dir_, msh_, log_;
  std::atomic<pid_t> child_{0};
  int lock_ = -1;  // the directory, open and locked: the run that made it lives
  std::unique_ptr<CleanupOnSignal> onSignal_;
};

}  // namespace Mesh
}  // namespace Tribos
