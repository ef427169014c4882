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
// All errors throw Tribos::Error naming the file and the dataset, e.g.
//   FCLIB file X.hdf5: /fclib_local/vectors/q[17] is not finite (inf)
//
// A problem is validated when it is read, before anything uses it: every
// value finite (matrix entries, q, f, w, b, s, mu), mu >= 0, spacedim 2 or 3,
// and every size consistent with the stored vectors: the number of contacts
// nc is the length of mu, W is (spacedim nc) x (spacedim nc), ndof is the
// length of f, M is ndof x ndof, H is ndof x (spacedim nc). A declared size
// (a matrix's m, n, nz, pointers) that disagrees with the stored data is
// refused before it sizes any allocation, and so is a dataset whose declared
// extent the file does not actually store. Zero contacts is a valid problem.
#pragma once

#include <cstdint>
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
  LocalCsr W;
  std::vector<double> q, mu;
  int spacedim = 3;
  std::optional<LocalCsr> V, R;
  std::optional<std::vector<double>> s;

  int numberOfContacts() const { return static_cast<int>(mu.size()); }
};

// Global problem: M v = H r + G l + f, G' v + b = 0, u = H' v + w.
struct GlobalProblem {
  LocalCsr M, H;
  std::vector<double> f, w, mu;
  int spacedim = 3;
  std::optional<LocalCsr> G;
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

// Every reader opens only a regular file of at most this size: a FIFO or a
// device would block HDF5 or feed it without end. The problems of the FCLIB
// collection have less than 1 GB, and what is read is held in memory on one
// rank.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t(4) << 30;

ProblemKind problemKind(const std::string& path);

// Read and validate (see above and validate()).
LocalProblem readLocal(const std::string& path);
GlobalProblem readGlobal(const std::string& path);
// Info of whichever problem the file holds.
Info readInfo(const std::string& path);
// std::nullopt when the file has no /solution group. Vectors are sized by the
// problem (u, r: spacedim x length of mu; v: length of f) and must be finite.
std::optional<Solution> readSolution(const std::string& path);
// The stored solution as reference data for a problem already read: a vector
// of the wrong size or with a non-finite entry is left empty, an unreadable
// /solution group gives std::nullopt, and each time the reason is appended to
// 'notes'. Never throws for the content of the file: a stored solution is
// never a reason to refuse the problem.
std::optional<Solution> readSolutionLeniently(const std::string& path,
                                              std::vector<std::string>& notes);
// Empty when the file has no /guesses group.
std::vector<Solution> readGuesses(const std::string& path);

// Writers create temporaryPathFor(path) (Tribos_FileSystem.hpp) and rename it
// onto path only once everything is written, so a failure never leaves a
// truncated file in place of a good one. The problem is validated and the
// solution and guesses checked (sizes, finite values) before anything is
// written: what a writer accepts, the readers accept.
void writeLocal(const std::string& path, const LocalProblem& problem, const Info& info,
                const Solution* solution = nullptr,
                const std::vector<Solution>& guesses = {},
                Storage storage = Storage::CompressedRows);
void writeGlobal(const std::string& path, const GlobalProblem& problem, const Info& info,
                 const Solution* solution = nullptr,
                 const std::vector<Solution>& guesses = {},
                 Storage storage = Storage::Triplets);

// The checks of the readers on a problem in memory (built by hand, exported,
// about to be solved or written): sizes, canonical CSR structure, finite
// values, mu >= 0. Throws Tribos::Error "context: /fclib_local/W is ...",
// naming the dataset the offending value belongs to.
void validate(const LocalProblem& problem, const std::string& context);
void validate(const GlobalProblem& problem, const std::string& context);

}  // namespace FCLIB
}  // namespace Tribos
