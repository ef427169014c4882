// Tribos_FCLIB_Export.hpp: a Tribos contact problem (an elastic body on a
// rigid plane, solved by FETI) as an FCLIB global problem, with the FETI
// solution, so that other frictional contact solvers can be run on it.
//
//   M = the assembled stiffness K of the whole body, Dirichlet dofs
//       eliminated symmetrically (their rows and columns keep only the
//       diagonal, the prescribed values move into f), dof = 3 node + c;
//   f = the assembled load with that lifting;
//   H (ndof x 3nc): for contact node k with outward face normal n and the
//       FETI tangents (t1, t2), the columns 3k, 3k+1, 3k+2 are -n, -t1, +t2
//       on the node's dofs: the local frame (N, T1, T2) = (-n, -t1, t2) is
//       right-handed with N pointing from the obstacle into the body;
//   w: w_N = gap d, w_T = 0, so u_N = d - n.v >= 0 is the FETI condition
//       n.v <= d, and u_T = (-t1.v, t2.v);
//   mu = the Coulomb coefficient F (0 for frictionless contact).
// With the FETI multipliers (lambda_N, lambda_T1, lambda_T2) (forces on the
// body -B'lambda) the FCLIB reaction is r = (lambda_N, lambda_T1, -lambda_T2):
// M v = H r + f is K u = f - B'lambda, and lambda_T = g T u/||T u|| becomes
// r_T = -g u_T/||u_T||, Coulomb's law in the FCLIB sign convention.
// Contacts are ordered by mesh node. The "velocities" v are displacements of
// the static problem.
#pragma once

#include <string>

#include "Tribos_FCLIB.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {
namespace FCLIB {

// Builds the problem and the solution (v, u = H'v + w, r) from a solved FETI
// contact problem. Collective over the FETI communicator; the result is
// complete on rank 0 only (other ranks get empty objects). 'law' is
// Frictionless or Coulomb (FCLIB has no Tresca friction: throws). A
// contact between bodies puts the master nodes' weights into H (the local
// velocity is the relative one). wholeMesh: the mesh the problem's
// discretization was cut from, read on rank 0 only (the FCLIB problem is
// global: M is assembled there).
void buildFromFeti(const Feti::FetiProblem& problem, const Mesh::Mesh& wholeMesh, const Fem::BodyMaterials& mat,
                   const Fem::LoadCase& loads, FrictionLaw law, double coefficient, const Vector& u,
                   const Vector& lambda, GlobalProblem& out, Solution& solution);

// buildFromFeti, then writeGlobal on rank 0 (compressed rows).
void exportFeti(const std::string& path, const Feti::FetiProblem& problem, const Mesh::Mesh& wholeMesh,
                const Fem::BodyMaterials& mat, const Fem::LoadCase& loads, FrictionLaw law, double coefficient,
                const Vector& u, const Vector& lambda, const Info& info);

}  // namespace FCLIB
}  // namespace Tribos
