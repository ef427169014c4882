// prism_counts.cpp: the prism meshes of the paper, levels 2..8: nodes
// (nx+1)(ny+1)(nz+1) and contact nodes nx(ny+1) (the zmin nodes on the
// clamped face xmin are Dirichlet nodes, not contact nodes), and the nodal
// slip bounds add up to the traction bound times the contact area.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>

#include "PrismProblem.hpp"

namespace {

using namespace Tribos;

void checkLevel(int L, Teuchos::FancyOStream& out, bool& success) {
  const int nodes[] = {225, 637, 1377, 4056, 9537, 27072, 70785};
  const int contact[] = {40, 84, 144, 299, 544, 1104, 2112};
  Semismooth::MeshContactProblem pr = sstest::prism(L);
  const auto c = Mesh::prismLevelCells(L);
  TEST_EQUALITY(pr.mesh.numNodes(), nodes[L - 2]);
  TEST_EQUALITY((c[0] + 1) * (c[1] + 1) * (c[2] + 1), nodes[L - 2]);  // cell counts
  const Semismooth::ContactProblem p = Semismooth::buildContactProblem(pr.mesh, pr.material, pr.loads, pr.contactFace,
                                                                       pr.gap, pr.slipBoundTraction);
  TEST_EQUALITY(static_cast<int>(p.contact.size()), contact[L - 2]);
  TEST_EQUALITY(c[0] * (c[1] + 1), contact[L - 2]);  // nx(ny+1)
  // Nodal areas: the whole zmin face is 2 x 1; the excluded x = 0 edge
  // carries half a cell width of it.
  double gsum = 0;
  for (const auto& n : p.contact) gsum += n.g;
  const double area = 2.0 - 0.5 * (2.0 / c[0]);
  out << "sum g_i = " << gsum << ", expected " << pr.slipBoundTraction * area << "\n";
  TEST_COMPARE(std::abs(gsum - pr.slipBoundTraction * area), <=, 1e-12 * pr.slipBoundTraction * area);
  bool normalsDown = true;
  for (const auto& n : p.contact)
    normalsDown = normalsDown && n.normal[2] < 0 && std::abs(n.normal[0]) + std::abs(n.normal[1]) <= 1e-12 * -n.normal[2];
  TEST_ASSERT(normalsDown);  // the outward normals of zmin point to -z
}

}  // namespace

TEUCHOS_UNIT_TEST(PrismCounts, Level2) { checkLevel(2, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level3) { checkLevel(3, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level4) { checkLevel(4, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level5) { checkLevel(5, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level6) { checkLevel(6, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level7) { checkLevel(7, out, success); }
TEUCHOS_UNIT_TEST(PrismCounts, Level8) { checkLevel(8, out, success); }
