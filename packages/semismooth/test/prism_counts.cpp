// prism_counts.cpp: the prism meshes of the paper, levels 2..8: nodes
// (nx+1)(ny+1)(nz+1) and contact nodes nx(ny+1) (the zmin nodes on the
// clamped face xmin are Dirichlet nodes, not contact nodes), and the nodal
// slip bounds add up to the traction bound times the contact area.
#include "SemismoothTestUtils.hpp"

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  using namespace Tribos;
  const int nodes[] = {225, 637, 1377, 4056, 9537, 27072, 70785};
  const int contact[] = {40, 84, 144, 299, 544, 1104, 2112};
  for (int L = 2; L <= 8; ++L) {
    Semismooth::MeshContactProblem pr = sstest::prism(L);
    const auto c = Mesh::prismLevelCells(L);
    SS_CHECK(pr.mesh.numNodes() == nodes[L - 2], "L=" << L << ": " << pr.mesh.numNodes() << " nodes");
    SS_CHECK((c[0] + 1) * (c[1] + 1) * (c[2] + 1) == nodes[L - 2], "L=" << L << ": cell counts");
    const Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                         pr.gap, pr.slipBoundTraction);
    SS_CHECK(static_cast<int>(p.contact.size()) == contact[L - 2],
             "L=" << L << ": " << p.contact.size() << " contact nodes, expected " << contact[L - 2]);
    SS_CHECK(c[0] * (c[1] + 1) == contact[L - 2], "L=" << L << ": nx(ny+1)");
    // Nodal areas: the whole zmin face is 2 x 1; the excluded x = 0 edge
    // carries half a cell width of it.
    double gsum = 0;
    for (const auto& n : p.contact) gsum += n.g;
    const double area = 2.0 - 0.5 * (2.0 / c[0]);
    SS_CHECK(std::abs(gsum - pr.slipBoundTraction * area) <= 1e-12 * pr.slipBoundTraction * area,
             "L=" << L << ": sum g_i = " << gsum << ", expected " << pr.slipBoundTraction * area);
    bool normalsDown = true;
    for (const auto& n : p.contact)
      normalsDown = normalsDown && n.normal[2] < 0 && std::abs(n.normal[0]) + std::abs(n.normal[1]) <= 1e-12 * -n.normal[2];
    SS_CHECK(normalsDown, "L=" << L << ": outward normals of zmin must point to -z");
  }
  return sstest::finish();
}
