// Tribos_FCLIB.hpp: reading and writing 3D frictional contact problems in the
// FCLIB HDF5 format.
//
// Layout of a file, as the public FCLIB library and the shipped samples use it:
//   /fclib_local/{W, V?, R?}            sparse matrices (see below)
//   /fclib_local/vectors/{q, mu, s?}    float64 vectors
//   /fclib_local/spacedim               int32, shape (1,)
//   /fclib_local/info/{title, description, math_info}   strings
//   /fclib_global/{M, H, G?}, /fclib_global/vectors/{f, w, mu, b?},
//   /fclib_global/spacedim, /fclib_global/info/...
//   /solution/{v?, u?, r?, l?}
//   /guesses/number_of_guesses, /guesses/1, /guesses/2, ... (same as solution)
// A sparse matrix is a group with int32 datasets nzmax, m, n, nz and arrays
// p, i (int32) and x (float64): nz = -2 compressed rows (p row pointers, i
// column indices), nz = -1 compressed columns (p column pointers, i row
// indices), nz >= 0 triplets with i the row and p the column of each entry.
//
// Problems (per contact the local frame is normal, tangent 1, tangent 2):
//   local:  u = W r + q,                      W is 3nc x 3nc
//   global: M v = H r + f (+ G l),  u = H' v + w,
//           H is ndof x 3nc (stored with m = ndof rows), so H maps contact
//           forces to generalized forces and H' maps velocities to contacts.
// with r in the Coulomb cone and the De Saxce complementarity (see
// Tribos_FCLIB_Accuracy.hpp).
//
// All errors throw std::runtime_error naming the file and the group/dataset.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Tribos_FCLIB_SparseMatrix.hpp"

namespace Tribos {
namespace FCLIB {

struct Info {
  std::string title, description, math_info;
};

// Mixed local problem: u = W r + V l + q, V' r + R l + s = 0; V, R, s are
// absent for a pure contact problem (all shipped files).
struct LocalProblem {
  SparseMatrix W;
  std::vector<double> q, mu;
  int spacedim = 3;
  std::optional<SparseMatrix> V, R;
  std::optional<std::vector<double>> s;

  int numberOfContacts() const { return static_cast<int>(mu.size()); }
};

// Global problem: M v = H r + G l + f, G' v + b = 0, u = H' v + w.
struct GlobalProblem {
  SparseMatrix M, H;
  std::vector<double> f, w, mu;
  int spacedim = 3;
  std::optional<SparseMatrix> G;
  std::optional<std::vector<double>> b;

  int numberOfContacts() const { return static_cast<int>(mu.size()); }
};

// A solution or a guess; a vector absent from the file is left empty.
struct Solution {
  std::vector<double> v, u, r, l;
};

enum class ProblemKind { Local, Global };

// How a writer stores sparse matrices.
enum class Storage { CompressedRows, Triplets };

ProblemKind problemKind(const std::string& path);

LocalProblem readLocal(const std::string& path);
GlobalProblem readGlobal(const std::string& path);
// Info of whichever problem the file holds.
Info readInfo(const std::string& path);
// std::nullopt when the file has no /solution group.
std::optional<Solution> readSolution(const std::string& path);
// Empty when the file has no /guesses group.
std::vector<Solution> readGuesses(const std::string& path);

// Writers create path + ".tmp" and rename it onto path only once everything
// is written, so a failure never leaves a truncated file in place of a good
// one. Dimensions are checked before anything is written.
void writeLocal(const std::string& path, const LocalProblem& problem, const Info& info,
                const Solution* solution = nullptr,
                const std::vector<Solution>& guesses = {},
                Storage storage = Storage::CompressedRows);
void writeGlobal(const std::string& path, const GlobalProblem& problem, const Info& info,
                 const Solution* solution = nullptr,
                 const std::vector<Solution>& guesses = {},
                 Storage storage = Storage::Triplets);

// Dimension checks used by readers and writers; 'where' prefixes the message.
void checkDimensions(const LocalProblem& problem, const std::string& where);
void checkDimensions(const GlobalProblem& problem, const std::string& where);

}  // namespace FCLIB
}  // namespace Tribos
