// Tribos_MeshBroadcast.hpp: a mesh packed into bytes, and a mesh read on one
// rank sent to every rank.
#pragma once

#include <Teuchos_Comm.hpp>

#include "Tribos_ByteBuffer.hpp"
#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// Cell type, nodes, cells, faces (with the part face nodes), bodies and node
// sets, appended to / read from a buffer.
void packMesh(const Mesh& mesh, ByteBuffer& buffer);
Mesh unpackMesh(ByteBuffer& buffer);

// Replaces `mesh` on every rank but `root` by root's. Collective.
// Reading a file on one rank and broadcasting it keeps every rank's mesh the
// same (ranks meshing a .geo on their own could differ) and prints the
// reader's warnings once.
void broadcastMesh(Mesh& mesh, const Teuchos::Comm<int>& comm, int root = 0);

}  // namespace Mesh
}  // namespace Tribos
