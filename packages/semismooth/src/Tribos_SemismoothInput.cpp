#include "Tribos_SemismoothInput.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

std::array<double, 2> range2(Teuchos::ParameterList& m, const std::string& key) {
  const auto v = m.get<Teuchos::Array<double>>(key, Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 1.0)));
  TRIBOS_REQUIRE(v.size() == 2, "Mesh/" << key << " needs two values");
  return {v[0], v[1]};
}

Fem::Point point3(Teuchos::ParameterList& p, const std::string& key, const std::string& where) {
  const auto v = p.get<Teuchos::Array<double>>(key, Teuchos::Array<double>(3, 0.0));
  TRIBOS_REQUIRE(v.size() == 3, where << "/" << key << " needs three values");
  return {v[0], v[1], v[2]};
}

}  // namespace

MeshContactProblem readMeshContactProblem(const std::string& xmlFile, int level) {
  Teuchos::RCP<Teuchos::ParameterList> pl;
  try {
    pl = Teuchos::getParametersFromXmlFile(xmlFile);
  } catch (const std::exception& e) {
    throw Error("cannot read \"" + xmlFile + "\": " + e.what());
  }
  MeshContactProblem pr;
  Teuchos::ParameterList& m = pl->sublist("Mesh");
  pr.box.type = Mesh::cellTypeFromName(m.get<std::string>("Element", "Hex8"));
  pr.box.x = range2(m, "X Range");
  pr.box.y = range2(m, "Y Range");
  pr.box.z = range2(m, "Z Range");
  const int L = level > 0 ? level : m.get<int>("Level", 0);
  if (L > 0 && m.get<std::string>("Level Rule", "Prism") == "Prism") {
    pr.box.cells = Mesh::prismLevelCells(L);
  } else {
    const auto c = m.get<Teuchos::Array<int>>("Cells", Teuchos::Array<int>(Teuchos::tuple<int>(4, 4, 4)));
    TRIBOS_REQUIRE(c.size() == 3, "Mesh/Cells needs three values");
    pr.box.cells = {c[0], c[1], c[2]};
  }
  pr.mesh = Mesh::generateBox(pr.box);

  Teuchos::ParameterList& mat = pl->sublist("Material");
  pr.material.E = mat.get<double>("Young's Modulus", 2.1e11);
  pr.material.nu = mat.get<double>("Poisson's Ratio", 0.3);

  Teuchos::ParameterList& bc = pl->sublist("Boundary Conditions");
  Teuchos::ParameterList& dir = bc.sublist("Dirichlet");
  for (auto it = dir.begin(); it != dir.end(); ++it) {
    Teuchos::ParameterList& item = dir.sublist(dir.name(it));
    Fem::DirichletCondition d;
    d.face = item.get<std::string>("Face");
    const std::string comps = item.get<std::string>("Components", "xyz");
    for (int c = 0; c < 3; ++c) d.fix[c] = comps.find("xyz"[c]) != std::string::npos;
    d.value = point3(item, "Value", "Dirichlet/" + dir.name(it));
    pr.loads.dirichlet.push_back(d);
  }
  Teuchos::ParameterList& tr = bc.sublist("Traction");
  for (auto it = tr.begin(); it != tr.end(); ++it) {
    Teuchos::ParameterList& item = tr.sublist(tr.name(it));
    pr.loads.tractions.push_back({item.get<std::string>("Face"), point3(item, "Value", "Traction/" + tr.name(it))});
  }
  pr.loads.volumeForce = point3(bc, "Volume Force", "Boundary Conditions");

  Teuchos::ParameterList& contact = pl->sublist("Contact");
  TRIBOS_REQUIRE(contact.get<bool>("Enabled", false), xmlFile << ": Contact/Enabled is not true");
  // Frictionless contact is Tresca friction with a zero slip bound.
  const std::string law = contact.get<std::string>("Friction Law", "Tresca");
  TRIBOS_REQUIRE(law == "Tresca" || law == "Frictionless",
                 xmlFile << ": the semismooth* solver needs Contact/\"Friction Law\" = \"Tresca\" or \"Frictionless\"");
  pr.contactFace = contact.get<std::string>("Face", "zmin");
  pr.gap = contact.get<double>("Gap", 0.0);
  pr.slipBoundTraction = law == "Frictionless" ? 0.0 : contact.get<double>("Slip Bound Traction");
  pr.solverParams = pl->sublist("Solver").sublist("SemismoothStarNewton");
  return pr;
}

}  // namespace Semismooth
}  // namespace Tribos
