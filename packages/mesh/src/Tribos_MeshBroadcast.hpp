// Tribos_MeshBroadcast.hpp: a mesh read on one rank, sent to every rank.
#pragma once

#include <Teuchos_Comm.hpp>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Replaces `mesh` on every rank but `root` by root's: cell type, nodes,
// cells, faces, bodies (cellBody, bodyNames) and node sets. Collective.
// Reading a file on one rank and broadcasting it keeps every rank's mesh the
// same (ranks meshing a .geo on their own could differ) and prints the
// reader's warnings once.
void broadcastMesh(Mesh& mesh, const Teuchos::Comm<int>& comm, int root = 0);

}  // namespace Mesh
}  // namespace Tribos
