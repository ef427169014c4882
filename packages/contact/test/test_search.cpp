// The contact search's geometry: the rigid plane's normal from a face.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <string>

#include "Tribos_ContactSearch.hpp"
#include "Tribos_Mesh.hpp"

namespace {

using namespace Tribos;

// The rigid plane's normal from the contact face's facets: the box table's
// normals exactly, a rotated box's rotated normal, and a bent face refused.
TEUCHOS_UNIT_TEST(ContactNormal, FromFacets) {
  for (auto type : {Mesh::CellType::Tet4, Mesh::CellType::Hex8}) {
    Mesh::BoxSpec spec;
    spec.type = type;
    spec.x = {-1, 2};
    spec.cells = {3, 2, 2};
    Mesh::Mesh mesh = Mesh::generateBox(spec);
    for (const char* face : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
      TEST_ASSERT(Contact::faceNormal(mesh, face) == Contact::faceNormal(face));
    // Rotated by 30 degrees about x: zmin's normal (0, 0, -1) turns with it.
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    for (auto& p : mesh.coords) p = {p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]};
    const auto n = Contact::faceNormal(mesh, "zmin");
    TEST_COMPARE(std::abs(n[0]) + std::abs(n[1] - s) + std::abs(n[2] + c), <, 1e-14);
    auto& bent = mesh.faces["bent"];
    bent = mesh.faces["zmin"];
    bent.insert(bent.end(), mesh.faces["xmax"].begin(), mesh.faces["xmax"].end());
    std::string message;
    try {
      Contact::faceNormal(mesh, "bent");
    } catch (const std::exception& e) {
      message = e.what();
    }
    out << message << "\n";
    TEST_ASSERT(message.find("contact surface 'bent' is not planar") != std::string::npos);
  }
}

}  // namespace
