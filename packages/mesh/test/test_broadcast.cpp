// broadcastMesh: every rank ends with rank 0's mesh, bodies, faces and node
// sets included (run on 1 and 2 ranks).
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include "Tribos_MeshBroadcast.hpp"

namespace {

using namespace Tribos::Mesh;

// A Tet4 box made into two bodies (cells below and above z = 1) with a node
// set and a face: what a reader returns.
Mesh sample() {
  BoxSpec spec;
  spec.type = CellType::Tet4;
  spec.z = {0, 2};
  spec.cells = {2, 3, 2};
  Mesh m = generateBox(spec);
  m.bodyNames = {"lower", "upper"};
  m.cellBody.assign(m.numCells(), 0);
  for (int c = m.numCells() / 2; c < m.numCells(); ++c) m.cellBody[c] = 1;
  m.nodeSets["pins"] = {1, 7, 30};
  m.nodeSets["empty"] = {};
  m.faces["empty face"] = {};
  return m;
}

bool sameMesh(const Mesh& a, const Mesh& b) {
  bool same = a.type == b.type && a.coords == b.coords && a.connectivity == b.connectivity &&
              a.cellBody == b.cellBody && a.bodyNames == b.bodyNames && a.nodeSets == b.nodeSets &&
              a.faceNames() == b.faceNames();
  for (const auto& name : a.faceNames()) {
    const auto &fa = a.face(name), &fb = b.face(name);
    same = same && fa.size() == fb.size();
    for (size_t k = 0; same && k < fa.size(); ++k) same = fa[k].nodes == fb[k].nodes && fa[k].cell == fb[k].cell;
  }
  return same;
}

}  // namespace

TEUCHOS_UNIT_TEST(Broadcast, EveryRankGetsRootsMesh) {
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const Mesh reference = sample();
  Mesh m;
  if (comm->getRank() == 0) m = reference;
  else m.coords = {{9, 9, 9}};  // replaced
  broadcastMesh(m, *comm);
  TEST_ASSERT(sameMesh(m, reference));
  TEST_EQUALITY(m.numBodies(), 2);
  TEST_EQUALITY(m.faceBody("zmax"), 1);
  // A Hex8 mesh of one body without names from the last rank.
  BoxSpec spec;
  spec.cells = {1, 2, 3};
  const Mesh box = generateBox(spec);
  Mesh h;
  if (comm->getRank() == comm->getSize() - 1) h = box;
  broadcastMesh(h, *comm, comm->getSize() - 1);
  TEST_ASSERT(sameMesh(h, box));
  TEST_EQUALITY(h.numBodies(), 1);
}
