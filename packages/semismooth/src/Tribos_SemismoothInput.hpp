// Tribos_SemismoothInput.hpp: reads a Tribos XML file (schema of the driver:
// Mesh, Material, Boundary Conditions, Contact, Solver) into what
// solveFromMesh() takes. Used by the prism benchmark and the tests until the
// driver calls solveFromMesh() itself.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <string>

#include "Tribos_Loads.hpp"
#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Semismooth {

struct MeshContactProblem {
  Mesh::BoxSpec box;
  Mesh::Mesh mesh;
  Fem::Material material;
  Fem::LoadCase loads;
  std::string contactFace = "zmin";
  double gap = 0.0, slipBoundTraction = 0.0;
  Teuchos::ParameterList solverParams;  // Solver/SemismoothStarNewton
};

// level > 0 replaces Mesh/Level (with Mesh/"Level Rule" = "Prism" the cells
// are Mesh::prismLevelCells(level); otherwise Mesh/Cells is used).
MeshContactProblem readMeshContactProblem(const std::string& xmlFile, int level = 0);

}  // namespace Semismooth
}  // namespace Tribos
