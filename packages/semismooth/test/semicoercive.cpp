// semicoercive.cpp: problems the semismooth* method must refuse, with a
// message that says why.
//  - The quarter block of symmetry_block.cpp pressed onto the plane by a
//    traction -1e7 on zmax instead of a prescribed displacement: only the
//    contact holds it in z, K_rr is singular; every "Newton Solver" refuses
//    it before any factorization, naming "translation z" (and no other
//    motion).
//  - freeRigidMotions on other Dirichlet sets of the same block: none
//    (all six motions free), u_z = 0 on zmin (translation x, y and the
//    rotation about z free), the symmetry planes with u_z on zmax (none
//    free), a clamped face (none free).
//  - The block rotated in space with a symmetry condition u_x = 0 on xmin:
//    the fixed global x is oblique to the rotated contact normal, refused
//    naming the node.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <set>

#include "Tribos_Error.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_RigidMotions.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

using namespace Tribos;

namespace {

Fem::DirichletCondition condition(const std::string& face, const std::string& comps, double value = 0.0) {
  Fem::DirichletCondition d;
  d.face = face;
  for (int c = 0; c < 3; ++c) d.fix[c] = comps.find("xyz"[c]) != std::string::npos;
  d.value = {0, 0, 0};
  for (int c = 0; c < 3; ++c)
    if (d.fix[c]) d.value[c] = value;
  return d;
}

std::set<std::string> freeMotions(const Mesh::Mesh& mesh, const std::vector<Fem::DirichletCondition>& bcs) {
  const auto names = Fem::freeRigidMotions(mesh.coords, Fem::constrainedDofs(mesh, bcs));
  return std::set<std::string>(names.begin(), names.end());
}

std::string join(const std::set<std::string>& s) {
  std::string out;
  for (const auto& n : s) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Mesh::Mesh block() {
  Mesh::BoxSpec spec;
  spec.cells = {4, 4, 4};
  spec.type = Mesh::CellType::Hex8;
  return Mesh::generateBox(spec);
}

Fem::Material material() {
  Fem::Material m;
  m.E = 1e9;
  m.nu = 0.3;
  return m;
}

// The pressed quarter block: refused by every solver, naming translation z.
void checkPressed(const std::string& solver, Teuchos::FancyOStream& out, bool& success) {
  Fem::LoadCase pressed;
  pressed.dirichlet = {condition("xmin", "x"), condition("ymin", "y")};
  pressed.tractions.push_back({"zmax", {0, 0, -1e7}});
  Teuchos::ParameterList params;
  if (solver == "Dense Schur") params.set("Dense Schur", true);
  else params.set("Newton Solver", solver);
  std::string message;
  bool otherException = false;
  try {
    Semismooth::solveFromMesh(block(), material(), pressed, "zmin", 0.0, 0.0, params, nullptr, Tpetra::getDefaultComm());
  } catch (const Error& e) {
    message = e.what();
  } catch (const std::exception& e) {
    otherException = true;
    message = e.what();
  }
  out << solver << ": " << message << "\n";
  TEST_ASSERT(!otherException);  // a Tribos::Error
  // The message names translation z and FETI ...
  TEST_ASSERT(message.find("translation z") != std::string::npos && message.find("FETI") != std::string::npos);
  // ... and no motion that is held.
  TEST_ASSERT(message.find("translation x") == std::string::npos && message.find("translation y") == std::string::npos &&
              message.find("rotation") == std::string::npos);
}

}  // namespace

TEUCHOS_UNIT_TEST(PressedBlock, SparseDirect) { checkPressed("Sparse Direct", out, success); }
TEUCHOS_UNIT_TEST(PressedBlock, ReducedCG) { checkPressed("Reduced CG", out, success); }
TEUCHOS_UNIT_TEST(PressedBlock, CGMueLu) { checkPressed("CG+MueLu", out, success); }
TEUCHOS_UNIT_TEST(PressedBlock, DenseSchur) { checkPressed("Dense Schur", out, success); }

// Which motions other Dirichlet sets leave free.
TEUCHOS_UNIT_TEST(FreeRigidMotions, NoDirichlet) {
  const std::set<std::string> all{"translation x", "translation y", "translation z",
                                  "rotation about x", "rotation about y", "rotation about z"};
  const auto none = freeMotions(block(), {});
  out << "free: " << join(none) << "\n";
  TEST_ASSERT(none == all);
}

TEUCHOS_UNIT_TEST(FreeRigidMotions, BottomZ) {
  const auto bottom = freeMotions(block(), {condition("zmin", "z")});
  out << "u_z = 0 on zmin: free " << join(bottom) << "\n";
  TEST_ASSERT(bottom == std::set<std::string>({"translation x", "translation y", "rotation about z"}));
}

TEUCHOS_UNIT_TEST(FreeRigidMotions, SymmetryPlanesAndTop) {
  const auto symmetric =
      freeMotions(block(), {condition("xmin", "x"), condition("ymin", "y"), condition("zmax", "z", -0.01)});
  out << "symmetry planes and u_z on zmax: free " << join(symmetric) << "\n";
  TEST_ASSERT(symmetric.empty());
}

TEUCHOS_UNIT_TEST(FreeRigidMotions, Clamped) {
  const auto clamped = freeMotions(block(), {condition("xmin", "xyz")});
  out << "clamped xmin: free " << join(clamped) << "\n";
  TEST_ASSERT(clamped.empty());
}

TEUCHOS_UNIT_TEST(FreeRigidMotions, SymmetryPlanesOnly) {
  const auto planes = freeMotions(block(), {condition("xmin", "x"), condition("ymin", "y")});
  out << "symmetry planes only: free " << join(planes) << "\n";
  TEST_ASSERT(planes == std::set<std::string>({"translation z"}));
}

// An oblique prescribed component: the block rotated about the y axis, so
// that the contact normal of zmin is no longer -e_z and the global x that
// xmin fixes is neither normal nor tangent to it.
TEUCHOS_UNIT_TEST(ObliqueComponent, RefusedNamingTheNode) {
  Mesh::Mesh rotated = block();
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (auto& X : rotated.coords) X = {c * X[0] + s * X[2], X[1], -s * X[0] + c * X[2]};
  Fem::LoadCase loads;
  loads.dirichlet = {condition("xmin", "x"), condition("ymin", "y"), condition("zmax", "xyz")};
  std::string message;
  try {
    Semismooth::buildContactProblem(rotated, material(), loads, "zmin", 0.0, 0.0);
  } catch (const Error& e) {
    message = e.what();
  }
  out << "oblique: " << message << "\n";
  TEST_ASSERT(message.find("contact node") != std::string::npos &&
              message.find("neither its normal") != std::string::npos && message.find("on x,") != std::string::npos);
}
