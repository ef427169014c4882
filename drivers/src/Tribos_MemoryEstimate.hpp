// Tribos_MemoryEstimate.hpp: how much memory a run will need, from the mesh
// sizes and the solver choice alone, before anything is allocated. A run
// that would not fit is refused with the estimate instead of ending in
// std::bad_alloc or swapping for minutes.
//
// The model (bytes, per rank; constants fitted to measured peak resident
// sizes, docs/exit_codes.md#memory):
//   base           80 MB (libraries, MPI)
//   mesh           every rank holds the whole mesh: 400 per node + 50 per cell
//                  (the box's counts, or those of the mesh read from Mesh/File)
//   FETI           per subdomain s with n_s nodes, d_s = 3 n_s dofs:
//                    4000 n_s (K_s, B_s, maps) + 150 d_s^(4/3) (sparse Cholesky
//                    factor with nested dissection) + 16 b_s^2 (dense (K+)_bb
//                    and its workspace, when F is explicit; b_s = 3/2 of the
//                    subdomain's surface dofs)
//   Monolithic     8000 per owned node (matrix, MueLu hierarchy, vectors);
//                  a direct solve adds 300 d^(4/3) for the whole mesh
//   Newton         Semismooth Newton on FETI, on every rank: 24 n^2 for n dual
//                  rows (0.65 S b), at most its Dense Limit
//   semismooth*    on rank 0: 28000 per node + 150 d^(4/3) for the whole mesh
// It is meant to be right within a factor of two, which is what a refusal needs.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>

#include "Tribos_Input.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

struct MemoryEstimate {
  double mesh = 0;    // bytes: base, replicated mesh and vectors
  double solver = 0;  // bytes: matrices, factors, dense blocks
  double total() const { return mesh + solver; }
  std::string describe() const;  // "1.2 GB (mesh 0.1 GB, solver 1.1 GB)"
};

// This rank's estimate for the run `params` describes on numRanks ranks; the
// mesh is the box of Input::boxSpec(params), or of size *meshSize when given.
MemoryEstimate estimateMemory(const Teuchos::ParameterList& params, int numRanks, int rank, bool verify,
                              const MeshSize* meshSize = nullptr);

// The bytes one load step adds to the output directory: its data file (the
// mesh, the displacement, the cell fields and the contact point set), its
// part of the index, its row of the steps table and its history rows. Within
// a factor of two, like the memory estimate.
double outputBytesPerStep(const Teuchos::ParameterList& params, const MeshSize* meshSize = nullptr);

// Memory this machine can give a run: MemAvailable, lowered by a cgroup
// limit when there is one (bytes; 0 when unknown).
double availableMemory();

// The memory a run may use on this machine: --max-memory (maxMemory > 0),
// which may only lower availableMemory(); 0 when neither is known.
double memoryLimit(double maxMemory);

// "4G", "500M", "2.5GB", "1e9": bytes. Throws Tribos::Error naming `what`.
double parseMemorySize(const std::string& text, const std::string& what);

// Collective: sums the estimates of the ranks that share a machine and
// compares them with `limit` (bytes; 0 = the machine's available memory).
// Throws CollectiveError with the estimate when the run does not fit.
// Returns this rank's estimate.
MemoryEstimate requireMemory(const Teuchos::ParameterList& params, double limit, bool verify, const RCP<const Comm>& comm,
                             const MeshSize* meshSize = nullptr);

}  // namespace Tribos
