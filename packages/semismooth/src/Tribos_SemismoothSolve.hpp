// Tribos_SemismoothSolve.hpp: the semismooth* method as a solve on the ranks
// of a run, returning the result every method returns
// (Contact::SolveResult): the displacement held on every rank (owned by rank
// 0), the contact nodes on rank 0, the KKT residuals of that result
// (Contact::resultKKT, as for FETI) and the verdict on them.
//
// The method is serial: rank 0 solves (with "CG+MueLu" every rank takes
// part in the CG solves, each holding the whole problem), then the result is
// broadcast.
#pragma once

#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "Tribos_FrictionLaw.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_Mesh.hpp"
#include "Tribos_SolveResult.hpp"

namespace Tribos {
namespace Semismooth {

// One face of the body against a rigid plane parallel to it, a distance gap
// beyond it; Tresca friction with a slip bound per unit area, or none.
struct PlaneContact {
  std::string face;
  double gap = 0.0;
  FrictionLaw law = FrictionLaw::Frictionless;  // Frictionless or Tresca (the method has no Coulomb law)
  double slipBoundTraction = 0.0;              // Tresca; 0 when frictionless
};

// The shared result and the method's own report.
struct SemismoothSolveResult : Contact::SolveResult {
  std::vector<double> residuals;  // ||S x^ - l + y^|| / ||l|| after each approximation step
  double assemblySeconds = 0, reductionSeconds = 0, newtonSeconds = 0;
  int cgIterations = 0;              // CG steps of every solve (Reduced CG, CG+MueLu)
  double preconditionerSeconds = 0;  // CG+MueLu: every MueLu setup
};

// Solves on every rank of comm (collective; every rank holds mesh). params:
// the "SemismoothStarNewton" list; resultCheckFactor: the verdict's factor
// on the requested "Tolerance". Throws CollectiveError, before rank 0
// starts, for a body the Dirichlet conditions do not hold (the method
// eliminates them and factors K_rr) and for Dirichlet values the contact
// face cannot take. log (rank 0): one line per Newton step.
SemismoothSolveResult solvePlaneContact(const Mesh::Mesh& mesh, const Fem::Material& material,
                                        const Fem::LoadCase& loads, const PlaneContact& contact,
                                        const Teuchos::ParameterList& params, double resultCheckFactor,
                                        const RCP<const Comm>& comm, std::ostream* log = nullptr);

}  // namespace Semismooth
}  // namespace Tribos
